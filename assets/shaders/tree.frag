#version 330
// Lit bark (kind 0), leaf cards (1), blossoms (2) and fruit (3): sun with a filtered shadow map, a sky/ground
// hemisphere ambient, and an ambient-occlusion term that darkens the inside of the crown. Bark has relief
// from a tangent-space normal map (x around the branch, y along it) and darkens and coarsens with age (its
// radius: deeper relief, darker furrows between lighter ridges);
// leaves vary in shade and hue card by card, are lighter on the crown's sunlit side and let the sun
// through when it is behind them (u_translucency; 0 = an opaque card). In autumn (u_autumn 0..1) leaves
// turn yellow, orange and red, each at its own time (by its hash); fruit is a lit ball, green while it
// ripens and red when it is ripe; a rock (4) is a grey, lumpy ball.
uniform sampler2D u_tex;
uniform sampler2DShadow u_shadow;
uniform sampler2D u_normal_map;
uniform vec3 u_sun_dir;
uniform vec3 u_sun_color;
uniform vec3 u_sky_color;
uniform vec3 u_ground_color;
uniform vec3 u_tint;
uniform vec3 u_eye;
uniform int u_kind;
uniform vec2 u_uv_scale;
uniform vec3 u_crown_center;
uniform float u_crown_radius;
uniform float u_shadow_texel;
uniform float u_shadowed = 1.0;  // 0: skip the shadow lookup (far leaves; the crown's AO shades them)
uniform float u_autumn = 0.0;
uniform float u_relief = 1.0;  // strength of the bark's normal map (0: smooth tubes)
uniform float u_translucency = 1.0;
uniform float u_soft = 1.0;  // shadow edges filtered over this many texels (0: one tap)
in vec3 v_pos;
in vec3 v_normal;
in vec3 v_tangent;
in vec2 v_uv;
in vec4 v_light;
in float v_extra;
out vec4 f_color;

float sun_visibility() {
    vec3 p = v_light.xyz / v_light.w * 0.5 + 0.5;
    if (p.x < 0.0 || p.x > 1.0 || p.y < 0.0 || p.y > 1.0) return 1.0;
    float z = p.z - 0.003;
    // bilinear-filtered comparison taps: one for leaves (cheap on a software GL, where every tap is shaded
    // on the CPU, and the crown's own clutter hides it), four on a rotated grid u_soft texels apart for the
    // wood and rocks (soft shadow edges along the branches, no steps of texels on a rock's round face close
    // up; u_soft 0: one tap everywhere)
    if (u_soft <= 0.0 || (u_kind != 0 && u_kind != 4)) return texture(u_shadow, vec3(p.xy, z));
    vec2 d = vec2(u_shadow_texel * u_soft);
    return 0.25 * (texture(u_shadow, vec3(p.xy + d * vec2(-1.5, -0.5), z)) + texture(u_shadow, vec3(p.xy + d * vec2(0.5, -1.5), z))
                   + texture(u_shadow, vec3(p.xy + d * vec2(1.5, 0.5), z)) + texture(u_shadow, vec3(p.xy + d * vec2(-0.5, 1.5), z)));
}

vec3 autumn_leaf(vec3 green) {
    float turn = clamp(u_autumn * 1.8 - fract(v_extra * 3.17) * 0.8, 0.0, 1.0);
    vec3 hue = mix(vec3(1.0, 0.78, 0.18), vec3(0.92, 0.28, 0.08), fract(v_extra * 13.7));
    return mix(green, hue * (0.35 + 1.6 * dot(green, vec3(0.3, 0.55, 0.15))), turn);
}

vec3 bark_normal(vec3 n, vec2 uv) {
    // the relief in the frame of the tube: around = t x n (the direction u grows in), along = t
    if (dot(v_tangent, v_tangent) < 0.25 || u_relief <= 0.0) return n;
    vec3 t = normalize(v_tangent - dot(v_tangent, n) * n);
    vec3 m = texture(u_normal_map, uv).xyz * 2.0 - 1.0;
    m.xy *= u_relief * (v_extra < 0.0 ? 1.0 : mix(0.6, 1.7, smoothstep(0.1, 1.5, v_extra)));  // older: deeper
    return normalize(m.x * cross(t, n) + m.y * t + m.z * n);
}

