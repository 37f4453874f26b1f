"""The game's trees on the GPU: per-segment and per-leaf records drawn by instancing.

One template per level of detail (sides per ring); one buffer of records per tree part. A grown tree
is uploaded once; after that each frame rewrites only the rows that grew (the young block at the end of
each view's records, see engine/life/form/growth_view.py, kept in buffers of their own), so a frame costs
what changed, not the tree.

The grown (old) block is uploaded in order of importance: segments thickest first, leaves by the hash
a coarse level keeps them by. A level of detail then draws a prefix of it: only the segments at least
so thick, only the leaves it keeps. On a software GL every instance costs its vertices even when the
shader drops it, so drawing fewer instances is what makes a big tree affordable.
"""

from __future__ import annotations

import math
import weakref
from dataclasses import dataclass, field

import moderngl
import numpy as np

from arbor.engine.life.form.growth_view import GrowthView
from arbor.game.render.backdrop import program, set_uniforms

SIDES = (8, 6, 4, 3)  # ring sides per level of detail
TEMPLATE_VERTICES = tuple(3 * (s + 1) + 1 for s in SIDES)  # two rings, the cap ring and the tip
# per level: the least radius (pixels) at which a ring of its sides is a pixel wide across its flats too
# (a square's flats are 1.41 radii apart, a triangle's height 1.5 radii), so no twig falls between pixels
TWIG_RADIUS = tuple(1.02 / (2 * math.cos(math.pi / s) if s % 2 == 0 else 1 + math.cos(math.pi / s)) for s in SIDES)
LEAF_KEPT = (1.0, 0.75, 0.5, 0.3)  # share of leaves drawn per level (the rest grow to cover the same area)
TUBE_LAYOUT = ("3f 3f 3f 3f 3f 3f 2f 2f 2f 1f 4x/i",  # the last float (branch order) is not read
               ("i_c0", "i_t0", "i_x0", "i_c1", "i_t1", "i_x1", "i_r", "i_v", "i_flex", "i_tip"))
PARTS = (("leaf", 1), ("leaf_young", 1), ("blossom", 2), ("fruit", 3), ("tube", 0), ("tube_young", 0),
         ("stone", 4))  # record buffers and shader kinds, in drawing order: wood hidden by leaves is not shaded
RADIUS = 18  # column of a tube record's start radius
HASH = 12  # column of a leaf record's hash
LENGTH = 9  # column of a leaf record's length (its width next)
LEAF_LAYOUT = ("2f 3f 3f 3f 3f 1f", ("i_base", "i_axis", "i_normal", "i_size", "i_hash"))  # a corner, then the record
CORNERS = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], "f4")  # of a leaf's quad (four vertices per leaf: a
QUAD = np.array([0, 1, 2, 0, 2, 3], "u4")  # software GL draws them faster than one instance per leaf)
MIN_PIXELS = (0.0, 0.0, 26.0, 6.5, 0.0)  # per kind: blossoms and fruit are drawn at least this many pixels across
BLOSSOM_GROW = 2.4  # a blossom record is drawn as a cluster of flowers (blossom.png), this much wider than one
BLOSSOM_FORWARD = 0.35  # and moved toward the eye by this share of its width (out of the leaves it sits among)
BARK_UV = (2.0, 1.0)  # the bark texture twice around a branch (u), once per growth step along it (v)


