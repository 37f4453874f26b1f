#version 330
uniform mat4 u_mvp;
uniform mat4 u_light_mvp;
in vec3 in_pos;
out vec3 v_pos;
out vec4 v_light;
void main() {
    v_pos = in_pos;
    v_light = u_light_mvp * vec4(in_pos, 1.0);
    gl_Position = u_mvp * vec4(in_pos, 1.0);
}
