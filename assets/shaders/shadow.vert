#version 330
uniform mat4 u_light_mvp;
in vec3 in_pos;
in vec2 in_uv;
out vec2 v_uv;
void main() {
    v_uv = in_uv;
    gl_Position = u_light_mvp * vec4(in_pos, 1.0);
}
