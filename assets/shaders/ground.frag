#version 330
// Grass ground that receives the tree's shadow and fades into the horizon colour far away.
uniform sampler2DShadow u_shadow;
uniform float u_shadow_texel;
uniform vec3 u_sun_dir;
uniform vec3 u_grass;
uniform vec3 u_horizon;
uniform float u_fade_start;
uniform float u_fade_end;
in vec3 v_pos;
in vec4 v_light;
out vec4 f_color;
float sun_visibility() {
    vec3 p = v_light.xyz / v_light.w * 0.5 + 0.5;
    if (p.x < 0.0 || p.x > 1.0 || p.y < 0.0 || p.y > 1.0) return 1.0;
    float sum = 0.0;
    for (int x = -2; x <= 2; x++)
        for (int y = -2; y <= 2; y++)
            sum += texture(u_shadow, vec3(p.xy + vec2(x, y) * u_shadow_texel * 1.5, p.z - 0.002));
    return sum / 25.0;
}
void main() {
    float light = 0.45 + 0.55 * max(u_sun_dir.y, 0.0) * sun_visibility();
    float r = length(v_pos.xz);
    float speckle = fract(sin(dot(floor(v_pos.xz * 40.0 / u_fade_start), vec2(12.9898, 78.233))) * 43758.5453);
    vec3 color = u_grass * light * (0.95 + 0.05 * speckle);
    f_color = vec4(mix(color, u_horizon, smoothstep(u_fade_start, u_fade_end, r)), 1.0);
}
