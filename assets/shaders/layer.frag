#version 330
// A layer's picture of the trees laid over the frame (premultiplied by its alpha). Only where the picture
// has something: there it also writes depth, so a pass after it (FXAA) knows where the trees are.
uniform sampler2D u_tex;
in vec2 v_uv;
out vec4 f_color;
void main() {
    vec4 c = texture(u_tex, v_uv);
    if (c.a <= 0.0) discard;
    f_color = c;
}
