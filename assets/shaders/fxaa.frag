#version 330
// Edge smoothing for a software GL (after FXAA: find the local luminance edge and blend along it), made
// of exact texel reads only: on Mesa llvmpipe a filtered texture tap costs several plain texel fetches,
// and Lottes' FXAA takes nine filtered taps a pixel. Flat pixels (most of the frame) read their four
// neighbours and are kept; at an edge the 3x3 neighbourhood gives the edge's direction (across the
// luminance gradient) and the pixel is blended with the neighbours that lie along it, so stair steps
// soften and a thin twig broken into dots is joined along its own line.
uniform sampler2D u_tex;
uniform float u_strength = 1.0;
out vec4 f_color;
float luma(vec3 c) { return dot(c, vec3(0.299, 0.587, 0.114)); }
vec3 at(ivec2 p) { return texelFetch(u_tex, p, 0).rgb; }
void main() {
    ivec2 c = ivec2(gl_FragCoord.xy);
    vec3 m = at(c), n = at(c + ivec2(0, 1)), s = at(c + ivec2(0, -1)), e = at(c + ivec2(1, 0)), w = at(c + ivec2(-1, 0));
    float lm = luma(m), ln = luma(n), ls = luma(s), le = luma(e), lw = luma(w);
    float lo = min(lm, min(min(ln, ls), min(le, lw)));
    float hi = max(lm, max(max(ln, ls), max(le, lw)));
    float contrast = hi - lo;
    if (contrast < max(0.05, hi * 0.15)) { f_color = vec4(m, 1.0); return; }
    vec3 ne = at(c + ivec2(1, 1)), nw = at(c + ivec2(-1, 1)), se = at(c + ivec2(1, -1)), sw = at(c + ivec2(-1, -1));
    float lne = luma(ne), lnw = luma(nw), lse = luma(se), lsw = luma(sw);
    vec2 grad = vec2((lne + 2.0 * le + lse) - (lnw + 2.0 * lw + lsw), (lnw + 2.0 * ln + lne) - (lsw + 2.0 * ls + lse));
    if (dot(grad, grad) < 1e-6) { f_color = vec4(m, 1.0); return; }
    vec2 t = normalize(vec2(-grad.y, grad.x));  // along the edge
    const float D = 0.70710678;
    float wn = pow(abs(t.y), 4.0), we = pow(abs(t.x), 4.0);
    float wne = pow(abs(dot(t, vec2(D, D))), 4.0), wnw = pow(abs(dot(t, vec2(-D, D))), 4.0);
    vec3 sum = m + wn * (n + s) + we * (e + w) + wne * (ne + sw) + wnw * (nw + se);
    vec3 blend = sum / (1.0 + 2.0 * (wn + we + wne + wnw));
    float k = u_strength * clamp(contrast * 4.0, 0.0, 1.0);
    f_color = vec4(mix(m, blend, k), 1.0);
}
