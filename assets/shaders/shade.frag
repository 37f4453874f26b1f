#version 330
// The trees' shadow on the ground, only where it can fall: multiplies what the ground pass drew by
// (ambient + sun x visibility) / (ambient + sun). Soft edges: four bilinear-filtered comparison taps on a
// rotated grid u_soft texels apart (a 4x4-texel percentage-closer filter); u_soft 0 is one tap.
uniform sampler2DShadow u_shadow;
uniform vec3 u_sun_dir;
uniform float u_shadow_texel;
uniform float u_soft = 1.0;
in vec3 v_pos;
in vec4 v_light;
out vec4 f_color;
void main() {
    vec3 p = v_light.xyz / v_light.w * 0.5 + 0.5;
    float vis = 1.0;
    if (p.x >= 0.0 && p.x <= 1.0 && p.y >= 0.0 && p.y <= 1.0) {
        float z = p.z - 0.002;
        if (u_soft > 0.0) {
            vec2 d = vec2(u_shadow_texel * u_soft);
            vis = 0.25 * (texture(u_shadow, vec3(p.xy + d * vec2(-1.5, -0.5), z))
                          + texture(u_shadow, vec3(p.xy + d * vec2(0.5, -1.5), z))
                          + texture(u_shadow, vec3(p.xy + d * vec2(1.5, 0.5), z))
                          + texture(u_shadow, vec3(p.xy + d * vec2(-0.5, 1.5), z)));
        } else {
            vis = texture(u_shadow, vec3(p.xy, z));
        }
    }
    float sun = 0.55 * max(u_sun_dir.y, 0.0);
    f_color = vec4(vec3((0.45 + sun * vis) / (0.45 + sun)), 1.0);
}
