"""3D turtle interpretation of an L-string (ABOP conventions, Y up).

The turtle state is a frame (columns H, L, U: heading, left, up), a position, a width and a colour
index. One compiled pass over the string (engine.geometry.turtle_kernel) keeps a stack of states for
'[' and ']', writes a row per drawn piece and records the state going into the modules asked about
(leaves, blossoms, fruit, probes); everything after it (radii, tip leaves) is whole-array numpy.

Symbols: F G (move, draw), f (move), + - (turn about U), & ^ (pitch about L), / \\ (roll about H),
| (turn around), $ (roll so L is horizontal), T(a) (bend a degrees towards the tropism vector),
[ ] (push, pop), !(w) (width; bare '!' shrinks it),
'(c) (colour index; bare ' increments it), L (leaf) and K (blossom) with an optional size.
A missing parameter takes the default from the .lsys source (angle, step, width).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from arbor.engine.lsystem import brackets
from arbor.engine.lsystem.lstring import LString

# Initial frame: heading up (+Y), left -X, up +Z (H x L = U, right-handed).
INITIAL_FRAME = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])

_DRAW = np.zeros(256, bool)
_DRAW[[ord("F"), ord("G")]] = True
LEAF, BLOSSOM, FRUIT = ord("L"), ord("K"), ord("O")
_INSTANCE = np.zeros(256, bool)
_INSTANCE[[LEAF, BLOSSOM, FRUIT]] = True


@dataclass
class TurtleConfig:
    """Defaults for parameter-less modules and how leaves are placed."""

    angle: float = 90.0  # degrees
    step: float = 1.0
    width: float | None = None  # initial diameter; None: 1 for '!' systems, auto-scaled for pipe-model ones
    width_scale: float = 1.0  # '!' values are multiplied by this (ABOP widths are in other units)
    width_factor: float = 0.7  # bare '!' multiplies the width by this
    leaf_size: float | None = None  # None: 0.8 x the mean length of tip segments
    leaves_at_tips: int | None = None  # leaves at every branch tip; None: 3 when the string has no L
    pipe_model: bool | None = None  # radii from the pipe model; None: when the string has no '!'
    pipe_exponent: float = 2.0  # r_parent^e = sum of r_child^e (2 = area preserving, da Vinci)
    tropism: tuple[float, float, float] | None = None  # world vector that 'T(angle)' bends towards

    @classmethod
    def from_system(cls, system, **overrides) -> TurtleConfig:
        """Defaults taken from an LSystem's header (angle, step, width, width_scale, leaves)."""
        cfg = cls(angle=system.angle, step=system.step, width=system.width, width_scale=system.width_scale,
                  leaf_size=system.leaf_size, leaves_at_tips=system.leaves_at_tips, tropism=system.tropism)
        for key, value in overrides.items():
            setattr(cfg, key, value)
        return cfg


@dataclass
class Segments:
    """Drawn segments as flat arrays (one row per F module)."""

    start: np.ndarray  # (m, 3)
    end: np.ndarray  # (m, 3)
    radius: np.ndarray  # (m,) radius at the start of the segment
    radius_end: np.ndarray  # (m,) radius at the end (the next segment's start radius on the same axis)
    frame: np.ndarray  # (m, 3, 3) columns H, L, U
    order: np.ndarray  # (m,) branch order (bracket depth)
    module: np.ndarray  # (m,) index of the F module in the L-string
    parent: np.ndarray  # (m,) index of the segment it grows from, -1 for the root
    continues: np.ndarray  # (m,) True when it continues its parent's axis (shares its joint ring)
    colour: np.ndarray  # (m,) colour index

    def __len__(self) -> int:
        return len(self.module)


@dataclass
class Leaves:
    """Leaf or blossom instances: position, frame (H along the leaf, U its normal), size, source module."""

    position: np.ndarray  # (k, 3)
    frame: np.ndarray  # (k, 3, 3)
    size: np.ndarray  # (k,)
    module: np.ndarray  # (k,)

    def __len__(self) -> int:
        return len(self.module)


@dataclass
class TurtleResult:
    """Everything the mesher, picking and overlays need from one interpretation."""

    segments: Segments
    leaves: Leaves
    blossoms: Leaves
    fruits: Leaves | None = None  # 'O' modules: position and size of each fruit
    probes: Leaves | None = None  # the turtle's state going into modules the caller asked about
    nearest_move: np.ndarray | None = None  # (n,) module index of the move before each module (-1 none)

    def carriers(self, idx: np.ndarray) -> np.ndarray:
        """The segment each of the modules ``idx`` grows from (the last drawn piece on its path; -1 none)."""
        segs = self.segments
        lookup = np.full(len(self.nearest_move) + 1, -1, dtype=np.int64)
        lookup[segs.module] = np.arange(len(segs))
        return lookup[self.nearest_move[np.asarray(idx, dtype=np.int64)]]

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """Axis-aligned bounds of all segment end points and leaves."""
        pts = [self.segments.start, self.segments.end, self.leaves.position, self.blossoms.position]
        allp = np.concatenate([p for p in pts if len(p)] or [np.zeros((1, 3))])
        return allp.min(axis=0), allp.max(axis=0)


