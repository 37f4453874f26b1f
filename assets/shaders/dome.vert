#version 330
// Sky dome around the camera: the gradient and the sun's glow are computed per vertex (a few hundred)
// instead of per pixel, and the dome sits on the far plane so it only fills what nothing else covers.
uniform mat4 u_vp;
uniform vec3 u_eye;
uniform float u_radius;
uniform vec3 u_zenith;
uniform vec3 u_horizon;
uniform vec3 u_below;  // below the horizon: the far ground (backdrop.far_ground)
uniform vec3 u_sun_dir;
uniform vec3 u_glow;
in vec3 in_dir;
out vec3 v_color;
void main() {
    float t = clamp(in_dir.y, 0.0, 1.0);
    vec3 c = in_dir.y < -0.001 ? u_below : mix(u_horizon, u_zenith, pow(t, 0.6));
    float s = max(dot(in_dir, u_sun_dir), 0.0);
    v_color = c + u_glow * (pow(s, 40.0) * 0.5 + pow(s, 5.0) * 0.1);
    vec4 p = u_vp * vec4(u_eye + in_dir * u_radius, 1.0);
    gl_Position = p.xyww;
}
