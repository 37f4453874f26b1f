#version 330
// Grass ground that receives the tree's shadow and fades into the horizon colour far away.
uniform sampler2DShadow u_shadow;
uniform float u_shadow_texel;
uniform vec3 u_sun_dir;
uniform vec3 u_grass;
uniform vec3 u_horizon;
uniform float u_fade_start;
uniform float u_fade_end;
uniform sampler2D u_noise;  // soft blotches (backdrop.ground_speckle), read nearest
in vec3 v_pos;
in vec4 v_light;
out vec4 f_color;
float sun_visibility() {
    vec3 p = v_light.xyz / v_light.w * 0.5 + 0.5;
    if (p.x < 0.0 || p.x > 1.0 || p.y < 0.0 || p.y > 1.0) return 1.0;
    // one comparison tap, bilinear-filtered by the sampler (a software GL shades every ground pixel)
    return texture(u_shadow, vec3(p.xy, p.z - 0.002));
}
void main() {
    float light = 0.45 + 0.55 * max(u_sun_dir.y, 0.0) * sun_visibility();
    float r = length(v_pos.xz);
    float speckle = texture(u_noise, v_pos.xz * (24.0 / u_fade_start) / 64.0).r;  // grass patches
    vec3 color = u_grass * light * (0.95 + 0.05 * speckle);
    f_color = vec4(mix(color, u_horizon, smoothstep(u_fade_start, u_fade_end, r)), 1.0);
}
