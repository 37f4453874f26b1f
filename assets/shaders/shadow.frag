#version 330
uniform sampler2D u_tex;
uniform int u_alpha_test;
in vec2 v_uv;
void main() {
    if (u_alpha_test == 1 && texture(u_tex, v_uv).a < 0.5) discard;
}
