"""What surrounds the trees: a sky dome with the sun's disc, and the ground that receives their shadow.

Cheap on purpose (a software GL like llvmpipe shades every pixel on the CPU): the sky gradient is per
vertex of a dome on the far plane, so it only fills pixels nothing else covers; the sun (and at night
the moon) is a small additive square, the stars some fifteen hundred points; the ground shadow uses four filtered taps.
"""

from __future__ import annotations

import math
import re
import weakref

import moderngl
import numpy as np

from arbor.game.paths import ASSETS

SKY_ZENITH = (0.30, 0.52, 0.86)
SKY_HORIZON = (0.78, 0.87, 0.95)
NIGHT_ZENITH = (0.05, 0.08, 0.22)  # nights are dark blue, never black, lighter toward the horizon
NIGHT_HORIZON = (0.27, 0.31, 0.50)
MOON = (0.80, 0.84, 0.92)
MOONLIGHT = (0.30, 0.34, 0.46)  # the full moon's light on the trees at night (cool, about a third of the sun's)
MOONLIT = (0.03, 0.05, 0.09)  # what the moon adds to the ground at night
STARS = 1500  # points over the sky (a few thousand vertices: nothing for any GL)
CLOUDS = 11  # cards in the sky, drifting with the wind
CLOUD_DRIFT = 0.002  # radians of azimuth a second
CLOUD_STEP = 0.004  # drift between redraws of the sky's picture on a software GL (about 3 px at 720 px)
GRASS = (0.33, 0.50, 0.22)
FAR_HAZE = 0.25  # where the ground's fade ends it takes this share of the horizon's colour (aerial haze)
HORIZON_HAZE = 2.0  # and toward the horizon, with the distance from the eye, on to this many FAR_HAZEs (per
# pixel: the far ground a gradient up to the horizon; a haze by ring was a flat grey-green band under a low
# camera), no more: faded all the way into the sky's pale horizon it was a grey fog band under the sky line
HORIZON_REACH = 25.0  # the ground's last ring reaches this many times the disc's radius (near the horizon)
SOIL = (0.36, 0.26, 0.17)  # the cut-away view: the ground as soil
# The ground disc's mesh: few, large triangles (a software GL pays per triangle, also for the ones
# clipped behind the camera: 64 x 24 cost 3-5 ms more per frame than 24 x 10 on llvmpipe)
GROUND_SECTORS, GROUND_RINGS = 24, 10


def program(ctx: moderngl.Context, vertex: str, fragment: str, include: tuple[str, ...] = (),
            constants: dict[str, int | float] | None = None) -> moderngl.Program:
    """A shader program from assets/shaders, with shared snippets (e.g. wind.glsl) after #version.

    ``constants`` fixes uniforms for this program: each one's declaration (``uniform int u_kind;``) in
    either shader becomes a constant of that value, so the compiler drops the paths it rules out (on a
    software GL a fragment shader that may ``discard`` is shaded before its depth test: a wood-only
    program without the leaves' alpha test is drawn with an early depth test, half the cost)."""
    shaders = ASSETS / "shaders"

    def source(name: str) -> str:
        text = (shaders / name).read_text()
        if not include or not text.startswith("#version"):
            return text
        head, _, rest = text.partition("\n")
        return "\n".join([head, *((shaders / inc).read_text() for inc in include), rest])

    sources = [source(vertex), source(fragment)]
    for name, value in (constants or {}).items():
        found = False
        for k, text in enumerate(sources):
            sources[k], n = re.subn(rf"\buniform\s+(int|float)\s+{name}\s*(=[^;]*)?;",
                                    lambda m, n=name, v=value: f"const {m.group(1)} {n} = {_literal(m.group(1), v)};",
                                    text)
            found = found or n > 0
        if not found:
            raise ValueError(f"no uniform {name} in {vertex} or {fragment} to make a constant")
    return ctx.program(vertex_shader=sources[0], fragment_shader=sources[1])


def _literal(kind: str, value: float) -> str:
    """``value`` written as a GLSL literal of ``kind`` ('int' or 'float')."""
    return str(int(value)) if kind == "int" else repr(float(value))


_NAMES: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()  # each program's member names


