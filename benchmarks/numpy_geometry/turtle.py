"""The level-scan numpy turtle as it was before engine/geometry/turtle_kernel.py (the peer only)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from arbor.engine.geometry.turtle import (  # what did not change is the engine's own
    Leaves,
    Segments,
    TurtleConfig,
    TurtleResult,
    _auto_leaf_size,
    _concat_leaves,
    _first_param,
    _radii,
    tip_segments,
    unit,
)
from arbor.engine.lsystem import brackets
from arbor.engine.lsystem.lstring import LString
from benchmarks.numpy_geometry.chains import (
    Levels,
    compose_maps,
    compose_turtle,
    quat_entries,
    quat_mul,
    rows_to_quat,
    to_rows,
)

WORLD_UP = np.array([0.0, 1.0, 0.0])
# Initial frame: heading up (+Y), left -X, up +Z (H x L = U, right-handed).
INITIAL_FRAME = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])

_DRAW = np.zeros(256, bool)
_DRAW[[ord("F"), ord("G")]] = True
_MOVE = _DRAW.copy()
_MOVE[ord("f")] = True
_ROT_AXIS = {ord("+"): (2, 1), ord("-"): (2, -1), ord("&"): (1, 1), ord("^"): (1, -1), ord("/"): (0, 1),
             ord("\\"): (0, -1)}
_AXIS_OF = np.full(256, -1)
_SIGN_OF = np.zeros(256)
for _code, (_axis, _sign) in _ROT_AXIS.items():
    _AXIS_OF[_code], _SIGN_OF[_code] = _axis, _sign
LEAF, BLOSSOM, FRUIT = ord("L"), ord("K"), ord("O")
ROLL_LEVEL = ord("$")
TROPISM = ord("T")
_TURNLIKE = np.zeros(256, bool)
_TURNLIKE[[ord(c) for c in "+-&^/\\|$!'T"]] = True
_COS_DEG, _SIN_DEG = np.cos(np.radians(np.arange(360))), np.sin(np.radians(np.arange(360)))


def _axis_quaternions(axis: int, angles_deg: np.ndarray) -> np.ndarray:
    """Rotations about local axis 0 (H), 1 (L) or 2 (U) by the given angles, as quaternion rows (4, k)."""
    half = np.radians(angles_deg) / 2
    q = np.zeros((4, len(half)))
    q[0] = np.cos(half)
    q[1 + axis] = np.sin(half)
    return q


# Rows of a turn block: rotation as a quaternion (0-3), width map a, b (4, 5), colour map a, b (6, 7).
_WIDTH, _COLOUR = 4, 6
_BLOCK = 8
_IDENTITY = np.array([1.0, 0, 0, 0, 1, 0, 1, 0])[:, None]
assert np.array_equal(np.abs(INITIAL_FRAME).sum(axis=1), np.ones(3))  # a signed permutation (_world_frames)


def _turn_blocks(ls: LString, cfg: TurtleConfig, turn_idx: np.ndarray) -> np.ndarray:
    """Local rotation and scalar maps of every turn-like module, as (8, t + 1) column blocks (the last
    column: no turn)."""
    blocks = np.empty((_BLOCK, len(turn_idx) + 1))
    blocks[:] = _IDENTITY
    sym = ls.sym[turn_idx]
    k = np.flatnonzero(_AXIS_OF[sym] >= 0)  # all turns, pitches and rolls at once
    half = np.radians(_SIGN_OF[sym[k]] * _first_param(ls, turn_idx[k], cfg.angle)) / 2
    blocks[0, k] = np.cos(half)
    blocks[1 + _AXIS_OF[sym[k]], k] = np.sin(half)
    k = np.flatnonzero(sym == ord("|"))
    blocks[:4, k] = _axis_quaternions(2, np.full(len(k), 180.0))
    _affine_rows(ls, turn_idx, sym == ord("!"), blocks[_WIDTH:_WIDTH + 2], cfg.width_factor)
    _affine_rows(ls, turn_idx, sym == ord("'"), blocks[_COLOUR:_COLOUR + 2], None)
    return blocks


def _affine_rows(ls: LString, turn_idx: np.ndarray, sel: np.ndarray, rows: np.ndarray, factor) -> None:
    """Scalar updates as maps x -> a x + b: 'S(w)' sets (a=0, b=w); a bare one scales by ``factor``
    (width) or adds 1 (colour, ``factor`` None)."""
    k = np.flatnonzero(sel)
    has = ls.nparams[turn_idx[k]] > 0
    rows[0, k[has]] = 0.0
    rows[1, k[has]] = ls.params[ls.offsets[turn_idx[k[has]]]]
    rows[:, k[~has]] = [[factor], [0.0]] if factor is not None else [[1.0], [1.0]]


def predecessors(sym: np.ndarray, depth: np.ndarray | None = None) -> np.ndarray:
    """For each module, the module whose output state is its input state (-1 for the first);
    ``depth``: the bracket depths, when the caller has them."""
    n = len(sym)
    par = np.arange(n, dtype=np.int64) - 1
    partner = brackets.match(sym, depth)
    after_close = np.flatnonzero(sym[:-1] == brackets.CLOSE) + 1
    par[after_close] = partner[after_close - 1]
    return par


def interpret(ls: LString, cfg: TurtleConfig | None = None, probes: np.ndarray | None = None) -> TurtleResult:
    """Interpret an L-string with the 3D turtle; returns segments and leaf/blossom instances.

    ``probes`` (module indices) also returns the turtle's position and frame going into those modules
    (buds and apices, for light and phototropism) and what every module grows from.
    """
    cfg = cfg or TurtleConfig()
    depth = brackets.check_balanced(ls.sym)
    states = _solve_states(ls, cfg, predecessors(ls.sym, depth))
    segs = _segments(ls, states, cfg, depth)
    _radii(ls, segs, cfg)
    leaf_size = cfg.leaf_size if cfg.leaf_size is not None else _auto_leaf_size(segs)
    leaves = _instances(ls, LEAF, states, leaf_size)
    tips = cfg.leaves_at_tips if cfg.leaves_at_tips is not None else (0 if len(leaves) else 3)
    if tips:
        leaves = _concat_leaves(leaves, _tip_leaves(segs, tips, leaf_size))
    blossoms = _instances(ls, BLOSSOM, states, leaf_size)
    fruits = _instances(ls, FRUIT, states, leaf_size)
    result = TurtleResult(segs, leaves, blossoms, fruits, nearest_move=states.topo.nearest_move)
    if probes is not None:
        idx = np.asarray(probes, dtype=np.int64)
        frames = _world_frames(states.blocks_in(idx)[:4])
        result.probes = Leaves(states.positions_in(idx).T, frames, np.zeros(len(idx)), idx)
    return result


@dataclass
class _Topology:
    """Which turns and moves follow which: fixed for a string, whatever the angles turn out to be."""

    turn_idx: np.ndarray  # module index of each turn column
    move_idx: np.ndarray  # module index of each move column
    turn_levels: Levels
    move_levels: Levels
    nearest_move: np.ndarray  # (n,) the nearest move strictly before each module on its path (-1 none)
    nearest_turn: np.ndarray  # (n,) the nearest turn strictly before, if after that move (-1 none)
    column: np.ndarray  # (n,) column of each turn or move module among its kind (-1 for others)

    @classmethod
    def of(cls, ls: LString, par: np.ndarray) -> _Topology:
        """Nearest moves and turns on each module's path, and the level order of both forests."""
        n = len(ls)
        is_move = _MOVE[ls.sym]
        is_turn = ~is_move & _TURNLIKE[ls.sym]
        near = first_good(par, is_move | is_turn)
        after_turn = (near >= 0) & is_turn[np.maximum(near, 0)]
        nearest_turn = np.where(after_turn, near, -1)
        turn_idx, move_idx = np.flatnonzero(is_turn), np.flatnonzero(is_move)
        column = np.full(n, -1, dtype=np.int64)
        column[turn_idx] = np.arange(len(turn_idx))  # for now: index among its kind
        column[move_idx] = np.arange(len(move_idx))
        tpar = _columns(nearest_turn[turn_idx], column, -1)
        turn_levels = Levels.of(tpar)
        # a run of turns starts right after a move (or at the start): its first turn's nearest module
        # is that move, and the whole run shares it
        run_move = turn_levels.scan(near[turn_idx[turn_levels.order]][None], lambda p, c: p)[0]
        move_of_turn = np.empty(len(turn_idx), np.int64)
        move_of_turn[turn_levels.order] = run_move
        nearest_move = near.copy()
        nearest_move[after_turn] = move_of_turn[column[near[after_turn]]]
        mpar = _columns(nearest_move[move_idx], column, -1)
        move_levels = Levels.of(mpar)
        column[turn_idx] = turn_levels.where
        column[move_idx] = move_levels.where
        return cls(turn_idx[turn_levels.order], move_idx[move_levels.order], turn_levels, move_levels,
                   nearest_move, nearest_turn, column)

    def base(self, idx: np.ndarray) -> np.ndarray:
        """Column of the nearest move before each of the modules ``idx`` (m: none)."""
        return _columns(self.nearest_move[idx], self.column, len(self.move_idx))

    def before(self, idx: np.ndarray) -> np.ndarray:
        """Column of the nearest turn before each of the modules ``idx`` after that move (t: none)."""
        return _columns(self.nearest_turn[idx], self.column, len(self.turn_idx))