@dataclass(frozen=True)
class Detail:
    """How much of a tree a frame draws: template level (sides per ring), how many of the grown
    segments (thickest first) and grown leaves (by hash) it draws, and the share of leaves that is
    (the shader grows the kept ones to cover for the rest). Young parts are always drawn whole."""

    lod: int
    tubes: int = 0
    leaves: int = 0
    leaf_share: float = 1.0
    leaf_grow: float = 1.0  # how much larger than life the drawn leaves are (length and width)
    thinnest: float = 0.0  # growing segments thinner than the grown ones drawn are left out too
    fine: int = 0  # the thickest grown segments drawn at level 0 whatever the level (a trunk stays round)

    @classmethod
    def of(cls, tree: TreeBuffers, lod: int, thinnest: float = 0.0, leaf_share: float = 1.0) -> Detail:
        """Level ``lod`` drawing the grown segments at least ``thinnest`` thick and ``leaf_share``
        of the grown leaves, grown to cover the same area as all of them."""
        return cls(lod, tree.tubes_at_least(thinnest), tree.leaves_kept(leaf_share), leaf_share,
                   cover_grow(leaf_share), thinnest)

    def vertices(self, tree: TreeBuffers) -> int:
        """Vertices this detail makes the GL shade for ``tree`` (the cost on a software GL)."""
        tubes, quads = self._drawn(tree)
        fine = self._fine()
        return TEMPLATE_VERTICES[self.lod] * (tubes - fine) + TEMPLATE_VERTICES[0] * fine + 4 * quads

    def triangles(self, tree: TreeBuffers) -> int:
        """Triangles drawn for ``tree`` (3 per side of a segment, 2 per leaf)."""
        tubes, quads = self._drawn(tree)
        fine = self._fine()
        return 3 * SIDES[self.lod] * (tubes - fine) + 3 * SIDES[0] * fine + 2 * quads

    def _fine(self) -> int:
        """Grown segments drawn at level 0 (the thickest, see ``fine``)."""
        return min(self.fine, self.tubes) if self.lod > 0 else 0

    def _drawn(self, tree: TreeBuffers) -> tuple[int, int]:
        """Segments and quads (leaves, blossoms, fruit) drawn: the grown prefixes and every young one."""
        def counted(names: tuple[str, ...]) -> int:
            return sum(tree.parts[name].count for name in names if name in tree.parts)
        return self.tubes + counted(("tube_young",)), self.leaves + counted(("leaf_young", "blossom", "fruit"))


@dataclass(frozen=True)
class Piece:
    """A share of a tree's drawing, for pictures drawn over several frames: the parts named, and of
    the grown leaves and grown segments a level draws only those from share ``lo`` to ``hi`` of them."""

    names: frozenset[str] = frozenset(name for name, _ in PARTS)
    lo: float = 0.0
    hi: float = 1.0


WHOLE = Piece()
_PREPARED: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()  # view -> its grown records, sorted


def prepare_upload(view: GrowthView) -> GrowthView:
    """Sort ``view``'s grown records by importance now (on the worker thread that built a big tree's
    view), so that the frame that uploads it does not have to."""
    _PREPARED[view] = _by_importance(view)
    return view


def _by_importance(view) -> tuple[np.ndarray, np.ndarray]:
    """The grown (old) tube records thickest first and leaf records by ascending hash."""
    tubes, leaves = view.tubes.data[: view.young_row], view.leaves.data[: view.young_leaf_row]
    return (tubes[np.argsort(-tubes[:, RADIUS], kind="stable")],
            leaves[np.argsort(leaves[:, HASH], kind="stable")])


def cover_grow(share: float) -> float:
    """How much a share of the leaves grows to cover the area all of them cover (at most 4.5x)."""
    return 1.0 / math.sqrt(max(share, 0.05))


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
    """One part of one tree (tubes, leaves, blossoms or fruit): its records on the CPU, the GPU buffer
    they go to (uploaded as far as they are drawn; leaves as four vertices each) and vertex arrays."""

    buffer: moderngl.Buffer
    capacity: int
    records: np.ndarray
    quads: moderngl.Buffer | None = None  # leaf parts: the two triangles of each quad
    uploaded: int = 0
    vaos: dict = field(default_factory=dict)

    @property
    def count(self) -> int:
        """Records in this part."""
        return len(self.records)

    def upload(self, count: int) -> None:
        """Make sure the first ``count`` records are on the GPU (only what is missing goes)."""
        if count <= self.uploaded:
            return
        rows = self.records[self.uploaded:count]
        if self.quads is not None:
            rows = np.concatenate([np.tile(CORNERS, (len(rows), 1)), np.repeat(rows, 4, axis=0)], axis=1)
        stride = rows.shape[1] * 4 * (4 if self.quads is not None else 1)
        self.buffer.write(np.ascontiguousarray(rows, dtype="f4").tobytes(), offset=self.uploaded * stride)
        self.uploaded = count

    def release(self) -> None:
        for vao in self.vaos.values():
            vao.release()
        self.buffer.release()
        if self.quads is not None:
            self.quads.release()


@dataclass
class _From:
    """A vertex array whose record attributes start ``first`` records into their buffer."""

    vao: moderngl.VertexArray
    first: int = -1

    def release(self) -> None:
        self.vao.release()


