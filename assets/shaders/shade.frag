#version 330
// The trees' shadow on the ground, only where it can fall: multiplies what the ground pass drew by
// (ambient + sun x visibility) / (ambient + sun). One bilinear-filtered comparison tap.
uniform sampler2DShadow u_shadow;
uniform vec3 u_sun_dir;
in vec3 v_pos;
in vec4 v_light;
out vec4 f_color;
void main() {
    vec3 p = v_light.xyz / v_light.w * 0.5 + 0.5;
    float vis = (p.x < 0.0 || p.x > 1.0 || p.y < 0.0 || p.y > 1.0) ? 1.0 : texture(u_shadow, vec3(p.xy, p.z - 0.002));
    float sun = 0.55 * max(u_sun_dir.y, 0.0);
    f_color = vec4(vec3((0.45 + sun * vis) / (0.45 + sun)), 1.0);
}