@dataclass
class _States:
    """Turtle states solved in two levels: short runs of turns between moves, then moves only.

    Rotations are unit quaternions relative to the initial frame (4 numbers to compose, not 9).
    Turns and moves are stored column-wise (see engine.geometry.chains) in the level order of their own
    forests, each with one extra last column: the state before anything happened (identity turn;
    initial frame at the origin), which modules with no turn or move before them point to.
    """

    topo: _Topology
    move_parent: np.ndarray  # column of the move before each move column (m: none)
    turns: np.ndarray  # (8, t + 1) accumulated rotation and scalar maps of each turn since its move
    moves: np.ndarray  # (8, m + 1) frame (from the initial one) and scalar maps into and out of each move
    move_t: np.ndarray  # (3, m + 1) world position after each move

    def blocks_in(self, idx: np.ndarray) -> np.ndarray:
        """World frame (quaternion rows) and scalar maps going *into* the modules ``idx``: (8, k)."""
        b, t = self.topo.base(idx), self.topo.before(idx)
        out = np.empty((_BLOCK, len(idx)))
        quat_mul(self.moves[:4, b], self.turns[:4, t], out[:4])
        compose_maps(self.moves[4:, b], self.turns[4:, t], out[4:])
        return out

    def positions_in(self, idx: np.ndarray) -> np.ndarray:
        """World positions going into the modules ``idx``: (3, k)."""
        return self.move_t[:, self.topo.base(idx)]


