"""Modeler I: drawn strokes become ordinary L-string modules (Onishi et al. 2003 section 4.1, Wakabayashi & Durikovic).

A stroke is sampled (curvature-adaptive), smoothed into an arc-length spline and cut into pieces of
even length. Each piece becomes ``F(l, Vx, Vy, Vz, Hx, Hy, Hz, Ux, Uy, Uz, M)``: its length, start
position V, frame (heading H, up U; L = U x H) and variation M (degrees turned from the previous
piece). Between pieces, the rotation that takes the turtle's heading onto the next piece is written as
a turn about U then a pitch about L (the U, L, H order of Onishi et al. 2003, 4.1.3; no roll is ever needed),
so the ordinary turtle redraws the stroke exactly. The width ``!(d)`` is inversely proportional to the
drawing speed (clamped). Growth points ``A(l, Vx, Vy, Vz, d)`` carry the attributes of the F they sit
on and are placed along the axis with a density lambda(s) (Wakabayashi & Durikovic algorithm 2); the active rule set
grows branches from them (assets/lsystems/game_tree.lsys wakes them like dormant buds).

A stroke that starts near an existing axis snaps to the nearest point on it and is inserted there as
a bracketed branch (the F it starts on is split in two); one that starts farther away in the air is
joined to the nearest branch by a connecting piece, and only one starting at the ground begins a new
trunk. A branch is never drawn thicker than the drawn branch it grows from. A stroke passing through
an existing trunk is bent around it (Onishi et al. 2003, 4.1.5): away from it, or, when the axes nearly meet,
towards the side of the tree with fewer polygons.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

import numpy as np

from arbor.engine.geometry.turtle import INITIAL_FRAME, Segments, TurtleConfig, interpret, unit
from arbor.engine.lsystem import brackets
from arbor.engine.lsystem.lstring import LString, concat, parse_lstring
from arbor.engine.lsystem.text import format_number
from arbor.engine.modeling.history import Undoable
from arbor.engine.modeling.smoothing import smoothed
from arbor.engine.modeling.strokes import ArcLengthSpline, Stroke, adaptive_sample, curvature, speeds_at

DRAWN = ord("F")
GROWTH_POINT = ord("A")
F_PARAMS = 11
MAX_PIECES = 400  # pieces of one stroke at most (a longer stroke gets longer pieces)
CHUNK_PAIRS = 250_000  # point x segment pairs held at once while bending a stroke around trunks


@dataclass
class ModelerSettings:
    """How strokes become trunks: piece length, widths, growth-point density, snapping, bypass."""

    piece: float = 0.25  # length of one F piece (at most 1/24 of the stroke)
    width_speed: float = 0.3  # diameter = width_speed / speed (scene units / second)
    min_width: float = 0.03
    max_width: float = 0.5
    tip_taper: float = 0.6  # the end of a stroke is this much thinner than its start
    # lambda(s): growth points per scene unit of axis length at 0, 1/4, 1/2, 3/4 and all of the axis'
    # length (linear between; a species sets its own with LAM0..LAM4, see for_species)
    density: tuple[float, ...] = (0.0, 0.0, 1.2, 1.2, 1.2)
    branch_angle: float = 55.0
    snap_distance: float = 0.35  # strokes starting this close to an axis join it
    bypass_margin: float = 0.05
    near_axes: float = 0.1  # axes closer than this: bypass towards the side with fewer polygons
    seed: int = 0

    def __post_init__(self) -> None:
        density = np.atleast_1d(np.asarray(self.density, float))
        if density.ndim != 1 or not (np.isfinite(density).all() and (density >= 0).all() and density.max() <= 50):
            raise ValueError(f"growth-point density must be 0..50 per unit length at each point, got {self.density}")
        self.density = tuple(float(v) for v in density)

    @classmethod
    def for_species(cls, constants: Mapping[str, float], **changes) -> ModelerSettings:
        """The settings with the species' lambda(s) (its LAM0..LAM4 defines, where it has them)."""
        curve = tuple(float(constants[k]) for k in DENSITY_KEYS if k in constants)
        return cls(**({"density": curve} if len(curve) == len(DENSITY_KEYS) else {}), **changes)

    def density_at(self, s: np.ndarray) -> np.ndarray:
        """lambda at fractions ``s`` (0 = the axis' base, 1 = its end) of an axis' length."""
        return np.interp(s, np.linspace(0.0, 1.0, len(self.density)), self.density)


