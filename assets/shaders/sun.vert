#version 330
// The sun's disc: a small camera-facing square on the far plane, in the sun's direction.
uniform mat4 u_vp;
uniform vec3 u_eye;
uniform vec3 u_sun_dir;
uniform vec3 u_right;
uniform vec3 u_up;
uniform float u_radius;
uniform float u_size;
in vec2 in_corner;
out vec2 v_corner;
void main() {
    v_corner = in_corner;
    vec3 centre = u_eye + u_sun_dir * u_radius;
    vec3 p = centre + (u_right * in_corner.x + u_up * in_corner.y) * u_size * u_radius;
    vec4 q = u_vp * vec4(p, 1.0);
    gl_Position = q.xyww;
}