def set_uniforms(prog: moderngl.Program, values: dict) -> None:
    """Set the uniforms ``prog`` has (a GLSL compiler drops the ones a shader does not use). (Its names are
    kept as a set: ``key in prog`` walks all its members; a turning frame of a year-10 tree sets 295 keys, 0.9
    ms of CPU that way, 0.5 ms with the set.)"""
    names = _NAMES.get(prog)
    if names is None:
        names = _NAMES[prog] = frozenset(prog)
    for key, value in values.items():
        if key in names:
            if isinstance(value, bytes):
                prog[key].write(value)
            else:
                prog[key].value = value


def convex_hull(points: np.ndarray) -> np.ndarray:
    """Convex hull of 2D points, counter-clockwise (Andrew's monotone chain; a few dozen points)."""
    pts = np.unique(np.round(points, 6), axis=0)
    if len(pts) < 3:
        return pts

    def half(seq) -> list:
        out: list = []
        for x, y in seq:
            while len(out) >= 2 and ((out[-1][0] - out[-2][0]) * (y - out[-2][1])
                                     - (out[-1][1] - out[-2][1]) * (x - out[-2][0])) <= 0:
                out.pop()
            out.append((x, y))
        return out

    rows = pts.tolist()
    lower, upper = half(rows), half(rows[::-1])
    return np.array(lower[:-1] + upper[:-1])


def sky_colors(sun: np.ndarray) -> tuple[tuple, tuple, float]:
    """Zenith and horizon colours and the daylight factor (0 night .. 1 day) for a sun direction."""
    day = float(np.clip((sun[1] + 0.15) / 0.35, 0.0, 1.0))
    zenith = tuple(n + (d - n) * day for n, d in zip(NIGHT_ZENITH, SKY_ZENITH, strict=True))
    horizon = tuple(n + (d - n) * day for n, d in zip(NIGHT_HORIZON, SKY_HORIZON, strict=True))
    return zenith, horizon, day


def lamp(sun: np.ndarray) -> tuple[np.ndarray, tuple[float, float, float]]:
    """What the trees are lit by, direction and colour: the sun while it is up (warmer and dimmer as it sinks,
    nothing at the horizon), the moon (drawn opposite the sun) while it is down, MOONLIGHT as strong as the
    night is dark and the moon high (nothing at the horizon either: no jump as one gives way to the other)."""
    sun = np.asarray(sun, float)
    if sun[1] >= 0.0:
        elevation = float(sun[1])
        strength = min(elevation * 4.0, 1.0)
        return sun, (1.05 * (0.4 + 0.6 * elevation) * strength, 0.98 * (0.4 + 0.6 * elevation) * strength,
                     0.85 * strength)
    moon = -sun
    _, _, day = sky_colors(sun)
    strength = min(float(moon[1]) * 4.0, 1.0) * (1.0 - day)
    return moon, tuple(c * strength for c in MOONLIGHT)


def ground_color(sun: np.ndarray, ground: tuple[float, float, float]) -> tuple[float, float, float]:
    """The colour of the sunlit ground (``ground``: grass or soil) under ``sun``, moonlit at night."""
    _, _, day = sky_colors(sun)
    light = (0.45 + 0.55 * max(float(sun[1]), 0.0)) * (0.7 + 0.3 * day)
    return tuple(c * light + m * (1.0 - day) for c, m in zip(ground, MOONLIT, strict=True))


def far_ground(sun: np.ndarray, ground: tuple[float, float, float], haze: float = FAR_HAZE
               ) -> tuple[float, float, float]:
    """The colour the ground fades into far away: the ground's own (``ground`` under ``sun``, see
    :func:`ground_color`) ``haze`` of the way to the horizon's (the dome below the horizon: HORIZON_HAZE
    FAR_HAZEs, what the ground hazes on to at the horizon)."""
    _, horizon, _ = sky_colors(sun)
    return tuple(g + (h - g) * haze for g, h in zip(ground_color(sun, ground), horizon, strict=True))


