#version 330
// Lit bark (kind 0), leaves (1) and blossoms (2): sun with a soft shadow map, a sky/ground hemisphere
// ambient, and an ambient-occlusion term that darkens the inside of the crown.
uniform sampler2D u_tex;
uniform sampler2DShadow u_shadow;
uniform vec3 u_sun_dir;
uniform vec3 u_sun_color;
uniform vec3 u_sky_color;
uniform vec3 u_ground_color;
uniform vec3 u_tint;
uniform int u_kind;
uniform vec2 u_uv_scale;
uniform vec3 u_crown_center;
uniform float u_crown_radius;
uniform float u_shadow_texel;
uniform float u_shadowed = 1.0;  // 0: skip the shadow lookup (far leaves; the crown's AO shades them)
in vec3 v_pos;
in vec3 v_normal;
in vec2 v_uv;
in vec4 v_light;
out vec4 f_color;

float sun_visibility() {
    vec3 p = v_light.xyz / v_light.w * 0.5 + 0.5;
    if (p.x < 0.0 || p.x > 1.0 || p.y < 0.0 || p.y > 1.0) return 1.0;
    // one comparison tap, bilinear-filtered by the sampler: soft enough at 1024 texels, and cheap on a
    // software GL (every tap is shaded on the CPU)
    return texture(u_shadow, vec3(p.xy, p.z - 0.003));
}

void main() {
    vec4 tex = texture(u_tex, v_uv * u_uv_scale);
    if (u_kind != 0 && tex.a < 0.5) discard;
    vec3 n = normalize(v_normal);
    if (u_kind != 0 && !gl_FrontFacing) n = -n;
    float ndl = dot(n, u_sun_dir);
    float diffuse = u_kind == 0 ? max(ndl, 0.0) : (max(ndl, 0.0) * 0.8 + max(-ndl, 0.0) * 0.45);
    vec3 hemi = mix(u_ground_color, u_sky_color, 0.5 + 0.5 * n.y);
    if (u_kind == 2) hemi = mix(hemi, vec3(dot(hemi, vec3(0.333))), 0.7);  // blossoms keep their pink
    float depth = length(v_pos - u_crown_center) / max(u_crown_radius, 1e-4);
    float ao = u_kind == 0 ? 1.0 : mix(0.5, 1.0, smoothstep(0.2, 1.0, depth));
    vec3 albedo = tex.rgb * u_tint;
    vec3 color = albedo * (hemi * ao * (u_kind == 0 ? 1.1 : 0.95) + u_sun_color * diffuse * (u_shadowed > 0.5 ? sun_visibility() : 0.8));
    f_color = vec4(color * (1.3 - 0.3 * min(color, vec3(1.0))), 1.0);  // lifts the darks like a gamma of 1.15, no pow
}