DENSITY_KEYS = ("LAM0", "LAM1", "LAM2", "LAM3", "LAM4")  # a species' lambda(s), in its .lsys defines


@dataclass
class StrokeResult:
    """What adding a stroke did, for feedback and tests."""

    pieces: int
    growth_points: int
    snapped_to: int | None = None  # module index of the F the stroke joined
    snap_point: np.ndarray | None = None  # where the stroke joins the tree (the joint point, Onishi et al. 2003)
    merged: bool = False  # a trunk drawn from the foot of a grown sapling, which now grows on top of it
    bypassed: int = 0  # samples moved to avoid a collision
    moved: float = 0.0  # how far a stroke started in the air was moved to start on the tree (scene units, m)
    text: str = ""



def _fmt(values) -> str:
    return ",".join(format_number(float(v)) for v in values)


def aimed(frame: np.ndarray, d: np.ndarray) -> tuple[str, np.ndarray]:
    """The turn and pitch (``+`` about U, then ``&`` about L) that aim a turtle with ``frame`` along the
    unit vector ``d``, as text, and its frame after them (H exactly ``d``)."""
    h, lft = frame[:, 0], frame[:, 1]
    turn = np.degrees(np.arctan2(d @ lft, d @ h))
    frame = frame @ _rot_z(turn)
    h, up = frame[:, 0], frame[:, 2]
    pitch = np.degrees(np.arctan2(-(d @ up), d @ h))
    frame = frame @ _rot_y(pitch)
    frame[:, 0] = d  # remove rounding drift: H is exactly the piece direction
    frame[:, 2] = unit(frame[:, 2] - (frame[:, 2] @ d) * d)
    frame[:, 1] = np.cross(frame[:, 2], d)
    text = f"+({format_number(float(turn))})" if abs(turn) > 1e-9 else ""
    return text + (f"&({format_number(float(pitch))})" if abs(pitch) > 1e-9 else ""), frame


def path_modules(path: np.ndarray, frame: np.ndarray, widths: np.ndarray, growth: list[tuple[int, float]],
                 settings: ModelerSettings, symbol: str = "F") -> tuple[str, np.ndarray]:
    """L-string text that makes a turtle with frame ``frame`` at ``path[0]`` draw the polyline ``path``.

    ``widths`` has one diameter per piece; ``growth`` lists (piece index, roll angle) for growth points.
    Returns the text and the turtle's frame at the end (``symbol`` 'f' moves without drawing).
    """
    out: list[str] = []
    frame = frame.copy()
    growth_at = dict(growth)
    prev_dir = frame[:, 0]
    for i in range(len(path) - 1):
        d = path[i + 1] - path[i]
        length = float(np.linalg.norm(d))
        if length <= 1e-12:
            continue
        d = d / length
        aim, frame = aimed(frame, d)
        out.append(aim)
        variation = float(np.degrees(np.arccos(np.clip(prev_dir @ d, -1.0, 1.0))))
        prev_dir = d
        w = float(widths[min(i, len(widths) - 1)])
        width = f"!({format_number(w)})" if symbol == "F" else ""
        out.append(f"{width}{symbol}({_fmt([length, *path[i], *d, *frame[:, 2], variation])})")
        if i in growth_at:
            attrs = _fmt([length, *path[i + 1], w])
            out.append(f"[/({format_number(growth_at[i])})&({format_number(settings.branch_angle)})A({attrs})]")
    return "".join(out), frame


def _rot_z(deg: float) -> np.ndarray:
    a = np.radians(deg)
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _rot_y(deg: float) -> np.ndarray:
    a = np.radians(deg)
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def smooth_path(stroke: Stroke, piece: float, tolerance: float = 0.002) -> tuple[np.ndarray, np.ndarray]:
    """Key points by curvature, an arc-length spline through them, resampled every ``piece`` at most.

    The stroke is smoothed first (engine/modeling/smoothing.py: jitter out, drawn bends kept). Where the
    curve bends, pieces get shorter so a chord
    never strays more than ``tolerance`` x the stroke length from the curve (sagitta l^2 kappa / 8).
    Returns the path (m, 3) and the arc length
    of each path point along the spline.
    """
    stroke = stroke.deduplicated()
    if len(stroke.points) < 2:
        return stroke.points.copy(), np.zeros(len(stroke.points))
    keys = smoothed(stroke.points)
    keys = keys[adaptive_sample(keys)]
    spline = ArcLengthSpline(keys)
    shape = spline.at(np.linspace(0.0, spline.length, 49))  # curvature at the drawing's scale, not tremor
    kappa = float(curvature(shape).max())
    if kappa > 0:
        piece = min(piece, float(np.sqrt(8 * tolerance * spline.length / kappa)))
    path = spline.resample(piece)
    return path, np.linspace(0.0, spline.length, len(path))


