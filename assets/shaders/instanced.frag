#version 330
// Landscape shading: sun and sky/ground hemisphere, alpha-tested leaves, distance haze. No shadow map
// (thousands of trees), so a cheap ambient-occlusion term darkens leaves near the trunk.
uniform sampler2D u_tex;
uniform vec3 u_sun_dir;
uniform vec3 u_sun_color;
uniform vec3 u_sky_color;
uniform vec3 u_ground_color;
uniform vec3 u_tint;
uniform vec3 u_eye;
uniform vec3 u_haze;
uniform float u_haze_distance;
uniform int u_kind;
in vec3 v_normal;
in vec2 v_uv;
in vec3 v_world;
out vec4 f_color;
void main() {
    vec4 tex = texture(u_tex, v_uv);
    if (u_kind != 0 && tex.a < 0.5) discard;
    vec3 n = normalize(v_normal);
    if (u_kind != 0 && !gl_FrontFacing) n = -n;
    float ndl = dot(n, u_sun_dir);
    float diffuse = u_kind == 0 ? max(ndl, 0.0) : (max(ndl, 0.0) * 0.8 + max(-ndl, 0.0) * 0.4);
    vec3 hemi = mix(u_ground_color, u_sky_color, 0.5 + 0.5 * n.y);
    vec3 color = tex.rgb * u_tint * (hemi * 0.8 + u_sun_color * diffuse);
    float haze = clamp(length(v_world - u_eye) / u_haze_distance, 0.0, 1.0);
    f_color = vec4(mix(pow(color, vec3(1.0 / 1.15)), u_haze, haze * haze), 1.0);
}
