#version 330
// Ground rings: the fade into the horizon and the sun's light are per vertex, so a pixel only mixes
// colours and reads one noise texel, the nearest (a software GL shades every pixel on the CPU). Far off
// the haze grows on with the distance from the eye, per pixel (ground_plain.frag).
uniform mat4 u_mvp;
uniform float u_fade_start;
uniform float u_fade_end;
in vec3 in_pos;
out vec2 v_noise;
out float v_fade;
void main() {
    v_noise = in_pos.xz * (40.0 / u_fade_start) / 64.0;
    float r = length(in_pos.xz);
    v_fade = smoothstep(u_fade_start, u_fade_end, r);
    gl_Position = u_mvp * vec4(in_pos, 1.0);
    // the last ring reaches past the far plane: kept in front of it (its depth matters to nothing)
    if (gl_Position.w > 0.0) gl_Position.z = min(gl_Position.z, gl_Position.w * 0.99999);
}
