#version 330
uniform mat4 u_mvp;
uniform mat4 u_light_mvp;
in vec3 in_pos;
in vec3 in_normal;
in vec2 in_uv;
out vec3 v_pos;
out vec3 v_normal;
out vec3 v_tangent;  // none here: a mesh's bark has no normal map
out vec2 v_uv;
out vec4 v_light;
out float v_extra;
void main() {
    v_pos = in_pos;
    v_normal = in_normal;
    v_uv = in_uv;
    v_tangent = vec3(0.0);
    v_extra = -1.0;  // (no radius: the bark's age tint is left out)
    v_light = u_light_mvp * vec4(in_pos, 1.0);
    gl_Position = u_mvp * vec4(in_pos, 1.0);
}
