#version 330
// Grass without shadows (shade.frag multiplies them in where they can fall), fading into the far ground's
// haze (u_horizon: near, by v_fade) and, with the distance from the eye, on into the hazier ground at the
// horizon (u_far): aerial haze grows with distance, so the far ground is a gradient up to the horizon, not
// a flat band (per pixel: a ring's vertices are too far apart for it).
uniform sampler2D u_noise;
uniform vec3 u_grass;
uniform vec3 u_horizon;
uniform vec3 u_far;
uniform vec2 u_eye;  // the eye over the ground (x, z)
uniform float u_fade_start;
uniform float u_fade_end;
in vec2 v_noise;
in float v_fade;
out vec4 f_color;
void main() {
    float speckle = texture(u_noise, v_noise).r;
    // (the ground point, from the noise coordinate: ground_plain.vert's v_noise is in_pos.xz * 40 / 64 / u_fade_start)
    float away = length(v_noise * (1.6 * u_fade_start) - u_eye);
    float far = clamp(1.0 - u_fade_end / max(away, 1e-3), 0.0, 1.0);
    vec3 near = mix(u_grass * (0.95 + 0.05 * speckle), u_horizon, v_fade);
    f_color = vec4(mix(near, u_far, far * sqrt(far)), 1.0);
}
