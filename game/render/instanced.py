"""The game's trees on the GPU: per-segment and per-leaf records drawn by instancing.

One template per level of detail (sides per ring); one buffer of records per tree part. A grown tree
is uploaded once; after that each frame rewrites only the rows that grew (the young block at the end of
each buffer, see engine/life/growth_view.py), so a frame costs what changed, not the tree.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import moderngl
import numpy as np

from engine.life.growth_view import GrowthView
from game.render.backdrop import program, set_uniforms

SIDES = (8, 6, 4, 3)  # ring sides per level of detail
LEAF_KEPT = (1.0, 0.75, 0.5, 0.3)  # share of leaves drawn per level (the rest grow to cover the same area)
TUBE_LAYOUT = ("3f 3f 3f 3f 3f 3f 2f 2f 2f 1f 4x/i",  # the last float (branch order) is not read
               ("i_c0", "i_t0", "i_x0", "i_c1", "i_t1", "i_x1", "i_r", "i_v", "i_flex", "i_tip"))
PARTS = (("tube", 0), ("leaf", 1), ("blossom", 2), ("fruit", 3), ("stone", 4))  # record buffers, shader kinds
LEAF_LAYOUT = ("3f 3f 3f 3f 1f/i", ("i_base", "i_axis", "i_normal", "i_size", "i_hash"))


def tube_template(sides: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(vertices: cos, sin, ring, u), cap flags and triangles of one segment with ``sides`` sides."""
    ang = np.linspace(0.0, 2 * np.pi, sides + 1)
    u = np.linspace(0.0, 1.0, sides + 1)
    ring = lambda s: np.stack([np.cos(ang), np.sin(ang), np.full_like(ang, s), u], axis=1)  # noqa: E731
    verts = np.concatenate([ring(0.0), ring(1.0), ring(1.0), [[0.0, 0.0, 2.0, 0.5]]]).astype("f4")
    cap = np.concatenate([np.zeros(2 * (sides + 1)), np.ones(sides + 2)]).astype("f4")
    n1 = sides + 1
    tris = []
    for k in range(sides):
        a0, a1, b0, b1 = k, k + 1, n1 + k, n1 + k + 1
        tris += [(a0, a1, b1), (a0, b1, b0), (2 * n1 + k, 2 * n1 + k + 1, 3 * n1)]
    return verts, cap, np.array(tris, "u4")


@dataclass
class _Part:
    """One instance buffer (tubes, leaves, blossoms or fruit) of one tree, with its vertex arrays."""

    buffer: moderngl.Buffer
    capacity: int
    count: int = 0
    vaos: dict = field(default_factory=dict)

    def release(self) -> None:
        for vao in self.vaos.values():
            vao.release()
        self.buffer.release()


@dataclass
class TreeBuffers:
    """The GPU side of one tree: its record buffers and the view they were filled from."""

    view: GrowthView | None = None
    parts: dict[str, _Part] = field(default_factory=dict)

    def release(self) -> None:
        """Free every buffer."""
        for part in self.parts.values():
            part.release()
        self.parts.clear()


