#version 330
// FXAA (after Lottes, reduced): find the local luminance edge and blend along it. Used where
// multisampling is too slow (a software GL); thin twigs also keep at least a pixel of width.
uniform sampler2D u_tex;
uniform vec2 u_texel;
in vec2 v_uv;
out vec4 f_color;
float luma(vec3 c) { return dot(c, vec3(0.299, 0.587, 0.114)); }
void main() {
    vec3 m = texture(u_tex, v_uv).rgb;
    float lm = luma(m);
    float ln = luma(textureOffset(u_tex, v_uv, ivec2(0, 1)).rgb);
    float ls = luma(textureOffset(u_tex, v_uv, ivec2(0, -1)).rgb);
    float le = luma(textureOffset(u_tex, v_uv, ivec2(1, 0)).rgb);
    float lw = luma(textureOffset(u_tex, v_uv, ivec2(-1, 0)).rgb);
    float lo = min(lm, min(min(ln, ls), min(le, lw)));
    float hi = max(lm, max(max(ln, ls), max(le, lw)));
    if (hi - lo < max(0.04, hi * 0.125)) { f_color = vec4(m, 1.0); return; }
    vec2 dir = vec2(-((ln) - (ls)), (le) - (lw));
    float scale = 1.0 / (min(abs(dir.x), abs(dir.y)) + 0.05 * (ln + ls + le + lw));
    dir = clamp(dir * scale, -4.0, 4.0) * u_texel;
    vec3 a = 0.5 * (texture(u_tex, v_uv - dir * (1.0 / 6.0)).rgb + texture(u_tex, v_uv + dir * (1.0 / 6.0)).rgb);
    vec3 b = a * 0.5 + 0.25 * (texture(u_tex, v_uv - dir * 0.5).rgb + texture(u_tex, v_uv + dir * 0.5).rgb);
    float lb = luma(b);
    f_color = vec4((lb < lo || lb > hi) ? a : b, 1.0);
}
