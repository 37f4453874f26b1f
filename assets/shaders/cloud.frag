#version 330
// Lit from above: white tops, grey-blue bellies; dim at night (u_light).
uniform sampler2D u_tex;
uniform vec3 u_light;
uniform vec3 u_shade;
uniform float u_alpha = 0.92;  // thinner at night (moonlit wisps, not dark blots)
in vec2 v_uv;
out vec4 f_color;
void main() {
    vec4 t = texture(u_tex, v_uv);
    if (t.a < 0.01) discard;
    f_color = vec4(mix(u_shade, u_light, t.r), t.a * u_alpha);
}
