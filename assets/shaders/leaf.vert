#version 330
// Instanced leaves, blossoms and fruit: one quad per record (base, axis, normal, length, width, flex,
// hash). Each leaf card (a spray of leaves in one texture) gets its own size and tilt by its hash. Leaves flutter in the wind on top of their twig's sway; at coarse levels of detail a share of
// them (by hash) is dropped and the rest grow by u_grow to cover for them; in autumn a share (by another
// hash) has fallen (u_keep). Fruit and lit blossoms (u_ball = 1) are a quad turned to the eye round the
// record's base (a fruit's width slot holds its ripeness; a blossom is a cluster of flowers u_grow times
// its size, moved u_forward of its width toward the eye, out of the leaves). Blossoms and fruit are never
// drawn smaller than u_min_pixels across (the size of a pixel at unit distance is u_pixel; 0 in the shadow
// pass).
uniform mat4 u_mvp;
uniform mat4 u_light_mvp;
uniform vec3 u_offset;
uniform vec3 u_eye;
uniform float u_fraction;
uniform float u_grow = 1.0;
uniform float u_keep = 1.0;
uniform int u_ball = 0;
uniform float u_pixel = 0.0;
uniform float u_min_pixels = 0.0;
uniform float u_forward = 0.0;  // a ball: moved toward the eye by this share of its width
in vec2 in_corner;
in vec3 i_base;
in vec3 i_axis;
in vec3 i_normal;
in vec3 i_size;
in float i_hash;
out vec3 v_pos;
out vec3 v_normal;
out vec3 v_tangent;
out vec2 v_uv;
out vec4 v_light;
out float v_extra;  // leaves: their hash (which autumn colour, and when); fruit: ripeness
void main() {
    if (i_hash > u_fraction || i_size.x <= 0.0 || fract(i_hash * 7.31) >= u_keep) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // outside the clip volume: not drawn
        v_pos = vec3(0.0); v_normal = vec3(0.0, 1.0, 0.0); v_tangent = vec3(1.0, 0.0, 0.0); v_uv = vec2(0.0); v_light = vec4(0.0); v_extra = 0.0;
        return;
    }
    vec3 p;
    if (u_ball == 1) {
        vec3 centre = i_base + sway(i_base + u_offset, i_size.z) + u_offset;
        vec3 to_eye = normalize(u_eye - centre);
        vec3 right = normalize(cross(vec3(0.0, 1.0, 0.0), to_eye));
        vec3 up = cross(to_eye, right);
        float across = max(i_size.x * u_grow, u_min_pixels * u_pixel * distance(centre, u_eye));
        centre += to_eye * across * u_forward;
        p = centre + (right * (in_corner.x - 0.5) + up * (in_corner.y - 0.5)) * across;
        v_normal = to_eye;
        v_tangent = up;
        v_extra = i_size.y;
    } else {
        float grow = u_grow * (0.85 + 0.3 * fract(i_hash * 11.13));  // each card its own size
        float seen = u_min_pixels * u_pixel * distance(i_base + u_offset, u_eye);
        grow = max(grow, seen / max(i_size.x, 1e-6));
        float tilt = (fract(i_hash * 5.71) - 0.5) * 0.9;  // and its own tilt about its axis
        vec3 side0 = cross(i_normal, i_axis);
        vec3 side = side0 * cos(tilt) + i_normal * sin(tilt);
        vec3 normal = i_normal * cos(tilt) - side0 * sin(tilt);
        p = i_base + i_axis * (i_size.x * grow * in_corner.y) + side * (i_size.y * grow * (in_corner.x - 0.5));
        float flutter = sin(u_wind.w * 7.0 + i_hash * 40.0) * length(u_wind.xyz) * 0.06 * in_corner.y;
        p += sway(i_base + u_offset, i_size.z) + normal * flutter * i_size.x + u_offset;
        v_normal = normal;
        v_tangent = i_axis;
        v_extra = i_hash;
    }
    v_pos = p;
    v_uv = in_corner;
    v_light = u_light_mvp * vec4(p, 1.0);
    gl_Position = u_mvp * vec4(p, 1.0);
}
