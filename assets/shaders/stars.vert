#version 330
// Stars: points on the far plane in fixed directions of the sky, brighter as the night deepens, faded
// near the horizon (where the air is thick).
uniform mat4 u_vp;
uniform vec3 u_eye;
uniform float u_radius;
uniform float u_night;
in vec3 in_dir;
in float in_bright;
out float v_bright;
void main() {
    v_bright = in_bright * u_night * smoothstep(0.0, 0.15, in_dir.y);
    gl_PointSize = 1.5 + 2.0 * in_bright;
    vec4 p = u_vp * vec4(u_eye + in_dir * u_radius, 1.0);
    gl_Position = p.xyww;
}
