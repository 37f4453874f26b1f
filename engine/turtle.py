"""Vectorised 3D turtle interpretation of an L-string (ABOP conventions, Y up).

The turtle state is a frame R (columns H, L, U: heading, left, up) and a position p. Every module is a
local transform M_i (a rotation and a move along its own heading); the state after module i is the
state after its *predecessor* composed with M_i. The predecessor is the previous module, except that
after ']' it is the matching '[' (whose transform is the identity): so states are prefix products
along a tree of parent pointers, computed for all modules at once by pointer jumping in O(n log n).

Symbols: F G (move, draw), f (move), + - (turn about U), & ^ (pitch about L), / \\ (roll about H),
| (turn around), $ (roll so L is horizontal), T(a) (bend a degrees towards the tropism vector),
[ ] (push, pop), !(w) (width; bare '!' shrinks it),
'(c) (colour index; bare ' increments it), L (leaf) and K (blossom) with an optional size.
A missing parameter takes the default from the .lsys source (angle, step, width).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from engine import brackets
from engine.chains import chain_compose, chain_sum
from engine.lstring import LString

WORLD_UP = np.array([0.0, 1.0, 0.0])
# Initial frame: heading up (+Y), left -X, up +Z (H x L = U, right-handed).
INITIAL_FRAME = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])

_DRAW = np.zeros(256, bool)
_DRAW[[ord("F"), ord("G")]] = True
_MOVE = _DRAW.copy()
_MOVE[ord("f")] = True
_ROT_AXIS = {ord("+"): (2, 1), ord("-"): (2, -1), ord("&"): (1, 1), ord("^"): (1, -1), ord("/"): (0, 1),
             ord("\\"): (0, -1)}
LEAF, BLOSSOM = ord("L"), ord("K")
ROLL_LEVEL = ord("$")
TROPISM = ord("T")
_TURNLIKE = np.zeros(256, bool)
_TURNLIKE[[ord(c) for c in "+-&^/\\|$!'T"]] = True


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

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """Axis-aligned bounds of all segment end points and leaves."""
        pts = [self.segments.start, self.segments.end, self.leaves.position, self.blossoms.position]
        allp = np.concatenate([p for p in pts if len(p)] or [np.zeros((1, 3))])
        return allp.min(axis=0), allp.max(axis=0)


def _axis_rotations(axis: int, angles_deg: np.ndarray) -> np.ndarray:
    """Rotation matrices about local axis 0 (H), 1 (L) or 2 (U) by the given angles."""
    a = np.radians(angles_deg)
    c, s = np.cos(a), np.sin(a)
    m = np.zeros((len(a), 3, 3))
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    m[:, axis, axis] = 1.0
    m[:, i, i] = c
    m[:, j, j] = c
    m[:, j, i] = s
    m[:, i, j] = -s
    return m


def _first_param(ls: LString, idx: np.ndarray, default: float) -> np.ndarray:
    has = ls.nparams[idx] > 0
    out = np.full(len(idx), default, dtype=np.float64)
    out[has] = ls.params[ls.offsets[idx[has]]]
    return out


def _local_transforms(ls: LString, cfg: TurtleConfig):
    """Per-module local rotation (n,3,3), move length (n,), width map (a, b) and colour map (a, b)."""
    n = len(ls)
    rot = np.broadcast_to(np.eye(3), (n, 3, 3)).copy()
    for sym, (axis, sign) in _ROT_AXIS.items():
        idx = np.flatnonzero(ls.sym == sym)
        if len(idx):
            rot[idx] = _axis_rotations(axis, sign * _first_param(ls, idx, cfg.angle))
    turn = np.flatnonzero(ls.sym == ord("|"))
    rot[turn] = _axis_rotations(2, np.full(len(turn), 180.0))
    move = np.zeros(n)
    idx = np.flatnonzero(_MOVE[ls.sym])
    move[idx] = _first_param(ls, idx, cfg.step)
    width = _affine_maps(ls, ord("!"), lambda k: (cfg.width_factor, 0.0))
    colour = _affine_maps(ls, ord("'"), lambda k: (1.0, 1.0))
    return rot, move, width, colour


def _affine_maps(ls: LString, symbol: int, bare) -> np.ndarray:
    """Scalar state updates as affine maps x -> a x + b: '!(w)' sets (a=0, b=w), bare '!' scales."""
    n = len(ls)
    ab = np.zeros((n, 2))
    ab[:, 0] = 1.0
    idx = np.flatnonzero(ls.sym == symbol)
    has = ls.nparams[idx] > 0
    set_idx = idx[has]
    ab[set_idx, 0] = 0.0
    ab[set_idx, 1] = ls.params[ls.offsets[set_idx]]
    a, b = bare(None)
    ab[idx[~has]] = (a, b)
    return ab


def predecessors(sym: np.ndarray) -> np.ndarray:
    """For each module, the module whose output state is its input state (-1 for the first)."""
    n = len(sym)
    par = np.arange(n, dtype=np.int64) - 1
    partner = brackets.match(sym)
    after_close = np.flatnonzero(sym[:-1] == brackets.CLOSE) + 1
    par[after_close] = partner[after_close - 1]
    return par


def module_positions(ls: LString, cfg: TurtleConfig | None = None) -> np.ndarray:
    """Where the turtle is when it reaches each module (n, 3): for regions, overlays and picking."""
    cfg = cfg or TurtleConfig()
    brackets.check_balanced(ls.sym)
    rot, move, width, colour = _local_transforms(ls, cfg)
    states = _solve_states(ls, predecessors(ls.sym), rot, move, np.stack([width, colour], axis=1), cfg.tropism)
    return states.state_in(np.arange(len(ls)))[1]


def interpret(ls: LString, cfg: TurtleConfig | None = None) -> TurtleResult:
    """Interpret an L-string with the 3D turtle; returns segments and leaf/blossom instances."""
    cfg = cfg or TurtleConfig()
    brackets.check_balanced(ls.sym)
    rot, move, width, colour = _local_transforms(ls, cfg)
    scalars = np.stack([width, colour], axis=1)
    par = predecessors(ls.sym)
    states = _solve_states(ls, par, rot, move, scalars, cfg.tropism)
    want = np.flatnonzero(_DRAW[ls.sym] | (ls.sym == LEAF) | (ls.sym == BLOSSOM))
    in_frame, in_pos, in_sc = states.state_in(want)
    out_pos = states.move_out_pos()
    width0 = 1.0 if cfg.width is None else cfg.width
    widths = (in_sc[:, 0, 0] * width0 + in_sc[:, 0, 1]) * cfg.width_scale
    colours = in_sc[:, 1, 1]  # colour index starts at 0
    segs = _segments(ls, par, want, in_frame, in_pos, out_pos, widths, colours, states)
    use_pipe = cfg.pipe_model if cfg.pipe_model is not None else not np.any(ls.sym == ord("!"))
    if use_pipe:
        tip_r = 0.5 * cfg.width * cfg.width_scale if cfg.width is not None else 0.08 * _mean_tip_length(segs)
        apply_pipe_model(ls, segs, tip_r, cfg.pipe_exponent)
    leaf_size = cfg.leaf_size if cfg.leaf_size is not None else _auto_leaf_size(segs)
    leaves = _instances(ls, LEAF, want, in_frame, in_pos, leaf_size)
    tips = cfg.leaves_at_tips if cfg.leaves_at_tips is not None else (0 if len(leaves) else 3)
    if tips:
        leaves = _concat_leaves(leaves, _tip_leaves(segs, tips, leaf_size))
    blossoms = _instances(ls, BLOSSOM, want, in_frame, in_pos, leaf_size)
    return TurtleResult(segs, leaves, blossoms)


@dataclass
class _States:
    """Turtle states solved in two levels: short runs of turns between moves, then moves only."""

    is_move: np.ndarray  # (n,) bool
    move_idx: np.ndarray  # module index of each move
    base: np.ndarray  # (n,) nearest move strictly before each module on its path (-1 none)
    before: np.ndarray  # (n,) nearest turn-like module strictly before, if after base (-1 none)
    compact: np.ndarray  # (n,) index of a module within its own class (turns or moves)
    turn_r: np.ndarray  # accumulated rotation of each turn since its base
    turn_s: np.ndarray  # accumulated scalar maps of each turn since its base
    move_r: np.ndarray  # world frame after each move
    move_t: np.ndarray  # world position after each move
    move_s: np.ndarray  # scalar maps after each move

    def _before_maps(self, idx: np.ndarray):
        b = self.before[idx]
        has = b >= 0
        r = np.broadcast_to(np.eye(3), (len(idx), 3, 3)).copy()
        s = np.zeros((len(idx), 2, 2))
        s[:, :, 0] = 1.0
        r[has] = self.turn_r[self.compact[b[has]]]
        s[has] = self.turn_s[self.compact[b[has]]]
        return r, s

    def state_in(self, idx: np.ndarray):
        """World frame, position and scalar maps going *into* the modules ``idx``."""
        r, s = self._before_maps(idx)
        base = self.base[idx]
        has = base >= 0
        frame = np.matmul(INITIAL_FRAME, r)
        pos = np.zeros((len(idx), 3))
        m = self.compact[base[has]]
        frame[has] = np.matmul(self.move_r[m], r[has])
        pos[has] = self.move_t[m]
        ms = self.move_s[m]
        s_has = s[has]
        out_s = s.copy()
        out_s[has, :, 1] = s_has[:, :, 0] * ms[:, :, 1] + s_has[:, :, 1]
        out_s[has, :, 0] = s_has[:, :, 0] * ms[:, :, 0]
        return frame, pos, out_s

    def move_out_pos(self) -> np.ndarray:
        """World position after each move module (indexed like ``move_idx``)."""
        return self.move_t


def _solve_states(ls, par, rot, move, scalars, tropism: np.ndarray | None = None) -> _States:
    """Solve all turtle states. '$' and 'T' turn by amounts that depend on the incoming heading, so
    they are found by repeated passes, one per nesting level of such modules along a path."""
    rolls = np.flatnonzero(ls.sym == ROLL_LEVEL)
    bends = np.flatnonzero(ls.sym == TROPISM) if tropism is not None else np.zeros(0, np.int64)
    special = np.concatenate([rolls, bends])
    angles = _first_param(ls, bends, 0.0) if len(bends) else np.zeros(0)
    for _ in range(64):
        states = _solve_once(ls, par, rot, move, scalars)
        if len(special) == 0:
            break
        frames_in, _, _ = states.state_in(special)
        new = np.concatenate([_level_rolls(frames_in[: len(rolls)]),
                              _tropism_turns(frames_in[len(rolls):], tropism, angles)])
        if np.allclose(new, rot[special], atol=1e-12):
            break
        rot[special] = new
    return states


def _tropism_turns(frames_in: np.ndarray, direction: np.ndarray | None, angles: np.ndarray) -> np.ndarray:
    """Local rotations for 'T(a)': turn the heading by a degrees towards the world vector ``direction``
    (about H x direction), never past it (ABOP's tropism, applied where the string asks for it)."""
    if len(frames_in) == 0:
        return np.zeros((0, 3, 3))
    h = unit(frames_in[:, :, 0])
    target = unit(np.asarray(direction, float))
    axis = np.cross(h, target)
    sin = np.linalg.norm(axis, axis=1)
    between = np.degrees(np.arctan2(sin, h @ target))
    turn = np.radians(np.clip(angles, -between, between))
    k = np.where((sin > 1e-9)[:, None], axis / np.maximum(sin, 1e-12)[:, None], frames_in[:, :, 1])
    c, s = np.cos(turn), np.sin(turn)
    kx = np.zeros((len(k), 3, 3))
    kx[:, 0, 1], kx[:, 0, 2], kx[:, 1, 2] = -k[:, 2], k[:, 1], -k[:, 0]
    kx[:, 1, 0], kx[:, 2, 0], kx[:, 2, 1] = k[:, 2], -k[:, 1], k[:, 0]
    world = np.eye(3) + s[:, None, None] * kx + (1 - c)[:, None, None] * np.matmul(kx, kx)
    local = np.matmul(np.transpose(frames_in, (0, 2, 1)), np.matmul(world, frames_in))
    return _orthonormal(local)


def _solve_once(ls, par, rot, move, scalars) -> _States:
    n = len(ls)
    is_move = _MOVE[ls.sym]
    is_turn = ~is_move & _TURNLIKE[ls.sym]
    base = brackets.first_good(par, is_move)
    near = brackets.first_good(par, is_move | is_turn)
    before = np.where((near >= 0) & ~is_move[np.maximum(near, 0)], near, -1)
    compact = np.full(n, -1, dtype=np.int64)
    turn_idx = np.flatnonzero(is_turn)
    move_idx = np.flatnonzero(is_move)
    compact[turn_idx] = np.arange(len(turn_idx))
    compact[move_idx] = np.arange(len(move_idx))
    tpar = np.where(before[turn_idx] >= 0, compact[np.maximum(before[turn_idx], 0)], -1)
    turn_r, turn_s = chain_compose(tpar, rot[turn_idx], scalars[turn_idx])
    states = _States(is_move, move_idx, base, before, compact, turn_r, turn_s,
                     np.zeros((0, 3, 3)), np.zeros((0, 3)), np.zeros((0, 2, 2)))
    r_before, s_before = states._before_maps(move_idx)
    mpar = np.where(base[move_idx] >= 0, compact[np.maximum(base[move_idx], 0)], -1)
    acc_r, acc_s = chain_compose(mpar, r_before, s_before)
    states.move_r = np.matmul(INITIAL_FRAME, acc_r)
    states.move_t = _move_positions(mpar, states.move_r, move[move_idx])
    states.move_s = acc_s
    return states


def _move_positions(mpar: np.ndarray, frames: np.ndarray, length: np.ndarray) -> np.ndarray:
    """World end position of each move: the sum of step vectors along its chain of moves."""
    return chain_sum(mpar, frames[:, :, 0] * length[:, None])


def _level_rolls(frames_in: np.ndarray) -> np.ndarray:
    """Local roll about H that makes L horizontal (ABOP '$'): L' = (V x H)/|V x H|.

    The result is re-orthonormalised: '$' often repeats along an axis (dozens of times on a long
    branch), and any drift from a true rotation would compound.
    """
    h = unit(frames_in[:, :, 0])
    lft = np.cross(WORLD_UP, h)
    norm = np.linalg.norm(lft, axis=1)
    ok = norm > 1e-9
    lft[ok] /= norm[ok, None]
    lft[~ok] = unit(frames_in[~ok, :, 1])
    target = np.stack([h, lft, np.cross(h, lft)], axis=2)
    return _orthonormal(np.matmul(np.transpose(frames_in, (0, 2, 1)), target))


def unit(v: np.ndarray) -> np.ndarray:
    """Vectors along the last axis scaled to length 1 (zero vectors stay zero)."""
    return v / np.maximum(np.linalg.norm(v, axis=-1, keepdims=True), 1e-300)


def _orthonormal(m: np.ndarray) -> np.ndarray:
    """Gram-Schmidt on the columns: the nearest proper rotation for matrices that almost are."""
    c0 = unit(m[:, :, 0])
    c1 = m[:, :, 1] - np.einsum("ni,ni->n", c0, m[:, :, 1])[:, None] * c0
    c1 = unit(c1)
    return np.stack([c0, c1, np.cross(c0, c1)], axis=2)


def _segments(ls, par, want, in_frame, in_pos, move_end, widths, colours, states: _States) -> Segments:
    draw = _DRAW[ls.sym[want]]
    idx = want[draw]
    start, frame = in_pos[draw], in_frame[draw]
    end = move_end[states.compact[idx]]
    seg_of_module = np.full(len(ls), -1, dtype=np.int64)
    seg_of_module[idx] = np.arange(len(idx))
    ancestor = brackets.first_good(par, _DRAW[ls.sym])[idx]
    parent = np.where(ancestor >= 0, seg_of_module[np.maximum(ancestor, 0)], -1)
    depth = brackets.depths(ls.sym)[idx]
    pp = np.maximum(parent, 0)
    scale = 1e-9 * (1.0 + np.abs(end).max(initial=0.0))
    joined = np.einsum("ni,ni->n", start - end[pp], start - end[pp]) <= scale * scale
    continues = (parent >= 0) & (depth == depth[pp]) & joined
    radius = 0.5 * widths[draw]
    radius_end = radius.copy()
    cont = np.flatnonzero(continues)
    radius_end[parent[cont]] = radius[cont]
    return Segments(start, end, radius, radius_end, frame, depth, idx, parent, continues, colours[draw])


def subtree_sums(ls: LString, segs: Segments, values: np.ndarray) -> np.ndarray:
    """For every segment, the sum of ``values`` (one per segment) over it and all segments above it.

    A bracketed string lists a segment's descendants right after it, up to the ']' closing its branch,
    so subtree sums are differences of one cumulative sum (no per-segment loop).
    """
    n = len(ls)
    partner = brackets.match(ls.sym)
    encl = brackets.enclosing_open(ls.sym)[segs.module]
    subtree_end = np.where(encl >= 0, partner[np.maximum(encl, 0)], n)
    per_module = np.zeros(n + 1)
    per_module[segs.module] = values
    cum = np.cumsum(per_module)
    return cum[subtree_end - 1] - cum[segs.module] + per_module[segs.module]


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


def _instances(ls: LString, symbol: int, want, in_frame, in_pos, default_size: float) -> Leaves:
    sel = ls.sym[want] == symbol
    idx = want[sel]
    return Leaves(in_pos[sel], in_frame[sel], _first_param(ls, idx, default_size), idx)


def tip_segments(segs: Segments) -> np.ndarray:
    """Indices of segments that carry no other segment."""
    children = np.bincount(segs.parent[segs.parent >= 0], minlength=len(segs))
    return np.flatnonzero(children == 0)


def _mean_tip_length(segs: Segments) -> float:
    tips = tip_segments(segs)
    if len(tips) == 0:
        return 1.0
    length = float(np.linalg.norm(segs.end[tips] - segs.start[tips], axis=1).mean())
    return length if length > 0 else 1.0


def _auto_leaf_size(segs: Segments) -> float:
    """Leaves sized to the twigs that carry them, and never lost in a big crown."""
    height = float(np.ptp(segs.end[:, 1])) if len(segs) else 0.0
    return max(0.8 * _mean_tip_length(segs), 0.025 * height)


def _tip_leaves(segs: Segments, k: int, size: float) -> Leaves:
    """A cluster of ``k`` leaves at the end of every segment with no child (seed 003 added them at ']').

    Leaf i of a tip is rolled i/k of a turn about the twig (plus a per-tip offset) and pitched 40 deg
    away from it; the frame is built from vectors, not matrix products, since tips are numerous.
    """
    tips = tip_segments(segs)
    tip = np.repeat(tips, k)
    j = np.tile(np.arange(k), len(tips))
    roll = np.radians(j * (360.0 / k) + (segs.module[tip] * 37 % 360))[:, None]
    h, lft, up = (segs.frame[tip][:, :, c] for c in range(3))
    side = np.cos(roll) * lft + np.sin(roll) * up
    cp, sp = np.cos(np.radians(40.0)), np.sin(np.radians(40.0))
    new_h = cp * h + sp * side
    new_u = -sp * h + cp * side
    new_l = np.cross(new_u, new_h)
    frames = np.stack([new_h, new_l, new_u], axis=2)
    return Leaves(segs.end[tip], frames, np.full(len(tip), size), segs.module[tip])


def _concat_leaves(a: Leaves, b: Leaves) -> Leaves:
    return Leaves(*(np.concatenate([getattr(a, f), getattr(b, f)]) for f in ("position", "frame", "size", "module")))
