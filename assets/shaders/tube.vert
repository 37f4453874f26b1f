#version 330
// Instanced generalized cylinders: one instance per segment, its start and end ring from the record
// (engine/geometry/instances.py), ring vertices from a small template (cos, sin, which ring, u).
// Cap vertices (in_cap = 1) form a cone at tips and collapse to a point elsewhere.
uniform mat4 u_mvp;
uniform mat4 u_light_mvp;
uniform vec3 u_offset;
uniform vec3 u_eye;
uniform float u_pixel;  // size of a pixel at unit distance (0 in the shadow pass)
uniform float u_thinnest = 0.0;  // segments thinner than this are left out (as the level's grown ones are)
uniform float u_min_radius = 0.55;  // pixels: the thinnest twig's radius (its polygon at least a pixel wide)
in vec4 in_ring;
in float in_cap;
in vec3 i_c0;
in vec3 i_t0;
in vec3 i_x0;
in vec3 i_c1;
in vec3 i_t1;
in vec3 i_x1;
in vec2 i_r;
in vec2 i_v;
in vec2 i_flex;
in float i_tip;
out vec3 v_pos;
out vec3 v_normal;
out vec3 v_tangent;  // along the branch (the bark's normal map: y along, x around)
out vec2 v_uv;
out vec4 v_light;
out float v_extra;
void main() {
    if (max(i_r.x, i_r.y) < u_thinnest) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // outside the clip volume: not drawn
        v_pos = vec3(0.0); v_normal = vec3(0.0, 1.0, 0.0); v_tangent = vec3(1.0, 0.0, 0.0); v_uv = vec2(0.0); v_light = vec4(0.0); v_extra = 0.0;
        return;
    }
    float s = min(in_ring.z, 1.0);
    vec3 t = normalize(mix(i_t0, i_t1, s));
    vec3 x = mix(i_x0, i_x1, s);
    x = normalize(x - dot(x, t) * t + 1e-9);
    vec3 y = cross(t, x);
    vec3 n = in_ring.x * x + in_ring.y * y;
    vec3 c = mix(i_c0, i_c1, s);
    // a twig thinner than a pixel is drawn a pixel wide however it turns (a ring of few sides is narrower
    // across its flats than its radius says): no dotted lines where it would fall between pixel centres
    // (multisampling is too slow on a software GL)
    float r = max(mix(i_r.x, i_r.y, s), u_min_radius * u_pixel * distance(c + u_offset, u_eye));
    vec3 p = c + r * n;
    float v = mix(i_v.x, i_v.y, s);
    if (in_cap > 0.5) {
        vec3 d = normalize(i_c1 - i_c0 + 1e-6 * i_t1);
        if (i_tip < 0.5) {
            p = i_c1;  // no cone inside a branch: the cap triangles collapse to nothing
        } else if (in_ring.z > 1.5) {
            p = i_c1 + d * (2.0 * i_r.y);
            n = d;
            v += 0.5;
        }
    }
    p += sway(p + u_offset, mix(i_flex.x, i_flex.y, s)) + u_offset;
    v_pos = p;
    v_normal = n;
    v_tangent = t;
    v_uv = vec2(in_ring.w, v);
    v_light = u_light_mvp * vec4(p, 1.0);
    v_extra = mix(i_r.x, i_r.y, s);  // the wood's radius: thicker is older, darker bark
    gl_Position = u_mvp * vec4(p, 1.0);
}