def _first_param(ls: LString, idx: np.ndarray, default: float) -> np.ndarray:
    has = ls.nparams[idx] > 0
    out = np.full(len(idx), default, dtype=np.float64)
    out[has] = ls.params[ls.offsets[idx[has]]]
    return out


@dataclass
class _Walk:
    """What the compiled walk returns: drawn pieces, nearest moves, and the recorded modules' states."""

    start: np.ndarray
    end: np.ndarray
    frame: np.ndarray
    width: np.ndarray
    colour: np.ndarray
    depth: np.ndarray  # bracket depth of each drawn piece
    parent: np.ndarray
    nearest_move: np.ndarray
    recorded: np.ndarray  # (k,) the recorded modules, in string order
    position: np.ndarray  # (k, 3) going into each recorded module
    rec_frame: np.ndarray  # (k, 3, 3)

    def states_in(self, idx: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Position and frame going into the (recorded) modules ``idx``."""
        rows = np.searchsorted(self.recorded, idx)
        return np.take(self.position, rows, axis=0), np.take(self.rec_frame, rows, axis=0)


def _walk(ls: LString, cfg: TurtleConfig, record: np.ndarray) -> _Walk:
    """Run the compiled turtle over the string (engine.geometry.turtle_kernel), recording the state
    going into every module where ``record`` is True; unbalanced brackets raise BracketError."""
    from arbor.engine.geometry.turtle_kernel import walk

    width0 = 1.0 if cfg.width is None else cfg.width
    bends = cfg.tropism is not None
    target = unit(np.asarray(cfg.tropism if bends else (0.0, -1.0, 0.0), float))
    defaults = np.array([cfg.angle, cfg.step, width0, cfg.width_factor, float(bends)])
    n_draw = int(np.count_nonzero(_DRAW[ls.sym]))
    *out, fault = walk(ls.sym, ls.nparams, ls.offsets, ls.params, defaults, INITIAL_FRAME, target, record, n_draw)
    if fault[0]:
        message = "']' without a matching '['" if fault[0] == 1 else "'[' is never closed"
        raise brackets.BracketError(message, int(fault[1]))
    return _Walk(*out)


def module_positions(ls: LString, cfg: TurtleConfig | None = None) -> np.ndarray:
    """Where the turtle is when it reaches each module (n, 3): for regions, overlays and picking."""
    return _walk(ls, cfg or TurtleConfig(), np.ones(len(ls), bool)).position


def interpret(ls: LString, cfg: TurtleConfig | None = None, probes: np.ndarray | None = None) -> TurtleResult:
    """Interpret an L-string with the 3D turtle; returns segments and leaf/blossom instances.

    ``probes`` (module indices) also returns the turtle's position and frame going into those modules
    (buds and apices, for light and phototropism) and what every module grows from.
    """
    cfg = cfg or TurtleConfig()
    record = _INSTANCE[ls.sym]
    idx = np.zeros(0, np.int64) if probes is None else np.asarray(probes, dtype=np.int64)
    record[idx] = True
    walked = _walk(ls, cfg, record)
    segs = _segments(ls, walked, cfg)
    _radii(ls, segs, cfg)
    leaf_size = cfg.leaf_size if cfg.leaf_size is not None else _auto_leaf_size(segs)
    leaves = _instances(ls, LEAF, walked, leaf_size)
    tips = cfg.leaves_at_tips if cfg.leaves_at_tips is not None else (0 if len(leaves) else 3)
    if tips:
        leaves = _concat_leaves(leaves, _tip_leaves(segs, tips, leaf_size))
    blossoms = _instances(ls, BLOSSOM, walked, leaf_size)
    fruits = _instances(ls, FRUIT, walked, leaf_size)
    result = TurtleResult(segs, leaves, blossoms, fruits, nearest_move=walked.nearest_move)
    if probes is not None:
        position, frames = walked.states_in(idx)
        result.probes = Leaves(position, frames, np.zeros(len(idx)), idx)
    return result


def _radii(ls: LString, segs: Segments, cfg: TurtleConfig) -> None:
    """Pipe-model radii where the config asks for them (by default when the string has no '!')."""
    use_pipe = cfg.pipe_model if cfg.pipe_model is not None else not np.any(ls.sym == ord("!"))
    if use_pipe:
        tip_r = 0.5 * cfg.width * cfg.width_scale if cfg.width is not None else 0.08 * _mean_tip_length(segs)
        apply_pipe_model(ls, segs, tip_r, cfg.pipe_exponent)


def unit(v: np.ndarray) -> np.ndarray:
    """Vectors along the last axis scaled to length 1 (zero vectors stay zero)."""
    return v / np.maximum(np.linalg.norm(v, axis=-1, keepdims=True), 1e-300)


def _segments(ls: LString, walked: _Walk, cfg: TurtleConfig) -> Segments:
    """One row per drawn module, and whether it continues the axis of the piece it grows from."""
    idx = np.flatnonzero(_DRAW[ls.sym])
    radius = 0.5 * walked.width * cfg.width_scale
    start, end, parent, depth = walked.start, walked.end, walked.parent, walked.depth
    pp = np.maximum(parent, 0)
    continues = (parent >= 0) & (depth == depth[pp])
    if np.any(ls.sym == ord("f")):  # an 'f' between a piece and its parent leaves a gap: a new axis
        scale = 1e-9 * (1.0 + np.abs(end).max(initial=0.0))
        gap = start - end[pp]
        continues &= np.einsum("ni,ni->n", gap, gap) <= scale * scale
    radius_end = radius.copy()
    cont = np.flatnonzero(continues)
    radius_end[parent[cont]] = radius[cont]
    return Segments(start, end, radius, radius_end, walked.frame, depth, idx, parent, continues, walked.colour)


def subtree_sums(ls: LString, segs: Segments, values: np.ndarray, ends: np.ndarray | None = None) -> np.ndarray:
    """For every segment, the sum of ``values`` (one per segment) over it and all segments above it.

    A bracketed string lists a segment's descendants right after it, up to the ']' closing its branch,
    so subtree sums are differences of one cumulative sum (no per-segment loop). ``ends``: the segments'
    :func:`subtree_ends`, when several sums over one string are taken (they cost a bracket pass each).
    """
    n = len(ls)
    subtree_end = subtree_ends(ls, segs) if ends is None else ends
    per_module = np.zeros(n + 1)
    per_module[segs.module] = values
    cum = np.cumsum(per_module)
    return cum[subtree_end - 1] - cum[segs.module] + per_module[segs.module]


def subtree_ends(ls: LString, segs: Segments) -> np.ndarray:
    """Per segment, the index of the ']' closing its branch (``len(ls)`` on the main axis): where the
    modules growing from it end."""
    return brackets.branch_ends(ls.sym, segs.module)


def set_radii(segs: Segments, radius: np.ndarray) -> None:
    """Give segments their start radii; end radii follow the next segment of the same axis."""
    segs.radius = radius
    segs.radius_end = radius.copy()
    cont = np.flatnonzero(segs.continues)
    segs.radius_end[segs.parent[cont]] = radius[cont]


def apply_pipe_model(ls: LString, segs: Segments, tip_radius: float, exponent: float = 2.0) -> None:
    """Set radii by the pipe model: each segment carries the pipes of all tips above it."""
    if len(segs) == 0:
        return
    is_tip = np.zeros(len(segs))
    is_tip[tip_segments(segs)] = 1.0
    tips = subtree_sums(ls, segs, is_tip)
    set_radii(segs, tip_radius * np.maximum(tips, 1.0) ** (1.0 / exponent))


def _instances(ls: LString, symbol: int, walked: _Walk, default_size: float) -> Leaves:
    """Leaf or blossom modules as instances at the turtle's state going into them."""
    rows = np.flatnonzero(ls.sym[walked.recorded] == symbol)
    idx = walked.recorded[rows]
    position, frames = np.take(walked.position, rows, axis=0), np.take(walked.rec_frame, rows, axis=0)
    return Leaves(position, frames, _first_param(ls, idx, default_size), idx)


