#version 330
// Ground rings: the fade into the horizon and the sun's light are per vertex, so a pixel only mixes
// two colours and reads one noise texel, the nearest (a software GL shades every pixel on the CPU). Past
// u_fade_end, on the last ring out toward the horizon, v_fade goes on past 1 (hazier than u_horizon).
uniform mat4 u_mvp;
uniform float u_fade_start;
uniform float u_fade_end;
uniform float u_haze_end = 1.0;  // the ground's last ring: from u_fade_end to here the haze grows on
uniform float u_haze_more = 0.0;  // by this much more (the colour mixed past u_horizon's, away from the grass)
in vec3 in_pos;
out vec2 v_noise;
out float v_fade;
void main() {
    v_noise = in_pos.xz * (40.0 / u_fade_start) / 64.0;
    float r = length(in_pos.xz);
    v_fade = smoothstep(u_fade_start, u_fade_end, r) + u_haze_more * clamp((r - u_fade_end) / (u_haze_end - u_fade_end), 0.0, 1.0);
    gl_Position = u_mvp * vec4(in_pos, 1.0);
    // the last ring reaches past the far plane: kept in front of it (its depth matters to nothing)
    if (gl_Position.w > 0.0) gl_Position.z = min(gl_Position.z, gl_Position.w * 0.99999);
}