def widths_from_speed(stroke: Stroke, s: np.ndarray, settings: ModelerSettings) -> np.ndarray:
    """Diameter per piece, inversely proportional to drawing speed (Onishi et al. 2003), clamped, and tapering
    towards the end of the stroke."""
    mids = 0.5 * (s[1:] + s[:-1]) if len(s) > 1 else s
    speed = speeds_at(stroke.deduplicated(), mids * stroke.length / max(s[-1], 1e-12), 4 * settings.piece)
    width = np.clip(settings.width_speed / np.maximum(speed, 1e-9), settings.min_width, settings.max_width)
    taper = 1.0 - (1.0 - settings.tip_taper) * mids / max(s[-1], 1e-12)
    return np.maximum(width * taper, settings.min_width)


def growth_points(s: np.ndarray, settings: ModelerSettings, rng: np.random.Generator) -> list[tuple[int, float]]:
    """Seed 002 algorithm 2: along the axis, a' = a + lambda(s) ds; with r a fresh random number, a
    piece gets a growth point when a' >= r (and a' drops by one): lambda(s) points per unit length on
    average, at random places, never two where the density allows one.

    lambda(s) is the settings' density curve over the axis' length (a species shapes it: bare low down,
    densest where its crown is). Each point is rolled by the golden angle from the previous one.
    """
    total = s[-1] if len(s) else 0.0
    out, acc, roll = [], 0.0, float(rng.random() * 360.0)
    draws = rng.random(max(len(s) - 1, 0))
    added = np.diff(s) * settings.density_at(0.5 * (s[1:] + s[:-1]) / max(total, 1e-12))
    for i in range(len(s) - 1):
        acc += float(added[i])
        if acc >= draws[i]:
            acc -= 1.0
            roll = (roll + 137.5) % 360.0
            out.append((i, roll))
    return out


def nearest_on_segments(point: np.ndarray, segs: Segments) -> tuple[int, float, float]:
    """(segment index, fraction along it, distance) of the closest point of any segment to ``point``."""
    a, b = segs.start, segs.end
    ab = b - a
    t = np.clip(np.einsum("ij,ij->i", point - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300), 0, 1)
    dist = np.linalg.norm(a + ab * t[:, None] - point, axis=1)
    k = int(np.argmin(dist))
    return k, float(t[k]), float(dist[k])


def _segment_distances(points: np.ndarray, segs: Segments) -> tuple[np.ndarray, np.ndarray]:
    """For each point: distance to every segment axis (n, m) and the closest points (n, m, 3)."""
    a, ab = segs.start[None], (segs.end - segs.start)[None]
    rel = points[:, None] - a
    t = np.clip(np.einsum("nmi,nmi->nm", rel, np.broadcast_to(ab, rel.shape))
                / np.maximum(np.einsum("mi,mi->m", ab[0], ab[0]), 1e-300), 0, 1)
    closest = a + ab * t[..., None]
    return np.linalg.norm(points[:, None] - closest, axis=2), closest


def _segments_near(segs: Segments, point: np.ndarray, distance: float) -> np.ndarray:
    """Segments whose axis passes within ``distance`` of ``point``."""
    dist, _ = _segment_distances(point[None], segs)
    return dist[0] < distance


