#version 330
// The pygame-drawn HUD and menu, composited over the 3D view (premultiplied by its alpha).
uniform sampler2D u_tex;
in vec2 v_uv;
out vec4 f_color;
void main() {
    f_color = texture(u_tex, v_uv);
}
