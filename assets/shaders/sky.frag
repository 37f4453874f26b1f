#version 330
// Sky gradient by view direction, with the sun drawn as a glowing disc.
uniform mat4 u_inv_vp;
uniform vec3 u_sun_dir;
uniform vec3 u_zenith;
uniform vec3 u_horizon;
in vec2 v_ndc;
out vec4 f_color;
void main() {
    vec4 far = u_inv_vp * vec4(v_ndc, 1.0, 1.0);
    vec4 near = u_inv_vp * vec4(v_ndc, -1.0, 1.0);
    vec3 dir = normalize(far.xyz / far.w - near.xyz / near.w);
    float t = clamp(dir.y, 0.0, 1.0);
    vec3 color = mix(u_horizon, u_zenith, pow(t, 0.6));
    float s = dot(dir, u_sun_dir);
    color += vec3(1.0, 0.9, 0.6) * (smoothstep(0.9990, 0.9995, s) * 1.5 + pow(max(s, 0.0), 64.0) * 0.35);
    f_color = vec4(color, 1.0);
}