def _solve_states(ls: LString, cfg: TurtleConfig, par: np.ndarray) -> _States:
    """Solve all turtle states. '$' and 'T' turn by amounts that depend on the incoming heading, so
    they are found by repeated passes, one per nesting level of such modules along a path."""
    topo = _Topology.of(ls, par)
    blocks = _turn_blocks(ls, cfg, topo.turn_idx)  # in the turns' level order
    rolls = np.flatnonzero(ls.sym == ROLL_LEVEL)
    bends = np.flatnonzero(ls.sym == TROPISM) if cfg.tropism is not None else np.zeros(0, np.int64)
    special = np.concatenate([rolls, bends])
    columns = topo.column[special]
    angles = _first_param(ls, bends, 0.0)
    move_len = _first_param(ls, topo.move_idx, cfg.step)
    for _ in range(64):
        states = _solve_once(topo, blocks, move_len, keep=len(special) > 0)
        if len(special) == 0:
            break
        frames_in = _world_frames(states.blocks_in(special)[:4])
        new = np.concatenate([_level_rolls(frames_in[: len(rolls)]),
                              _tropism_turns(frames_in[len(rolls):], cfg.tropism, angles)])
        new_quat = rows_to_quat(to_rows(new))
        if np.allclose(new_quat, blocks[:4, columns], atol=1e-12):
            break
        blocks[:4, columns] = new_quat
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