void main() {
    vec2 uv = v_uv * u_uv_scale;
    vec4 tex = texture(u_tex, uv);
    vec3 n = normalize(v_normal);
    vec3 to_eye = n;  // (fruit: the quad faces the eye)
    vec3 albedo = tex.rgb * u_tint;
    if (u_kind >= 3) {  // a ball facing the eye (fruit, rock): its normal from where in the disc the pixel lies
        vec2 d = v_uv * 2.0 - 1.0;
        float edge = 1.0;
        if (u_kind == 4) {  // a boulder: lower than it is wide, its outline bulging in big and small lumps
            d.y *= 1.35;
            float a = atan(d.y, d.x) * 0.159;  // (coarse mip levels: smooth lumps, and no jump where a wraps)
            edge = min(0.84 + 1.6 * (textureLod(u_tex, vec2(a, 0.37), 4.0).r - 0.5)
                       + 1.0 * (textureLod(u_tex, vec2(2.0 * a + 0.3, 0.71), 3.0).r - 0.5), 1.0);
        }
        float rr = dot(d, d);
        if (rr > edge * edge) discard;
        rr /= edge * edge;
        vec3 right = normalize(cross(vec3(0.0, 1.0, 0.0), n));
        n = normalize(right * d.x + cross(n, right) * d.y + n * sqrt(1.0 - rr));
        if (u_kind == 4) {  // rock: lumpy, cracked stone (its own textures: see textures.rock_height)
            n = normalize(n + 0.7 * (texture(u_normal_map, v_uv * 0.45).xyz * 2.0 - 1.0)  // (facets and cracks)
                          + 0.4 * (texture(u_normal_map, v_uv * 1.7).xyz * 2.0 - 1.0));
            albedo = vec3(0.47, 0.46, 0.44) * (0.55 + 0.8 * texture(u_tex, v_uv * 1.1).r);
        } else {
            albedo = mix(vec3(0.42, 0.62, 0.16), vec3(0.86, 0.12, 0.07), smoothstep(0.6, 1.0, v_extra));
        }
    } else if (u_kind != 0) {
        if (tex.a < 0.5) discard;
        if (dot(n, u_eye - v_pos) < 0.0) n = -n;  // the side facing the eye (a card's winding says nothing)
        // each card its own green: darker blue-greens to lighter yellow-greens
        if (u_kind == 1) albedo = autumn_leaf(albedo * mix(vec3(0.84, 0.8, 0.96), vec3(1.16, 1.2, 0.78), fract(v_extra * 5.3)));
    } else {
        n = bark_normal(n, uv);
        if (v_extra >= 0.0) albedo *= mix(vec3(1.1, 1.1, 0.92), vec3(0.66, 0.62, 0.58), smoothstep(0.03, 0.6, v_extra));
        // old bark (a radius of 1 to 15 cm: 0.1 to 1.5 scene units): its ridges lighter, its furrows darker
        // (about the bark texture's median, 0.23: its mean kept)
        albedo *= 1.0 + 0.4 * smoothstep(0.1, 1.5, v_extra) * clamp((tex.g - 0.23) * 8.0, -1.0, 1.0);
    }
    float ndl = dot(n, u_sun_dir);
    float diffuse = (u_kind == 0 || u_kind >= 3) ? max(ndl, 0.0) : max(ndl, 0.0) * 0.8;
    vec3 hemi = mix(u_ground_color, u_sky_color, 0.5 + 0.5 * n.y);
    if (u_kind >= 2) hemi = mix(hemi, vec3(dot(hemi, vec3(0.333))), 0.7);  // blossoms and fruit keep their colour
    float depth = length(v_pos - u_crown_center) / max(u_crown_radius, 1e-4);
    float ao = u_kind != 1 ? 1.0 : mix(0.5, 1.05, smoothstep(0.15, 1.0, depth));  // (blossoms sit out of the leaves)
    // leaves on the crown's sunlit side brighter, those on its far side a little darker (light through
    // the crown from outside in, on top of the AO's outside-in)
    float side = u_kind == 1 ? dot(v_pos - u_crown_center, u_sun_dir) / max(u_crown_radius, 1e-4) : 0.0;
    float sun = u_shadowed > 0.5 ? sun_visibility() : 0.8;
    vec3 color = albedo * (hemi * ao * (u_kind == 0 ? 1.1 : 0.95) + u_sun_color * diffuse * sun);
    color *= 1.0 + 0.5 * clamp(side * 1.6, 0.0, 1.0) - 0.1 * clamp(-side * 1.6, 0.0, 1.0);  // (crown: 0.6 of the bounds)
    if (u_kind == 1 || u_kind == 2) {  // light through the leaf: from behind it, most when looking into the sun
        float behind = max(-ndl, 0.0);
        float into_sun = pow(max(dot(normalize(v_pos - u_eye), u_sun_dir), 0.0), 4.0);
        vec3 through = albedo * (u_kind == 1 ? vec3(1.25, 1.45, 0.55) : vec3(0.8)) * u_sun_color * max(sun, 0.45);  // (scattered on through the crown)
        color += through * u_translucency * (0.8 * behind + 1.8 * into_sun * step(ndl, 0.0)) * mix(0.6, 1.0, ao);
    }
    if (u_kind == 3) color += u_sun_color * 0.35 * pow(max(dot(reflect(-u_sun_dir, n), to_eye), 0.0), 24.0);
    f_color = vec4(color * (1.3 - 0.3 * min(color, vec3(1.0))), 1.0);  // lifts the darks like a gamma of 1.15, no pow
}