def tip_segments(segs: Segments) -> np.ndarray:
    """Indices of segments that carry no other segment."""
    children = np.bincount(segs.parent[segs.parent >= 0], minlength=len(segs))
    return np.flatnonzero(children == 0)


def _mean_tip_length(segs: Segments) -> float:
    tips = tip_segments(segs)
    if len(tips) == 0:
        return 1.0
    gap = np.take(segs.end, tips, axis=0) - np.take(segs.start, tips, axis=0)
    length = float(np.sqrt(np.einsum("ij,ij->i", gap, gap)).mean())
    return length if length > 0 else 1.0


def _auto_leaf_size(segs: Segments) -> float:
    """Leaves sized to the twigs that carry them, and never lost in a big crown."""
    ys = segs.end[:, 1]
    height = float(ys.max() - ys.min()) if len(segs) else 0.0
    return max(0.8 * _mean_tip_length(segs), 0.025 * height)


def _tip_leaves(segs: Segments, k: int, size: float) -> Leaves:
    """A cluster of ``k`` leaves at the end of every segment with no child (the tamagotchi thesis added them at ']').

    Leaf i of a tip is rolled i/k of a turn about the twig (plus a per-tip offset) and pitched 40 deg
    away from it. With the twig's frame (H, L, U) and side = cos r L + sin r U, the leaf's frame is
    H' = cos p H + sin p side, U' = -sin p H + cos p side, L' = U' x H' = sin r L - cos r U.
    """
    from arbor.engine.geometry.turtle_kernel import tip_leaves

    tips = tip_segments(segs)
    position, frames = tip_leaves(segs.frame, segs.end, segs.module, tips, k)
    return Leaves(position, frames, np.full(len(position), size), np.repeat(segs.module[tips], k))


def _concat_leaves(a: Leaves, b: Leaves) -> Leaves:
    if len(a) == 0 or len(b) == 0:
        return b if len(a) == 0 else a
    return Leaves(*(np.concatenate([getattr(a, f), getattr(b, f)]) for f in ("position", "frame", "size", "module")))
