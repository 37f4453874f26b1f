#version 330
// Overlay tiles: quads in clip space over the parts of the HUD texture that have something in them.
in vec2 in_pos;
out vec2 v_uv;
void main() {
    v_uv = in_pos * 0.5 + 0.5;
    gl_Position = vec4(in_pos, 0.0, 1.0);
}
