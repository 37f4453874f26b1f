#version 330
uniform vec3 u_color;
in vec2 v_corner;
out vec4 f_color;
void main() {
    float r = length(v_corner);
    float disc = 1.0 - smoothstep(0.30, 0.36, r);
    float halo = pow(max(1.0 - r, 0.0), 3.0) * 0.6;
    f_color = vec4(u_color * (disc + halo), 1.0);
}
