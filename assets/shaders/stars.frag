#version 330
in float v_bright;
out vec4 f_color;
void main() {
    f_color = vec4(vec3(0.9, 0.93, 1.0) * v_bright, 1.0);
}