def _stars(count: int = STARS, seed: int = 29) -> np.ndarray:
    """``count`` stars: unit directions spread evenly over the upper sky and a brightness (most faint)."""
    rng = np.random.default_rng(seed)
    y = rng.random(count) ** 0.8  # (even over the hemisphere would be uniform in y; a few more up high)
    a = rng.random(count) * 2 * math.pi
    ring = np.sqrt(1 - y**2)
    bright = 0.25 + 0.75 * rng.random(count) ** 3
    return np.column_stack([ring * np.cos(a), y, ring * np.sin(a), bright]).astype("f4")


def cloud_rgba(size: int = 128, seed: int = 17) -> np.ndarray:
    """A cumulus as a texture twice as wide as tall: lobes of soft puffs with a ragged edge; red is how
    lit a point is (its top), alpha how thick."""
    rng = np.random.default_rng(seed)
    h, w = size // 2, size
    y, x = np.mgrid[0:h, 0:w] / np.array([h, w])[:, None, None]
    thick = np.zeros((h, w))
    for _ in range(16):
        cx, r = rng.uniform(0.15, 0.85), rng.uniform(0.07, 0.17)
        cy = 0.3 + 0.35 * (1.0 - 2.0 * abs(cx - 0.5)) * rng.random()  # heaped up in the middle
        thick += np.exp(-(((x - cx) * 2.0) ** 2 + (y - cy) ** 2) / (r * r))
    noise = np.fft.ifft2(np.fft.fft2(rng.standard_normal((h, w))) * np.exp(-np.add.outer(
        np.fft.fftfreq(h) ** 2, np.fft.fftfreq(w) ** 2) * 120.0)).real
    thick = thick * (0.7 + 0.6 * noise / max(float(np.abs(noise).max()), 1e-9)) * np.clip(y * 4.0, 0.0, 1.0)
    alpha = np.clip((thick - 0.35) * 1.6, 0.0, 1.0)
    lit = np.clip(0.6 + 1.2 * (y - 0.3), 0.0, 1.0)  # (rows from the bottom: the top is lit)
    return (np.dstack([lit, lit, lit, alpha]) * 255).astype("u1")


def ground_speckle(cells: int = 64, texels: int = 256, seed: int = 7) -> np.ndarray:
    """The ground's speckle: ``cells`` x ``cells`` random values (0..255) over a tile, smoothly interpolated
    to ``texels`` a side (periodic, by the Fourier transform), so that the nearest texel, the cheapest
    lookup on a software GL, shows soft blotches and not a grid of squares close to the camera (a bilinear
    lookup of the ``cells`` themselves costs llvmpipe 2 ms more a redrawn ground)."""
    cell = np.random.default_rng(seed).random((cells, cells))
    spectrum = np.fft.fftshift(np.fft.fft2(cell - cell.mean()))
    pad = (texels - cells) // 2
    fine = np.real(np.fft.ifft2(np.fft.ifftshift(np.pad(spectrum, pad)))) * (texels / cells) ** 2 + cell.mean()
    return np.clip(fine * 255.0 + 0.5, 0.0, 255.0).astype("u1")


def speckle_texture(ctx: moderngl.Context) -> moderngl.Texture:
    """The ground's speckle (:func:`ground_speckle`) as a repeating texture read nearest (already smooth:
    the cheapest lookup on a software GL), for the game's ground and the single-tree pictures' alike."""
    speckle = ground_speckle()
    texture = ctx.texture(speckle.shape[::-1], 1, speckle.tobytes())
    texture.filter = (moderngl.NEAREST, moderngl.NEAREST)
    texture.repeat_x = texture.repeat_y = True
    return texture


def _dome(rings: int = 14, sectors: int = 48) -> tuple[np.ndarray, np.ndarray]:
    """Unit directions of a dome from straight down to the zenith, and its triangles: below the horizon it
    is the far ground's colour (:func:`far_ground`), so where the ground disc ends (a camera close over a
    seedling sees past it) the view goes on into the far ground instead of showing the cleared, black
    framebuffer; a ring just under the horizon makes the line between ground and sky a sharp one."""
    elev = np.concatenate([[-math.pi / 2, -0.6, -0.15, -0.003], np.linspace(0.0, math.pi / 2, rings)])
    az = np.linspace(0.0, 2 * math.pi, sectors, endpoint=False)
    e, a = np.meshgrid(elev, az, indexing="ij")
    dirs = np.stack([np.cos(e) * np.cos(a), np.sin(e), np.cos(e) * np.sin(a)], axis=-1).reshape(-1, 3)
    idx = []
    for r in range(len(elev) - 1):
        for s in range(sectors):
            a0, a1 = r * sectors + s, r * sectors + (s + 1) % sectors
            b0, b1 = a0 + sectors, a1 + sectors
            idx += [(a0, a1, b1), (a0, b1, b0)]
    return dirs.astype("f4"), np.array(idx, "u4")


