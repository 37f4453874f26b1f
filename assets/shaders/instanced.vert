#version 330
// One tree mesh drawn many times: each instance has a position, a yaw and a uniform scale.
uniform mat4 u_vp;
in vec3 in_pos;
in vec3 in_normal;
in vec2 in_uv;
in vec4 in_inst;    // x, y, z, yaw
in float in_scale;
out vec3 v_normal;
out vec2 v_uv;
out vec3 v_world;
void main() {
    float c = cos(in_inst.w), s = sin(in_inst.w);
    mat3 rot = mat3(c, 0.0, -s, 0.0, 1.0, 0.0, s, 0.0, c);
    vec3 world = rot * (in_pos * in_scale) + in_inst.xyz;
    v_normal = rot * in_normal;
    v_uv = in_uv;
    v_world = world;
    gl_Position = u_vp * vec4(world, 1.0);
}