def bypass(path: np.ndarray, radius: np.ndarray, segs: Segments, skip: np.ndarray,
           settings: ModelerSettings, free: np.ndarray | None = None) -> tuple[np.ndarray, int]:
    """Bend ``path`` around existing segments it would pass through (Onishi et al. 2003, 4.1.5).

    ``radius`` is the new axis' radius per path point; segments flagged in ``skip`` (the one the stroke
    starts on) are ignored, and so are path points not flagged in ``free`` (the joint region).
    Returns the new path and how many points moved.
    """
    if len(segs) == 0 or len(path) < 3:
        return path, 0
    reach = float(radius.max()) + float(segs.radius.max()) + settings.bypass_margin + 1e-9
    lo, hi = path.min(axis=0) - 2 * reach, path.max(axis=0) + 2 * reach
    seg_lo, seg_hi = np.minimum(segs.start, segs.end), np.maximum(segs.start, segs.end)
    near = np.flatnonzero(np.all(seg_hi >= lo, axis=1) & np.all(seg_lo <= hi, axis=1) & ~skip)
    if len(near) == 0:
        return path, 0
    segs = _subset(segs, near)  # only pieces near the stroke: memory grows with the stroke, not the tree
    skip = np.zeros(len(near), bool)
    moved_total = 0
    out = path.copy()
    for _ in range(4):  # pushing away from one trunk may touch another: settle in a few passes
        owner, closest, dist, need = _owners(out, radius, segs, settings.bypass_margin)
        owner[0] = -1  # the start point stays where it was drawn or snapped
        if free is not None:
            owner[~free] = -1
        if not (owner >= 0).any():
            break
        offset = np.zeros_like(out)
        for j in np.unique(owner[owner >= 0]):
            offset += _push_from(out, closest, dist, need, owner == j, segs, j, settings)
        out = out + _spread(offset)
        moved_total += int((owner >= 0).sum())
    return out, moved_total


