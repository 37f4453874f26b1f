#version 330
// A cloud: a camera-facing card on the far plane in its direction (like the sun's disc), textured.
uniform mat4 u_vp;
uniform vec3 u_eye;
uniform vec3 u_dir;
uniform vec3 u_right;
uniform vec3 u_up;
uniform float u_radius;
uniform vec2 u_size;
in vec2 in_corner;
out vec2 v_uv;
void main() {
    v_uv = in_corner * 0.5 + 0.5;
    vec3 centre = u_eye + u_dir * u_radius;
    vec3 p = centre + (u_right * in_corner.x * u_size.x + u_up * in_corner.y * u_size.y) * u_radius;
    vec4 q = u_vp * vec4(p, 1.0);
    gl_Position = q.xyww;
}