@dataclass
class TreeBuffers:
    """The GPU side of one tree: its record buffers and the view they were filled from."""

    view: GrowthView | None = None
    parts: dict[str, _Part] = field(default_factory=dict)
    radii: np.ndarray = field(default_factory=lambda: np.zeros(0, np.float32))  # old segments', thickest first
    hashes: np.ndarray = field(default_factory=lambda: np.zeros(0, np.float32))  # old leaves' hashes, ascending
    leaf_area: float = 0.0  # of all its leaves (scene units squared)

    def tubes_at_least(self, radius: float) -> int:
        """How many old segments are at least ``radius`` thick (the prefix a level draws)."""
        return len(self.radii) - int(np.searchsorted(self.radii[::-1], radius, side="left"))

    def leaves_kept(self, fraction: float) -> int:
        """How many old leaves a level keeping ``fraction`` of them draws (hash <= fraction)."""
        return int(np.searchsorted(self.hashes, fraction, side="right"))

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
            # wood only: no alpha test, so a software GL tests depth before shading (see program)
            ("tube", "lit"): program(ctx, "tube.vert", "tree.frag", wind, {"u_kind": 0}),
            ("tube", "shadow"): program(ctx, "tube.vert", "shadow.frag", wind, {"u_alpha_test": 0}),
            ("leaf", "lit"): program(ctx, "leaf.vert", "tree.frag", wind),
            ("card", "lit"): program(ctx, "leaf.vert", "tree.frag", wind, {"u_kind": 1}),  # leaves only
            ("leaf", "shadow"): program(ctx, "leaf.vert", "shadow.frag", wind),
        }
        self.cull_wood = True  # the lit wood without its inner sides (closed tubes, wound outward)
        self.templates = []
        for sides in SIDES:
            verts, cap, tris = tube_template(sides)
            self.templates.append((ctx.buffer(verts.tobytes()), ctx.buffer(cap.tobytes()), ctx.buffer(tris.tobytes())))

    def sync(self, tree: TreeBuffers, view: GrowthView) -> None:
        """Bring ``tree``'s buffers up to ``view``: everything after a rebuild (the old blocks sorted
        by importance, see :func:`prepare_upload`), else only the young rows."""
        full = tree.view is not view
        tree.view = view
        if full:
            prepared = _PREPARED.pop(view, None) if isinstance(view, GrowthView) else None
            tubes, leaves = prepared if prepared is not None else _by_importance(view)
            tree.radii, tree.hashes = tubes[:, RADIUS].copy(), leaves[:, HASH].copy()
            tree.leaf_area = float(np.dot(view.leaves.data[:, LENGTH], view.leaves.data[:, LENGTH + 1]))
            self._write(tree, "tube", tubes)
            self._write(tree, "leaf", leaves)
            for name, records in (("blossom", view.blossoms.data), ("fruit", view.fruits.data),
                                  ("stone", view.stones.data)):
                self._write(tree, name, records)
        self._write(tree, "tube_young", view.tubes.data[view.young_row:])
        self._write(tree, "leaf_young", view.leaves.data[view.young_leaf_row:])

    def _write(self, tree: TreeBuffers, name: str, records: np.ndarray) -> None:
        """New records for a part (uploaded when drawn); its buffers grow when they must."""
        part = tree.parts.get(name)
        count, leafy = len(records), not name.startswith("tube")
        if part is None or part.capacity < count:
            if part is not None:
                part.release()
            capacity = max(64, int(count * 1.5))
            row = (records.shape[1] + 2) * 4 * 4 if leafy else records.shape[1] * 4
            quads = None
            if leafy:
                quads = self.ctx.buffer((QUAD[None, :] + 4 * np.arange(capacity, dtype="u4")[:, None]).tobytes())
            part = tree.parts[name] = _Part(self.ctx.buffer(reserve=capacity * row), capacity, records, quads)
        part.records, part.uploaded = records, 0

    def _vao(self, part: _Part, kind: str, pass_: str, lod: int) -> moderngl.VertexArray:
        key = (kind, pass_, lod if kind == "tube" else 0)
        vao = part.vaos.get(key)
        if vao is None:
            prog = self.programs[(kind if kind in ("tube", "card") else "leaf", pass_)]
            if kind == "tube":
                verts, cap, tris = self.templates[lod]
                layout, names = TUBE_LAYOUT
                content = [(verts, "4f", "in_ring"), (cap, "1f", "in_cap"), (part.buffer, layout, *names)]
            else:
                layout, names = LEAF_LAYOUT
                content, tris = [(part.buffer, layout, "in_corner", *names)], part.quads
            vao = part.vaos[key] = self.ctx.vertex_array(prog, content, tris, skip_errors=True)
        return vao

    def _tubes_from(self, part: _Part, pass_: str, lod: int, first: int) -> moderngl.VertexArray:
        """A vertex array of ``part``'s tubes at level ``lod`` whose instances begin at record ``first`` (its
        record attributes bound that far into the buffer: GL 3.3 has no base instance)."""
        key = ("tube_from", pass_, lod)
        prog = self.programs[("tube", pass_)]
        entry = part.vaos.get(key)
        if entry is None:
            verts, cap, tris = self.templates[lod]
            vao = self.ctx.vertex_array(prog, [(verts, "4f", "in_ring"), (cap, "1f", "in_cap")], tris,
                                        skip_errors=True)
            entry = part.vaos[key] = _From(vao)
        if entry.first != first:
            stride, offset = part.records.shape[1] * 4, first * part.records.shape[1] * 4
            for name, size in zip(TUBE_LAYOUT[1], (3, 3, 3, 3, 3, 3, 2, 2, 2, 1), strict=True):
                if name in prog:
                    entry.vao.bind(prog[name].location, "f", part.buffer, f"{size}f", offset, stride, 1)
                offset += size * 4
            entry.first = first
        return entry.vao

    def draw(self, tree: TreeBuffers, pass_: str, detail: Detail, uniforms: dict, textures: dict,
             piece: Piece = WHOLE) -> None:
        """Draw one tree's wood, leaves, blossoms and fruit in ``pass_`` ('lit' or 'shadow') at
        ``detail`` (fruit casts no shadow: too small to see in a 1024-texel map), or only ``piece``."""
        lod, share = detail.lod, detail.leaf_share
        for name, kind in PARTS:
            part = tree.parts.get(name)
            if part is None or part.count == 0 or (kind >= 3 and pass_ != "lit") or name not in piece.names:
                continue
            count = min(detail.tubes if name == "tube" else detail.leaves if name == "leaf" else part.count,
                        part.count)
            shared = name in ("leaf", "tube")  # (the grown leaves and wood a piece may draw a share of)
            first = round(count * piece.lo) if shared else 0
            count = round(count * piece.hi) if shared else count
            if count <= first:
                continue
            shape = "tube" if kind == 0 else "card" if kind == 1 and pass_ == "lit" else "leaf"
            prog = self.programs[(shape, pass_)]
            set_uniforms(prog, {k: v for k, v in uniforms.items() if k != "tints"})
            textures[("bark", "leaf_cluster", "blossom", "blossom", "rock")[kind]].use(location=0)
            per_part = {"u_tex": 0, "u_fraction": share if kind == 1 else 1.0, "u_min_pixels": MIN_PIXELS[kind],
                        "u_grow": detail.leaf_grow if kind == 1 else BLOSSOM_GROW if kind == 2 else 1.0,
                        "u_forward": BLOSSOM_FORWARD if kind == 2 and pass_ == "lit" else 0.0,
                        "u_thinnest": detail.thinnest,
                        "u_min_radius": TWIG_RADIUS[lod],
                        "u_keep": uniforms.get("u_keep", 1.0) if kind == 1 else 1.0,
                        # fruit is a ball and a lit blossom a flower, both turned to the eye (a small flower
                        # on a card seen edge-on, or tilted, was a pink speck of a pixel or two)
                        "u_ball": int(kind >= 3 or (kind == 2 and pass_ == "lit")),
                        # far away, leaves skip the shadow lookup (their shade is the AO)
                        "u_shadowed": float(pass_ != "lit" or kind == 0 or lod < 2)}
            if pass_ == "lit":
                textures["rock_normal" if kind == 4 else "bark_normal"].use(location=3)
                per_part.update(u_kind=kind, u_tint=(*uniforms["tints"], (1.0, 1.0, 1.0), (1.0, 1.0, 1.0))[kind],
                                u_uv_scale=BARK_UV if kind == 0 else (1.0, 1.0), u_normal_map=3)
            else:
                per_part["u_alpha_test"] = int(kind != 0)
            set_uniforms(prog, per_part)
            part.upload(count)
            vao = self._vao(part, shape, pass_, lod)
            if kind == 0:
                if pass_ == "lit" and self.cull_wood:
                    self.ctx.enable(moderngl.CULL_FACE)
                fine = detail._fine() if name == "tube" and pass_ == "lit" else 0
                # the thickest at level 0, the rest at the level's, each from its first record drawn on
                for level, start, end in ((0, first, min(count, fine)), (lod, max(first, fine), count)):
                    if end > start:
                        drawn = vao if start == 0 and level == lod else self._tubes_from(part, pass_, level, start)
                        drawn.render(instances=end - start)
                self.ctx.disable(moderngl.CULL_FACE)
            else:
                vao.render(vertices=6 * (count - first), first=6 * first)