class Backdrop:
    """Sky dome, sun disc and ground for one scene (see module docstring)."""

    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self.cutaway = False
        self.soft = (0.0, 1.0 / 1024)  # shadow edges filtered over this many texels, and a texel (the renderer's)
        self.dome_prog = program(ctx, "dome.vert", "dome.frag")
        self.sun_prog = program(ctx, "sun.vert", "sun.frag")
        self.ground_prog = program(ctx, "ground_plain.vert", "ground_plain.frag")
        self.noise = speckle_texture(ctx)
        self.shade_prog = program(ctx, "ground.vert", "shade.frag")
        self.shade_buffer = ctx.buffer(reserve=64 * 12)
        self.shade = ctx.vertex_array(self.shade_prog, [(self.shade_buffer, "3f", "in_pos")])
        dirs, idx = _dome()
        self.dome_dirs = dirs.astype(float)  # (the sky's colours are computed at these, see sky_look.py)
        self.dome_sectors = 48  # (_dome's default: rings of this many vertices)
        self.dome = ctx.vertex_array(self.dome_prog, [(ctx.buffer(dirs.tobytes()), "3f", "in_dir")],
                                     ctx.buffer(idx.tobytes()))
        corners = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]], "f4")
        self.sun = ctx.vertex_array(self.sun_prog, [(ctx.buffer(corners.tobytes()), "2f", "in_corner")],
                                    ctx.buffer(np.array([0, 1, 2, 0, 2, 3], "u4").tobytes()))
        self.stars_prog = program(ctx, "stars.vert", "stars.frag")
        stars = ctx.buffer(_stars().tobytes())
        self.stars = ctx.vertex_array(self.stars_prog, [(stars, "3f 1f", "in_dir", "in_bright")])
        self.cloud_prog = program(ctx, "cloud.vert", "cloud.frag")
        self.cloud_texture = ctx.texture((128, 64), 4, cloud_rgba().tobytes())
        self.cloud_texture.build_mipmaps()
        self.cloud_texture.filter = (moderngl.LINEAR_MIPMAP_LINEAR, moderngl.LINEAR)
        self.clouds = ctx.vertex_array(self.cloud_prog, [(ctx.buffer(corners.tobytes()), "2f", "in_corner")],
                                       ctx.buffer(np.array([0, 1, 2, 0, 2, 3], "u4").tobytes()))
        rng = np.random.default_rng(5)
        self.cloud_places = np.column_stack([rng.uniform(0, 2 * math.pi, CLOUDS), rng.uniform(0.06, 0.35, CLOUDS),
                                             rng.uniform(0.7, 1.3, CLOUDS)])  # azimuth, elevation, size
        self.drift = 0  # clouds' drift in CLOUD_STEPs (set by the renderer from its clock)
        self.ground = None
        self.ground_radius = 0.0

    @property
    def ground_kind(self) -> tuple[float, float, float]:
        """The ground's own colour: grass, or soil in the cut-away view (and the roots in it)."""
        return SOIL if self.cutaway else GRASS

    def set_ground(self, radius: float) -> None:
        """A ground disc of ``radius`` around the origin, in rings (rebuilt only when it must grow or
        shrink a lot)."""
        if self.ground is not None and 0.8 * self.ground_radius <= radius <= 1.25 * self.ground_radius:
            return
        self.ground_radius = radius
        sectors, radii = GROUND_SECTORS, radius * (np.geomspace(1.0, 101.0, GROUND_RINGS) - 1.0) / 100.0
        radii = np.append(radii, radius * HORIZON_REACH)  # (a last ring out toward the horizon, hazier)
        ang = np.linspace(0, 2 * np.pi, sectors, endpoint=False)
        rings = np.stack([np.outer(radii, np.cos(ang)), np.zeros((len(radii), sectors)),
                          np.outer(radii, np.sin(ang))], axis=-1).reshape(-1, 3).astype("f4")
        idx = []
        for r in range(len(radii) - 1):
            for s in range(sectors):
                a0, a1 = r * sectors + s, r * sectors + (s + 1) % sectors
                idx += [(a0, a1, a1 + sectors), (a0, a1 + sectors, a0 + sectors)]
        self.ground = self.ctx.vertex_array(self.ground_prog, [(self.ctx.buffer(rings.tobytes()), "3f", "in_pos")],
                                            self.ctx.buffer(np.array(idx, "u4").tobytes()))

    def draw_ground(self, mvp: bytes, sun: np.ndarray, fade: tuple[float, float], eye: np.ndarray | None = None
                    ) -> None:
        """The ground, lit by the sun, fading into the far ground from ``fade[0]`` to ``fade[1]`` and on,
        with the distance from ``eye``, into the hazier ground at the horizon (the trees' shadows go on it
        with :meth:`draw_shadows`)."""
        self.noise.use(location=2)
        grass = ground_color(sun, self.ground_kind)
        set_uniforms(self.ground_prog, {
            "u_mvp": mvp, "u_noise": 2, "u_grass": grass, "u_horizon": far_ground(sun, self.ground_kind),
            "u_far": far_ground(sun, self.ground_kind, FAR_HAZE * HORIZON_HAZE),
            "u_eye": (0.0, 0.0) if eye is None else (float(eye[0]), float(eye[2])),
            "u_fade_start": fade[0], "u_fade_end": fade[1]})
        if self.ground is not None:
            self.ground.render()

    def draw_shadows(self, mvp: bytes, light: bytes, sun: np.ndarray, boxes: list[tuple[np.ndarray, np.ndarray]]
                     ) -> None:
        """Darken the ground where the trees' shadows can fall: the ground under and behind their
        bounding boxes (along the sun), not the whole ground (the shadow test per pixel is the costly
        part on a software GL). Call right after :meth:`draw_ground`, before the trees, without depth."""
        if sun[1] < 0.02 or not boxes:
            return
        points = []
        for lo, hi in boxes:
            corners = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (max(lo[1], 0.0), hi[1])
                                for z in (lo[2], hi[2])])
            reach = corners - np.outer(corners[:, 1] / max(sun[1], 0.05), sun)  # along the sun onto y = 0
            points.append(np.concatenate([corners, reach])[:, [0, 2]])
        hull = convex_hull(np.concatenate(points))
        if len(hull) < 3 or len(hull) > 60:
            return
        centre = hull.mean(axis=0)
        pad = (hull - centre) * 0.08 + np.sign(hull - centre) * 0.3  # soft shadow edges stay inside
        ring = hull + pad
        fan = np.concatenate([[centre], ring, ring[:1]])
        tris = np.stack([np.repeat(fan[:1], len(ring), 0), fan[1:-1], fan[2:]], axis=1).reshape(-1, 2)
        vertices = np.column_stack([tris[:, 0], np.zeros(len(tris)), tris[:, 1]]).astype("f4")
        self.shade_buffer.orphan(vertices.nbytes)
        self.shade_buffer.write(vertices.tobytes())
        set_uniforms(self.shade_prog, {"u_mvp": mvp, "u_light_mvp": light, "u_shadow": 1, "u_sun_dir": tuple(sun),
                                       "u_soft": self.soft[0], "u_shadow_texel": self.soft[1]})
        ctx = self.ctx
        ctx.enable(moderngl.BLEND)
        ctx.blend_func = moderngl.DST_COLOR, moderngl.ZERO
        self.shade.render(moderngl.TRIANGLES, vertices=len(vertices))
        ctx.disable(moderngl.BLEND)

    def draw_sky(self, vp: np.ndarray, eye: np.ndarray, far: float, sun: np.ndarray) -> None:
        """Sky dome then the sun's disc (when it is above the horizon); drawn first, without depth."""
        ctx = self.ctx
        zenith, horizon, day = sky_colors(sun)
        vp_bytes = np.ascontiguousarray(vp.T, dtype="f4").tobytes()
        radius = far * 0.9
        prog = self.dome_prog
        prog["u_vp"].write(vp_bytes)
        prog["u_eye"].value = tuple(eye)
        prog["u_radius"].value = radius
        prog["u_zenith"].value, prog["u_horizon"].value = zenith, horizon
        prog["u_below"].value = far_ground(sun, self.ground_kind, FAR_HAZE * HORIZON_HAZE)
        prog["u_sun_dir"].value = tuple(sun)
        prog["u_glow"].value = tuple(c * day for c in (1.0, 0.85, 0.55))
        self.dome.render()
        ctx.enable(moderngl.BLEND)
        ctx.blend_func = moderngl.ONE, moderngl.ONE
        if day < 0.999:  # the night sky: stars, and the moon opposite the sun
            ctx.enable(moderngl.PROGRAM_POINT_SIZE)
            set_uniforms(self.stars_prog, {"u_vp": vp_bytes, "u_eye": tuple(eye), "u_radius": radius,
                                           "u_night": 1.0 - day})
            self.stars.render(moderngl.POINTS)
            ctx.disable(moderngl.PROGRAM_POINT_SIZE)
            self._disc(vp_bytes, eye, radius, -np.asarray(sun, float), 0.045, tuple(c * (1.0 - day) for c in MOON))
        ctx.blend_func = moderngl.SRC_ALPHA, moderngl.ONE_MINUS_SRC_ALPHA
        self._clouds(vp_bytes, eye, radius, day, horizon)
        ctx.blend_func = moderngl.ONE, moderngl.ONE
        if sun[1] > -0.05:  # (over the clouds: the sun the tree lives on is always seen)
            low = float(np.clip(sun[1] * 3.0, 0.0, 1.0))  # redder near the horizon
            self._disc(vp_bytes, eye, radius, sun, 0.06, (1.0, 0.75 + 0.2 * low, 0.45 + 0.4 * low))
        ctx.disable(moderngl.BLEND)

    def _clouds(self, vp: bytes, eye: np.ndarray, radius: float, day: float, horizon: tuple) -> None:
        """The clouds, drifted ``self.drift`` steps, white by day and dim blue-grey at night."""
        self.cloud_texture.use(location=0)
        light = tuple(h * (1.0 - day) + day * c for h, c in zip(horizon, (1.0, 0.99, 0.96), strict=True))
        shade = tuple(0.6 * h + 0.15 * day for h in horizon)
        set_uniforms(self.cloud_prog, {"u_vp": vp, "u_eye": tuple(eye), "u_radius": radius * 0.93, "u_tex": 0,
                                       "u_light": light, "u_shade": shade, "u_alpha": 0.35 + 0.57 * day})
        for azimuth, elevation, size in self.cloud_places:
            a = azimuth + self.drift * CLOUD_STEP
            ring = math.cos(elevation)
            toward = np.array([ring * math.cos(a), math.sin(elevation), ring * math.sin(a)])
            right = np.array([-math.sin(a), 0.0, math.cos(a)])
            up = np.cross(right, toward)
            set_uniforms(self.cloud_prog, {"u_dir": tuple(toward), "u_right": tuple(right), "u_up": tuple(up),
                                           "u_size": (0.22 * size, 0.11 * size)})
            self.clouds.render()

    def _disc(self, vp: bytes, eye: np.ndarray, radius: float, toward: np.ndarray, size: float, color: tuple) -> None:
        """A glowing disc (the sun, the moon) on the far plane in direction ``toward``, added to the sky."""
        if toward[1] < -0.05:
            return
        right = np.cross(toward, [0.0, 1.0, 0.0])
        right = right / max(float(np.linalg.norm(right)), 1e-6)
        up = np.cross(right, toward)
        set_uniforms(self.sun_prog, {"u_vp": vp, "u_eye": tuple(eye), "u_sun_dir": tuple(toward),
                                     "u_right": tuple(right), "u_up": tuple(up), "u_radius": radius * 0.95,
                                     "u_size": size, "u_color": color})
        self.sun.render()
