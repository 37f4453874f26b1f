#version 330
// Grass blades around the trees: one triangle each (two base corners and a tip), the tip swaying in the
// same wind as the trees (wind.glsl's gusts, scaled from the trees' tips to a blade's height), lit by the
// sun through the shadow map (looked up per vertex: three lookups a blade, not one a pixel).
uniform mat4 u_mvp;
uniform mat4 u_light_mvp;
uniform sampler2DShadow u_shadow;
uniform vec3 u_sun_dir;
uniform vec3 u_sun_color;
uniform vec3 u_sky_color;
uniform float u_shadowed = 1.0;  // 0: no shadow lookup (the ground's shade pass darkens them)
uniform float u_sway;  // a blade tip's sway per unit of the trees' outermost twigs' sway
in vec3 in_pos;
in float in_tip;  // 0 at the base, 1 at the tip
in vec3 in_color;
out vec3 v_color;
void main() {
    vec3 p = in_pos + sway(in_pos, 1.0) * (u_sway * in_tip);
    vec4 l = u_light_mvp * vec4(p, 1.0);
    vec3 s = l.xyz / l.w * 0.5 + 0.5;
    float sun = (u_shadowed < 0.5 || s.x < 0.0 || s.x > 1.0 || s.y < 0.0 || s.y > 1.0) ? 1.0 : texture(u_shadow, vec3(s.xy, s.z - 0.003));
    float light = max(u_sun_dir.y, 0.0) * 0.75 * sun;
    vec3 ambient = mix(vec3(0.55), u_sky_color * 1.2, 0.4) * mix(0.45, 1.0, in_tip);  // darker down in the sward
    v_color = in_color * (ambient + u_sun_color * light);
    gl_Position = u_mvp * vec4(p, 1.0);
}
