#version 330
// Grass without shadows (shade.frag multiplies them in where they can fall), fading into the horizon.
uniform sampler2D u_noise;
uniform vec3 u_grass;
uniform vec3 u_horizon;
in vec2 v_noise;
in float v_fade;
out vec4 f_color;
void main() {
    float speckle = texture(u_noise, v_noise).r;
    f_color = vec4(mix(u_grass * (0.95 + 0.05 * speckle), u_horizon, v_fade), 1.0);
}
