#version 330
// Grass ground without shadows (they are multiplied in afterwards where they can fall), fading into
// the horizon colour far away.
uniform vec3 u_sun_dir;
uniform vec3 u_grass;
uniform vec3 u_horizon;
uniform float u_fade_start;
uniform float u_fade_end;
in vec3 v_pos;
in vec4 v_light;
out vec4 f_color;
void main() {
    float light = 0.45 + 0.55 * max(u_sun_dir.y, 0.0);
    float speckle = fract(sin(dot(floor(v_pos.xz * 40.0 / u_fade_start), vec2(12.9898, 78.233))) * 43758.5453);
    vec3 color = u_grass * light * (0.95 + 0.05 * speckle);
    f_color = vec4(mix(color, u_horizon, smoothstep(u_fade_start, u_fade_end, length(v_pos.xz))), 1.0);
}
