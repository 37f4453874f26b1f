#version 330
in vec3 v_color;
out vec4 f_color;
void main() {
    f_color = vec4(v_color * (1.3 - 0.3 * min(v_color, vec3(1.0))), 1.0);  // (the trees' tone curve)
}
