#version 330
// A full-screen triangle at the far plane (depth 1): with the depth test '>' it shades only the pixels
// something was drawn on (the trees; the backdrop is drawn without depth), see game/render/fxaa.py.
in vec2 in_pos;
void main() {
    gl_Position = vec4(in_pos, 1.0, 1.0);
}