def _owners(points: np.ndarray, radius: np.ndarray, segs: Segments, margin: float):
    """For each point: the segment whose cylinder it enters most (-1: none), with the closest point on
    that segment's axis, the distance to it and the clearance needed. Works in chunks of points so the
    (points x segments) temporaries stay below about CHUNK_PAIRS pairs."""
    n = len(points)
    owner = np.full(n, -1, dtype=np.int64)
    closest, dist, need = np.zeros((n, 3)), np.zeros(n), np.zeros(n)
    step = max(1, CHUNK_PAIRS // max(len(segs), 1))
    for s in range(0, n, step):
        e = min(n, s + step)
        d, c = _segment_distances(points[s:e], segs)
        nd = segs.radius[None, :] + radius[s:e, None] + margin
        depth = np.where(d < nd, nd - d, -np.inf)
        deepest = np.argmax(depth, axis=1)  # each point answers to the segment it enters most
        rows = np.arange(e - s)
        owner[s:e] = np.where(np.isfinite(depth[rows, deepest]), deepest, -1)
        closest[s:e], dist[s:e], need[s:e] = c[rows, deepest], d[rows, deepest], nd[rows, deepest]
    return owner, closest, dist, need


def _subset(segs: Segments, idx: np.ndarray) -> Segments:
    """The segments ``idx`` (parents renumbered; a parent outside the subset becomes -1)."""
    index = np.full(len(segs) + 1, -1, dtype=np.int64)
    index[idx] = np.arange(len(idx))
    return Segments(segs.start[idx], segs.end[idx], segs.radius[idx], segs.radius_end[idx], segs.frame[idx],
                    segs.order[idx], segs.module[idx], index[segs.parent[idx]], segs.continues[idx],
                    segs.colour[idx])


def _push_from(path, closest, dist, need, hit, segs: Segments, j: int, settings: ModelerSettings) -> np.ndarray:
    """Offsets that move the hit points of ``path`` out of segment j's cylinder."""
    away = path - closest
    axis = unit(segs.end[j] - segs.start[j])
    if dist[hit].min() <= settings.near_axes:  # axes (nearly) meet: go to the emptier side
        crossing = unit(path[-1] - path[0])
        normal = unit(np.cross(axis, crossing))
        if np.linalg.norm(normal) < 1e-9:
            normal = unit(np.cross(axis, np.array([1.0, 0.0, 0.0])))
        mids = 0.5 * (segs.start + segs.end) - segs.start[j]
        side = np.sign(np.sum(np.sign(mids @ normal))) or 1.0
        direction = np.broadcast_to(-side * normal, path.shape)
    else:
        direction = unit(away - (away @ axis)[:, None] * axis)
    push = np.where(hit, need - dist + 1e-6, 0.0)
    current = np.einsum("ij,ij->i", away, direction)
    return direction * np.maximum(push, need - current)[:, None] * hit[:, None]


def _spread(offset: np.ndarray, weights=(0.35, 0.7, 1.0, 0.7, 0.35)) -> np.ndarray:
    """Let the neighbours of pushed points follow part of the way, so the axis bends instead of kinking.

    Each point takes the largest of its neighbours' pushes scaled by distance weights (a dilation,
    not a sum, so overlapping pushes never add up to more than the largest one).
    """
    n, half = len(offset), len(weights) // 2
    best = np.zeros_like(offset)
    best_norm = np.zeros(n)
    for k, w in enumerate(weights):
        shift = k - half
        cand = np.zeros_like(offset)
        if shift >= 0:
            cand[shift:] = offset[: n - shift] * w
        else:
            cand[:shift] = offset[-shift:] * w
        norm = np.linalg.norm(cand, axis=1)
        better = norm > best_norm
        best[better], best_norm[better] = cand[better], norm[better]
    best[0] = 0.0
    return best


@dataclass
class Modeler(Undoable):
    """An editable modeled tree: add strokes, undo, redo. The L-string is the only state; strokes,
    grown crowns and region edits all ``commit`` a new one."""

    HISTORY_OF = "lstring"

    lstring: LString = field(default_factory=LString.empty)
    settings: ModelerSettings = field(default_factory=ModelerSettings)
    undo_stack: list[LString] = field(default_factory=list)
    redo_stack: list[LString] = field(default_factory=list)
    segments_of: Callable[[LString], Segments] | None = None  # e.g. a growing tree's drawn view

    def __post_init__(self) -> None:
        self.rng = np.random.default_rng(self.settings.seed)

    def segments(self) -> Segments:
        """The current tree's segments (for snapping, collisions and picking)."""
        if self.segments_of is not None:
            return self.segments_of(self.lstring)
        return interpret(self.lstring, TurtleConfig(pipe_model=False, leaves_at_tips=0)).segments

    def convert(self, stroke: Stroke) -> tuple[LString, StrokeResult]:
        """The L-string this stroke would produce, without committing it (live preview)."""
        cfg = self.settings
        piece = min(cfg.piece, max(stroke.length / 24, 1e-3))  # short strokes still get enough pieces
        piece = max(piece, stroke.length / MAX_PIECES)  # a huge stroke gets longer pieces, not more
        path, s = smooth_path(stroke, piece)
        if len(path) < 2:
            return self.lstring, StrokeResult(0, 0)
        widths = widths_from_speed(stroke, s, cfg)
        result = StrokeResult(len(path) - 1, 0)
        growth = growth_points(s, cfg, np.random.default_rng(self.rng.integers(2**31)))
        result.growth_points = len(growth)
        if len(self.lstring) == 0:  # the first stroke is the trunk: the tree's base is where it starts
            path = path - path[0]
            body, _ = path_modules(path, INITIAL_FRAME, widths, growth, cfg)
            result.text = body
            return parse_lstring(body), result
        segs = self.segments()
        k, frac, dist = nearest_on_segments(path[0], segs)
        skip = np.zeros(len(segs), bool)
        base = np.flatnonzero(segs.parent < 0)
        at_foot = (len(base) and path[0][1] <= cfg.snap_distance
                   and float(np.linalg.norm(path[0] - segs.start[base[0]])) <= 2 * cfg.snap_distance)
        if at_foot and not self._is_drawn(int(segs.module[base[0]])):
            return self._trunk_under(path, widths, growth, 2 * float(segs.radius[base[0]]), result)
        on_ground = path[0][1] <= cfg.snap_distance and dist > cfg.snap_distance + segs.radius[k]
        if not on_ground:  # every stroke off the ground belongs to the tree: join the nearest branch
            snap = segs.start[k] + frac * (segs.end[k] - segs.start[k])  # where it was pressed, on any piece
            if dist <= cfg.snap_distance + segs.radius[k]:
                path = path + np.linspace(1.0, 0.0, len(path))[:, None] * (snap - path[0])  # ease onto the axis
            else:  # started in the air: the stroke, as drawn, moves to start on the tree (the preview shows it)
                result.moved = float(np.linalg.norm(snap - path[0]))
                path = path + (snap - path[0])
            result.snapped_to, result.snap_point = int(segs.module[k]), snap
            widths = np.minimum(widths, 2 * segs.radius[k] * 0.9)  # no thicker than the stem at the joint
            skip[k] = True
            skip[segs.parent == k] = True
        radius = np.append(widths, widths[-1]) / 2
        if result.snapped_to is not None:  # the joint itself is not a collision
            near = np.linalg.norm(path - path[0], axis=1) < 2.5 * (segs.radius[k] + radius)
            skip |= _segments_near(segs, path[0], 2.5 * (segs.radius[k] + radius[0]))
            path_free = ~near
        else:
            path_free = np.ones(len(path), bool)
        path, result.bypassed = bypass(path, radius, segs, skip, cfg, path_free)
        if result.snapped_to is not None:
            body, _ = path_modules(path, segs.frame[k], widths, growth, cfg)
            result.text = body
            return _branch_at(self.lstring, result.snapped_to, frac, body), result
        # a new axis away from the tree: move there from the base without drawing, then draw
        move, frame = path_modules(np.stack([np.zeros(3), path[0]]), INITIAL_FRAME, widths[:1], [], cfg, "f")
        body, _ = path_modules(path, frame, widths, growth, cfg)
        result.text = body
        # (at the start of the string the turtle is still at the base with its initial frame)
        return concat(parse_lstring("[" + move + body + "]"), self.lstring), result

    def preview(self, stroke: Stroke) -> tuple[LString, StrokeResult]:
        """What :meth:`convert` gives for ``stroke``, leaving the session's random generator as it was (a
        live preview redrawn many times must not change what the committed stroke grows)."""
        state = self.rng.bit_generator.state
        try:
            return self.convert(stroke)
        finally:
            self.rng.bit_generator.state = state

    def _trunk_under(self, path: np.ndarray, widths: np.ndarray, growth, top: float,
                     result: StrokeResult) -> tuple[LString, StrokeResult]:
        """A trunk drawn up from the foot of a grown sapling: it becomes the tree's trunk and the sapling
        carries on from its top, the drawn widths easing into the sapling's stem (no step at the joint,
        no second trunk beside the first)."""
        path = path - path[0]
        ease = np.linspace(0.0, 1.0, len(widths)) ** 2
        widths = np.maximum(widths * (1 - ease) + top * ease, top)
        body, frame = path_modules(path, INITIAL_FRAME, widths, growth, self.settings)
        # the sapling grows on upward, leaning as the drawn trunk leans as a whole: a flick of the hand at
        # the stroke's end must not send it sideways or down
        on, _ = aimed(frame, unit(unit(path[-1] - path[0]) + np.array([0.0, 1.0, 0.0])))
        body += on
        result.text, result.snap_point, result.merged = body, np.zeros(3), True
        return concat(parse_lstring(body), self.lstring), result

    def _is_drawn(self, module: int) -> bool:
        return bool(self.lstring.sym[module] == DRAWN and self.lstring.nparams[module] == F_PARAMS)

    def add_stroke(self, stroke: Stroke) -> StrokeResult:
        """Convert a finished stroke and commit it (undoable)."""
        new, result = self.convert(stroke)
        if result.pieces:
            self.commit(new)
        return result


def _branch_at(ls: LString, module: int, frac: float, body: str) -> LString:
    """Insert ``[body]`` at ``frac`` along module ``module``: drawn pieces are split there, and so are
    grown internodes ``I(b,g,o,s,w[,n])`` (whose length is ``n`` pieces' at their age: the two halves
    keep ``frac`` and ``1 - frac`` of the pieces, so they draw as the one did and grow on alike); any
    other module gets the branch at its end."""
    sym, params = ls.module(module)
    index = np.arange(len(ls))
    if sym == "I" and len(params) in (5, 6) and 1e-6 < frac < 1 - 1e-6:
        pieces = params[5] if len(params) == 6 else 1.0
        first, second = [*params[:5], pieces * frac], [*params[:5], pieces * (1 - frac)]
        mid = parse_lstring(f"I({_fmt(first)})[{body}]I({_fmt(second)})")
        return concat(ls.select(index < module), mid, ls.select(index > module))
    if not (sym == "F" and len(params) == F_PARAMS):
        at_start = sym == "I" and frac <= 1e-6
        return concat(ls.select(index < module if at_start else index <= module), parse_lstring(f"[{body}]"),
                      ls.select(index >= module if at_start else index > module))
    first, second = list(params), list(params)
    length = params[0]
    first[0] = length * frac
    second[0] = length * (1.0 - frac)
    if len(params) >= 7:  # a drawn piece: the second half starts further along its heading
        for c in range(3):
            second[1 + c] = params[1 + c] + params[4 + c] * length * frac
    mid = parse_lstring(f"{sym}({_fmt(first)})[{body}]{sym}({_fmt(second)})")
    out = concat(ls.select(index < module), mid, ls.select(index > module))
    brackets.check_balanced(out.sym)
    return out
