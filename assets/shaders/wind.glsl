// Wind sway shared by the tree shaders (inserted after #version): a steady lean with gusts, growing
// with the square of how far along the branches a point is (trunk base 0, outermost twigs 1), so the
// trunk barely moves and twigs and leaves move most. A joint moves as one: the same position and flex
// give the same sway. u_wind.xyz = direction x strength (scene units at the tips), u_wind.w = time.
uniform vec4 u_wind;
vec3 sway(vec3 p, float flex) {
    float f = flex * flex;
    float ph = dot(p, vec3(0.21, 0.13, 0.17));
    float t = u_wind.w;
    float gust = 0.55 + 0.3 * sin(t * 1.3 + ph) + 0.15 * sin(t * 3.7 + 2.3 * ph);
    vec3 across = vec3(-u_wind.z, 0.0, u_wind.x) * (0.25 * sin(t * 2.1 + 1.7 * ph));
    return (u_wind.xyz * gust + across) * f;
}