def _columns(nearest: np.ndarray, column: np.ndarray, none: int) -> np.ndarray:
    """Column of each module's nearest turn/move (``none`` where there is none)."""
    return np.where(nearest >= 0, column[np.maximum(nearest, 0)], none)


def _solve_once(topo: _Topology, blocks: np.ndarray, move_len: np.ndarray, keep: bool) -> _States:
    """Compose the turn runs, then the moves, each forest level by level in its own column order
    (``keep``: leave ``blocks`` as they are; else they are composed in place)."""
    t, m = len(topo.turn_idx), len(topo.move_idx)
    turns = blocks.copy() if keep else blocks
    topo.turn_levels.scan(turns[:, :t], compose_turtle)
    moves = np.empty((_BLOCK, m + 1))
    moves[:, :m] = np.take(turns, topo.before(topo.move_idx), axis=1)
    topo.move_levels.scan(moves[:, :m], compose_turtle)
    moves[:, m] = _IDENTITY[:, 0]
    move_t = np.zeros((3, m + 1))
    move_t[:, :m] = _headings(moves[:4, :m]) * move_len
    topo.move_levels.scan(move_t[:, :m], np.add)
    parent = topo.move_levels.parent
    return _States(topo, np.where(parent >= 0, parent, m), turns, moves, move_t)


def _headings(q: np.ndarray) -> np.ndarray:
    """World headings (3, k) of turtles turned by quaternion rows (4, k) from the initial frame."""
    w, x, y, z = q
    local = np.stack([1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)])
    return INITIAL_FRAME @ local


def _world_frames(q: np.ndarray) -> np.ndarray:
    """World frames (k, 3, 3) of turtles turned by quaternion rows (4, k) from the initial frame,
    written entry by entry (the initial frame picks and signs rows, so axis-aligned frames are exact)."""
    local = quat_entries(q)
    out = np.empty((q.shape[1], 3, 3))
    for r in range(3):
        source = int(np.argmax(np.abs(INITIAL_FRAME[r])))
        for c in range(3):
            np.multiply(local[source][c], INITIAL_FRAME[r, source], out=out[:, r, c])
    return out


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


def _orthonormal(m: np.ndarray) -> np.ndarray:
    """Gram-Schmidt on the columns: the nearest proper rotation for matrices that almost are."""
    c0 = unit(m[:, :, 0])
    c1 = m[:, :, 1] - np.einsum("ni,ni->n", c0, m[:, :, 1])[:, None] * c0
    c1 = unit(c1)
    return np.stack([c0, c1, np.cross(c0, c1)], axis=2)


def _segments(ls: LString, states: _States, cfg: TurtleConfig, depths: np.ndarray) -> Segments:
    """One row per drawn module. A move's frame and scalar maps going in are those it leaves with."""
    idx = np.flatnonzero(_DRAW[ls.sym])
    m = len(states.move_parent)
    cols = states.topo.column[idx]
    block = np.take(states.moves, cols, axis=1)
    frame = _world_frames(block[:4])
    width0 = 1.0 if cfg.width is None else cfg.width
    radius = 0.5 * (block[_WIDTH] * width0 + block[_WIDTH + 1]) * cfg.width_scale
    colours = block[_COLOUR + 1]  # the colour index starts at 0
    start = np.ascontiguousarray(np.take(states.move_t, states.move_parent[cols], axis=1).T)
    end = np.ascontiguousarray(np.take(states.move_t, cols, axis=1).T)
    draw_col = np.zeros(m, bool)
    draw_col[cols] = True
    seg_of_col = np.full(m, -1, dtype=np.int64)
    seg_of_col[cols] = np.arange(len(idx))
    chain = np.where(states.move_parent < m, states.move_parent, -1)
    # the segment a piece grows from: the nearest drawing move before it ('f' moves are skipped)
    all_draw = bool(draw_col.all())
    ancestor = chain[cols] if all_draw else first_good(chain, draw_col)[cols]
    parent = np.where(ancestor >= 0, seg_of_col[np.maximum(ancestor, 0)], -1)
    depth = depths[idx]
    pp = np.maximum(parent, 0)
    continues = (parent >= 0) & (depth == depth[pp])
    if not all_draw:  # an 'f' between a piece and its parent leaves a gap: a new axis starts there
        scale = 1e-9 * (1.0 + np.abs(end).max(initial=0.0))
        gap = start - end[pp]
        continues &= np.einsum("ni,ni->n", gap, gap) <= scale * scale
    radius_end = radius.copy()
    cont = np.flatnonzero(continues)
    radius_end[parent[cont]] = radius[cont]
    return Segments(start, end, radius, radius_end, frame, depth, idx, parent, continues, colours)


