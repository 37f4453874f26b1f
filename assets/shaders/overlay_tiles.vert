#version 330
// Overlay tiles: quads in clip space over the parts of the HUD texture that have something in them
// (the texture holds the pygame surface's rows as they are: top row first).
in vec2 in_pos;
out vec2 v_uv;
void main() {
    v_uv = vec2(in_pos.x * 0.5 + 0.5, 0.5 - in_pos.y * 0.5);
    gl_Position = vec4(in_pos, 0.0, 1.0);
}
