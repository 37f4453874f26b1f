#version 330
// Instanced leaves and blossoms: one textured quad per record (base, axis, normal, length, width,
// flex, hash). Leaves flutter in the wind on top of their twig's sway; at coarse levels of detail a
// share of them (by hash) is dropped and the rest grow to cover the same area.
uniform mat4 u_mvp;
uniform mat4 u_light_mvp;
uniform vec3 u_offset;
uniform float u_fraction;
in vec2 in_corner;
in vec3 i_base;
in vec3 i_axis;
in vec3 i_normal;
in vec3 i_size;
in float i_hash;
out vec3 v_pos;
out vec3 v_normal;
out vec2 v_uv;
out vec4 v_light;
void main() {
    if (i_hash > u_fraction || i_size.x <= 0.0) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // outside the clip volume: not drawn
        v_pos = vec3(0.0); v_normal = vec3(0.0, 1.0, 0.0); v_uv = vec2(0.0); v_light = vec4(0.0);
        return;
    }
    float grow = inversesqrt(max(u_fraction, 0.05));
    vec3 side = cross(i_normal, i_axis);
    vec3 p = i_base + i_axis * (i_size.x * grow * in_corner.y) + side * (i_size.y * grow * (in_corner.x - 0.5));
    float flutter = sin(u_wind.w * 7.0 + i_hash * 40.0) * length(u_wind.xyz) * 0.06 * in_corner.y;
    p += sway(i_base + u_offset, i_size.z) + i_normal * flutter * i_size.x + u_offset;
    v_pos = p;
    v_normal = i_normal;
    v_uv = in_corner;
    v_light = u_light_mvp * vec4(p, 1.0);
    gl_Position = u_mvp * vec4(p, 1.0);
}
