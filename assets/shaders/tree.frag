#version 330
// Lit bark (kind 0), leaves (1), blossoms (2) and fruit (3): sun with a soft shadow map, a sky/ground
// hemisphere ambient, and an ambient-occlusion term that darkens the inside of the crown. In autumn
// (u_autumn 0..1) leaves turn yellow, orange and red, each at its own time (by its hash); fruit is a
// lit ball, green while it ripens and red when it is ripe; a rock (4) is a grey ball.
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
uniform float u_autumn = 0.0;
in vec3 v_pos;
in vec3 v_normal;
in vec2 v_uv;
in vec4 v_light;
in float v_extra;
out vec4 f_color;

float sun_visibility() {
    vec3 p = v_light.xyz / v_light.w * 0.5 + 0.5;
    if (p.x < 0.0 || p.x > 1.0 || p.y < 0.0 || p.y > 1.0) return 1.0;
    // one comparison tap, bilinear-filtered by the sampler: soft enough at 1024 texels, and cheap on a
    // software GL (every tap is shaded on the CPU)
    return texture(u_shadow, vec3(p.xy, p.z - 0.003));
}

vec3 autumn_leaf(vec3 green) {
    float turn = clamp(u_autumn * 1.8 - fract(v_extra * 3.17) * 0.8, 0.0, 1.0);
    vec3 hue = mix(vec3(1.0, 0.78, 0.18), vec3(0.92, 0.28, 0.08), fract(v_extra * 13.7));
    return mix(green, hue * (0.35 + 1.6 * dot(green, vec3(0.3, 0.55, 0.15))), turn);
}

void main() {
    vec4 tex = texture(u_tex, v_uv * u_uv_scale);
    vec3 n = normalize(v_normal);
    vec3 to_eye = n;  // (fruit: the quad faces the eye)
    vec3 albedo = tex.rgb * u_tint;
    if (u_kind >= 3) {  // a ball facing the eye (fruit, rock): its normal from where in the disc the pixel lies
        vec2 d = v_uv * 2.0 - 1.0;
        float rr = dot(d, d);
        if (rr > 1.0) discard;
        vec3 right = normalize(cross(vec3(0.0, 1.0, 0.0), n));
        n = normalize(right * d.x + cross(n, right) * d.y + n * sqrt(1.0 - rr));
        albedo = u_kind == 3 ? mix(vec3(0.42, 0.62, 0.16), vec3(0.86, 0.12, 0.07), smoothstep(0.6, 1.0, v_extra))
                             : vec3(0.55, 0.53, 0.5) * (0.8 + 0.4 * texture(u_tex, v_uv * 2.0).r);  // rock: bark-grained stone
    } else if (u_kind != 0) {
        if (tex.a < 0.5) discard;
        if (!gl_FrontFacing) n = -n;
        if (u_kind == 1) albedo = autumn_leaf(albedo);
    }
    float ndl = dot(n, u_sun_dir);
    float diffuse = (u_kind == 0 || u_kind >= 3) ? max(ndl, 0.0) : (max(ndl, 0.0) * 0.8 + max(-ndl, 0.0) * 0.45);
    vec3 hemi = mix(u_ground_color, u_sky_color, 0.5 + 0.5 * n.y);
    if (u_kind >= 2) hemi = mix(hemi, vec3(dot(hemi, vec3(0.333))), 0.7);  // blossoms and fruit keep their colour
    float depth = length(v_pos - u_crown_center) / max(u_crown_radius, 1e-4);
    float ao = (u_kind == 0 || u_kind >= 3) ? 1.0 : mix(0.5, 1.0, smoothstep(0.2, 1.0, depth));
    vec3 color = albedo * (hemi * ao * (u_kind == 0 ? 1.1 : 0.95) + u_sun_color * diffuse * (u_shadowed > 0.5 ? sun_visibility() : 0.8));
    if (u_kind == 3) color += u_sun_color * 0.35 * pow(max(dot(reflect(-u_sun_dir, n), to_eye), 0.0), 24.0);
    f_color = vec4(color * (1.3 - 0.3 * min(color, vec3(1.0))), 1.0);  // lifts the darks like a gamma of 1.15, no pow
}
