"""Grass around the trees: a few thousand blades (a triangle each) scattered on the ground near every
tree, swaying in the trees' wind (assets/shaders/grass.vert).

The blades are one static buffer (made again only when the trees move or grow a lot), three vertices
each, the shadow looked up per vertex; far from the trees there is no grass, only the ground's own
colour. A GPU draws them every frame with the trees, swaying; a software GL, where they cost two thirds
of a sapling's frame, draws them still, into the sky-and-ground picture it keeps (game/render/stage.py),
where the ground's shade pass darkens them under the trees.
"""

from __future__ import annotations

import math

import moderngl
import numpy as np

from arbor.game.render.backdrop import program, set_uniforms

BLADES = 5000  # per tree
REACH = 2.2  # blades grow this many crown radii from a trunk (at least MIN_REACH units)
MIN_REACH = 14.0
CLEARING = 0.3  # share of the reach (at most 6 units) kept clear round a trunk
GREENS = np.array([[0.30, 0.50, 0.16], [0.36, 0.56, 0.18], [0.42, 0.55, 0.20], [0.26, 0.44, 0.15]])


def blades(centres: list[np.ndarray], reach: float, height: float, seed: int = 29) -> np.ndarray:
    """Vertices of grass blades (x, y, z, tip, r, g, b per vertex, three a blade) within ``reach`` of
    each centre on the ground, ``height`` tall on average, denser near the trunk."""
    rng = np.random.default_rng(seed)
    out = []
    for centre in centres:
        n = BLADES
        clear = min(CLEARING * reach, 6.0)  # a ring of bare soil round the trunk (as gardeners keep it)
        r = clear + (reach - clear) * np.sqrt(rng.random(n)) ** 1.3
        a = rng.random(n) * 2 * math.pi
        root = np.column_stack([centre[0] + r * np.cos(a), np.zeros(n), centre[2] + r * np.sin(a)])
        turn = rng.random(n) * 2 * math.pi
        across = np.column_stack([np.cos(turn), np.zeros(n), np.sin(turn)]) * (0.09 * height)
        tall = height * rng.uniform(0.6, 1.4, n)
        lean = np.column_stack([np.cos(turn + 1.57), np.zeros(n), np.sin(turn + 1.57)]) * (tall * rng.uniform(
            -0.35, 0.35, n))[:, None]
        tip = root + lean + np.column_stack([np.zeros(n), tall, np.zeros(n)])
        colour = GREENS[rng.integers(len(GREENS), size=n)] * rng.uniform(0.8, 1.15, (n, 1))
        corners = [np.column_stack([c, np.full(n, w), colour]) for c, w in ((root - across, 0.0),
                                                                              (root + across, 0.0), (tip, 1.0))]
        out.append(np.stack(corners, axis=1).reshape(-1, 7))
    return np.concatenate(out).astype("f4") if out else np.zeros((0, 7), "f4")


class Grass:
    """The blades around the placed trees, drawn with the trees (see module docstring)."""

    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self.prog = program(ctx, "grass.vert", "grass.frag", ("wind.glsl",))
        self.buffer: moderngl.Buffer | None = None
        self.vao: moderngl.VertexArray | None = None
        self.key: tuple | None = None
        self.version = 0  # counts the rebuilds (a picture with the grass in it is stale after one)

    def update(self, centres: list[np.ndarray], radius: float, tree_height: float) -> None:
        """Blades around ``centres`` for trees of crown ``radius`` and ``tree_height`` (made again only
        when the trees moved or changed size by more than a fifth)."""
        key = (tuple(tuple(np.round(c, 1)) for c in centres), round(math.log(max(radius, 1e-3)) / 0.2),
               round(math.log(max(tree_height, 1e-3)) / 0.2))
        if key == self.key:
            return
        self.key = key
        self.version += 1
        reach = max(REACH * radius, MIN_REACH)
        height = float(np.clip(0.035 * tree_height, 0.5, 2.5))  # (a sapling is not lost in the sward)
        data = blades(centres, reach, height)
        if self.vao is not None:
            self.vao.release()
            self.buffer.release()
        self.buffer = self.ctx.buffer(data.tobytes())
        self.vao = self.ctx.vertex_array(self.prog, [(self.buffer, "3f 1f 3f", "in_pos", "in_tip", "in_color")],
                                         skip_errors=True)
        self.sway = 1.6 * height / max(tree_height, 1.0)

    @staticmethod
    def look(uniforms: dict) -> np.ndarray:
        """How the blades are lit by ``uniforms`` (the trees' lit uniforms), in 8-bit levels of the
        brightest blade's colour at its tip and at its foot (as grass.vert lights them, unshadowed)."""
        sky, sun = np.asarray(uniforms["u_sky_color"]), np.asarray(uniforms["u_sun_color"])
        ambient = 0.55 * 0.6 + sky * 1.2 * 0.4
        light = sun * max(float(uniforms["u_sun_dir"][1]), 0.0) * 0.75
        brightest = float(GREENS.max()) * 1.15 * 1.3  # (and the tone curve's steepest)
        return np.concatenate([ambient + light, ambient * 0.45 + light]) * brightest * 255.0

    def draw(self, uniforms: dict, shadowed: bool = True) -> None:
        """Draw the blades (with ``shadowed``, the shadow map bound at unit 1)."""
        if self.vao is None:
            return
        set_uniforms(self.prog, {k: v for k, v in uniforms.items() if k != "tints"})
        set_uniforms(self.prog, {"u_shadow": 1, "u_sway": self.sway, "u_shadowed": float(shadowed)})
        self.ctx.disable(moderngl.CULL_FACE)
        self.vao.render(moderngl.TRIANGLES)