def _instances(ls: LString, symbol: int, states: _States, default_size: float) -> Leaves:
    """Leaf or blossom modules as instances at the turtle's state going into them."""
    idx = np.flatnonzero(ls.sym == symbol)
    frames = _world_frames(states.blocks_in(idx)[:4])
    return Leaves(states.positions_in(idx).T, frames, _first_param(ls, idx, default_size), idx)


def _tip_leaves(segs: Segments, k: int, size: float) -> Leaves:
    """A cluster of ``k`` leaves at the end of every segment with no child (the tamagotchi thesis added them at ']').

    Leaf i of a tip is rolled i/k of a turn about the twig (plus a per-tip offset) and pitched 40 deg
    away from it. With the twig's frame (H, L, U) and side = cos r L + sin r U, the leaf's frame is
    H' = cos p H + sin p side, U' = -sin p H + cos p side, L' = U' x H' = sin r L - cos r U.
    """
    tips = tip_segments(segs)
    frame = np.take(segs.frame, tips, axis=0)
    h, lft, up = frame[:, :, 0].copy(), frame[:, :, 1].copy(), frame[:, :, 2].copy()  # contiguous rows
    offset = segs.module[tips] * 37 % 360  # whole degrees: looked up, not computed per tip
    cos_o, sin_o = _COS_DEG[offset], _SIN_DEG[offset]
    cp, sp = np.cos(np.radians(40.0)), np.sin(np.radians(40.0))
    frames = np.empty((len(tips), k, 3, 3))
    for j in range(k):  # roll r = offset + j/k of a turn, by the angle-sum formulas
        a = np.radians(j * 360.0 / k)
        cos_r = (cos_o * np.cos(a) - sin_o * np.sin(a))[:, None]
        sin_r = (sin_o * np.cos(a) + cos_o * np.sin(a))[:, None]
        side = cos_r * lft + sin_r * up
        frames[:, j, :, 0] = cp * h + sp * side
        frames[:, j, :, 1] = sin_r * lft - cos_r * up
        frames[:, j, :, 2] = cp * side - sp * h
    position = np.repeat(segs.end[tips], k, axis=0)
    return Leaves(position, frames.reshape(-1, 3, 3), np.full(len(position), size), np.repeat(segs.module[tips], k))


def first_good(step: np.ndarray, good: np.ndarray) -> np.ndarray:
    """Follow pointers ``step`` (-1 = none) from each index until an index where ``good`` holds.

    Returns, for every i, the first good index among step[i], step[step[i]], ... (or -1).
    Pointer jumping: each round doubles how far every pointer has looked, so O(n log n).
    """
    n = len(step)
    good_ext = np.append(good, True)  # index n is the sentinel for "none"
    p = np.append(np.where(step < 0, n, step), n)
    while True:
        bad = ~good_ext[p]
        if not bad.any():
            break
        p = np.where(bad, p[p], p)
    p = p[:n]
    return np.where(p == n, -1, p)