class InstancedTrees:
    """Programs and templates shared by every tree; uploads and draws :class:`TreeBuffers`."""

    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        wind = ("wind.glsl",)
        self.programs = {
            ("tube", "lit"): program(ctx, "tube.vert", "tree.frag", wind),
            ("tube", "shadow"): program(ctx, "tube.vert", "shadow.frag", wind),
            ("leaf", "lit"): program(ctx, "leaf.vert", "tree.frag", wind),
            ("leaf", "shadow"): program(ctx, "leaf.vert", "shadow.frag", wind),
        }
        self.templates = []
        for sides in SIDES:
            verts, cap, tris = tube_template(sides)
            self.templates.append((ctx.buffer(verts.tobytes()), ctx.buffer(cap.tobytes()), ctx.buffer(tris.tobytes())))
        corners = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], "f4")
        self.quad = (ctx.buffer(corners.tobytes()), ctx.buffer(np.array([0, 1, 2, 0, 2, 3], "u4").tobytes()))

    def sync(self, tree: TreeBuffers, view: GrowthView) -> None:
        """Bring ``tree``'s buffers up to ``view``: everything after a rebuild, else the young rows."""
        full = tree.view is not view
        tree.view = view
        for name, records, young_from in (("tube", view.tubes.data, view.young_row),
                                          ("leaf", view.leaves.data, view.young_leaf_row),
                                          ("blossom", view.blossoms.data, len(view.blossoms.data)),
                                          ("fruit", view.fruits.data, len(view.fruits.data)),
                                          ("stone", view.stones.data, len(view.stones.data))):
            self._write(tree, name, records, 0 if full else young_from)

    def _write(self, tree: TreeBuffers, name: str, records: np.ndarray, first: int) -> None:
        part = tree.parts.get(name)
        count = len(records)
        if part is None or part.capacity < count:
            if part is not None:
                part.release()
            capacity = max(64, int(count * 1.5))
            part = tree.parts[name] = _Part(self.ctx.buffer(reserve=capacity * records.shape[1] * 4), capacity)
            first = 0
        part.count = count
        if count > first:
            part.buffer.write(np.ascontiguousarray(records[first:]).tobytes(), offset=first * records.shape[1] * 4)

    def _vao(self, part: _Part, kind: str, pass_: str, lod: int) -> moderngl.VertexArray:
        key = (kind, pass_, lod if kind == "tube" else 0)
        vao = part.vaos.get(key)
        if vao is None:
            prog = self.programs[(kind if kind == "tube" else "leaf", pass_)]
            if kind == "tube":
                verts, cap, tris = self.templates[lod]
                layout, names = TUBE_LAYOUT
                content = [(verts, "4f", "in_ring"), (cap, "1f", "in_cap"), (part.buffer, layout, *names)]
            else:
                corners, tris = self.quad
                layout, names = LEAF_LAYOUT
                content = [(corners, "2f", "in_corner"), (part.buffer, layout, *names)]
            vao = part.vaos[key] = self.ctx.vertex_array(prog, content, tris, skip_errors=True)
        return vao

    def draw(self, tree: TreeBuffers, pass_: str, lod: int, uniforms: dict, textures: dict) -> None:
        """Draw one tree's wood, leaves, blossoms and fruit in ``pass_`` ('lit' or 'shadow') at level
        ``lod`` (fruit casts no shadow: too small to see in a 1024-texel map)."""
        for name, kind in PARTS:
            part = tree.parts.get(name)
            if part is None or part.count == 0 or (kind >= 3 and pass_ != "lit"):
                continue
            prog = self.programs[("tube" if name == "tube" else "leaf", pass_)]
            set_uniforms(prog, {k: v for k, v in uniforms.items() if k != "tints"})
            textures["bark" if kind in (0, 4) else "leaf" if kind == 1 else "blossom"].use(location=0)
            per_part = {"u_tex": 0, "u_fraction": LEAF_KEPT[lod] if kind == 1 else 1.0,
                        "u_keep": uniforms.get("u_keep", 1.0) if kind == 1 else 1.0, "u_ball": int(kind >= 3),
                        # far away, leaves skip the shadow lookup (their shade is the AO)
                        "u_shadowed": float(pass_ != "lit" or kind == 0 or lod < 2)}
            if pass_ == "lit":
                per_part.update(u_kind=kind, u_tint=(*uniforms["tints"], (1.0, 1.0, 1.0), (1.0, 1.0, 1.0))[kind],
                                u_uv_scale=(1.0, 1.0))
            else:
                per_part["u_alpha_test"] = int(kind != 0)
            set_uniforms(prog, per_part)
            self._vao(part, "tube" if kind == 0 else "leaf", pass_, lod).render(instances=part.count)
