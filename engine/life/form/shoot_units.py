"""Shoot units drawn: a finished run of leafy nodes kept as one module, drawn as its internodes and leaves.

A shoot unit is an internode with 13 parameters (engine/life/plant/units.py makes them from old runs):
``I(birth T, birth G, order, shade, wood, pieces, sites, leaf birth, leaf size, kept, roll, roll step, pitch)``.
The first six are a consolidated internode's (``pieces``: its length in internode lengths, the chord of the
run it stands for); ``sites`` is how many leaf sites (nodes) it holds, ``leaf birth`` and ``leaf size`` are
its leaves' (when they last unfolded, and their vigour), ``kept`` the share of the sites that bear a leaf
now (1 in summer, falling through autumn, 0 in winter: the others hold a leaf bud), and the leaf of site
``i`` (1..sites, at ``i / pieces`` of the way along the unit, where the node stood) is turned ``roll + i x
roll step`` about the unit and pitched ``pitch`` from it, as its node's leaf bracket ``[/(roll)&(pitch)L]``
turned it. The string keeps one module; the turtle, the light and the renderer see every leaf.
"""

from __future__ import annotations

import numpy as np

from arbor.engine.geometry.turtle import Leaves, Segments, TurtleResult
from arbor.engine.lsystem.lstring import LString

UNIT_PARAMS = 13
PIECES, SITES, LEAF_BIRTH, LEAF_SIZE, KEPT, ROLL, ROLL_STEP, LEAF_PITCH = 5, 6, 7, 8, 9, 10, 11, 12
INTERNODE = ord("I")


def unit_modules(ls: LString) -> np.ndarray:
    """Indices of the shoot units of ``ls``."""
    return np.flatnonzero((ls.sym == INTERNODE) & (ls.nparams == UNIT_PARAMS))


def is_unit(ls: LString, idx: np.ndarray) -> np.ndarray:
    """Per module of ``idx``: whether it is a shoot unit."""
    return (ls.sym[idx] == INTERNODE) & (ls.nparams[idx] == UNIT_PARAMS)


def sites(ls: LString, units: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Every leaf site of the units ``units`` (module indices): (its unit's row in ``units``, its number i
    1..sites, whether it bears a leaf now). Site i bears a leaf while a hash of the unit and i is below the
    unit's ``kept`` share, so a unit sheds its leaves one by one as ``kept`` falls."""
    off = ls.offsets[units]
    count = np.maximum(np.rint(ls.params[off + SITES]), 0).astype(np.int64)
    row = np.repeat(np.arange(len(units)), count)
    first = np.cumsum(count) - count
    i = np.arange(int(count.sum())) - np.repeat(first, count) + 1
    at = off[row]  # (a hash of the unit's birth and roll, not its place: it keeps its leaves when the string
    h = np.modf(np.abs(np.sin(ls.params[at] * 12.9898 + ls.params[at + ROLL] * 4.1414 + i * 78.233)  # changes)
                       * 43758.5453))[0]
    return row, i, h < ls.params[at + KEPT]


def leaf_count(ls: LString) -> int:
    """Leaf clusters on the tree: its leaf modules and the leaves its shoot units bear."""
    units = unit_modules(ls)
    own = int(np.count_nonzero((ls.sym == ord("L")) & (ls.nparams >= 1)))
    return own + (int(np.count_nonzero(sites(ls, units)[2])) if len(units) else 0)


def turns(frames: np.ndarray, axis: int, degrees: np.ndarray) -> np.ndarray:
    """``frames`` (k, 3, 3; columns H, L, U) each turned about its own axis ``axis`` (0 H '/', 1 L '&')."""
    i, j = (axis + 1) % 3, (axis + 2) % 3
    c, s = np.cos(np.radians(degrees))[:, None], np.sin(np.radians(degrees))[:, None]
    out = frames.copy()
    out[:, :, i] = c * frames[:, :, i] + s * frames[:, :, j]
    out[:, :, j] = c * frames[:, :, j] - s * frames[:, :, i]
    return out


def unit_leaves(ls: LString, segs: Segments, sizes: np.ndarray | None = None) -> Leaves:
    """The leaves the shoot units among ``segs`` bear, as leaf instances of their unit's module (``sizes``:
    one per unit segment, the leaf length; default the full leaf)."""
    on = np.flatnonzero(is_unit(ls, segs.module))
    if len(on) == 0:
        return Leaves(np.zeros((0, 3)), np.zeros((0, 3, 3)), np.zeros(0), np.zeros(0, np.int64))
    module = segs.module[on]
    row, i, bears = sites(ls, module)
    row, i = row[bears], i[bears]
    off = ls.offsets[module[row]]
    pieces = np.maximum(np.rint(ls.params[off + PIECES]), 1.0)
    along = np.minimum(i / pieces, 1.0)[:, None]
    seg = on[row]
    position = segs.start[seg] + along * (segs.end[seg] - segs.start[seg])
    roll = ls.params[off + ROLL] + i * ls.params[off + ROLL_STEP]
    frame = turns(turns(segs.frame[seg], 0, roll), 1, ls.params[off + LEAF_PITCH])
    size = np.ones(len(on)) if sizes is None else sizes
    return Leaves(position, frame, size[row], module[row])


def unit_leaf_sizes(ls: LString, units: np.ndarray, now: float, const: dict[str, float]) -> np.ndarray:
    """Leaf length on each unit (module indices ``units``): unfolding from zero since the leaves' birth,
    times their vigour (the same law as a leaf module's, engine/life/form/interpret.py leaf_sizes)."""
    off = ls.offsets[units]
    age = np.maximum(now - ls.params[off + LEAF_BIRTH], 0.0)
    return const["LS"] * ls.params[off + LEAF_SIZE] * (1.0 - np.exp(-age / const["TAU"]))


def with_unit_leaves(ls: LString, turtle: TurtleResult, sizes: np.ndarray) -> TurtleResult:
    """``turtle`` with the shoot units' leaves added to its leaves (``sizes``: per unit segment, in the
    segments' order), each carried by its unit's own segment."""
    extra = unit_leaves(ls, turtle.segments, sizes)
    if len(extra) == 0:
        return turtle
    own = turtle.leaves
    turtle.leaves = Leaves(np.concatenate([own.position, extra.position]), np.concatenate([own.frame, extra.frame]),
                           np.concatenate([own.size, extra.size]), np.concatenate([own.module, extra.module]))
    if turtle.nearest_move is not None:  # a unit's leaves grow from the unit itself
        moves = turtle.nearest_move.copy()
        moves[extra.module] = extra.module
        turtle.nearest_move = moves
    return turtle


def bare(ls: LString) -> tuple[LString, int]:
    """``ls`` with every shoot unit stripped of its leaves (winter: each site keeps a leaf bud), and how many
    leaves fell."""
    units = unit_modules(ls)
    if len(units) == 0:
        return ls, 0
    fell = int(np.count_nonzero(sites(ls, units)[2]))
    params = ls.params.copy()
    params[ls.offsets[units] + KEPT] = 0.0
    return LString(ls.sym, ls.nparams, ls.offsets, params), fell


def bud_count(ls: LString) -> int:
    """Leaf buds on the tree: its leaf bud modules and its shoot units' sites that bear no leaf now."""
    units = unit_modules(ls)
    own = int(np.count_nonzero(ls.sym == ord("V")))
    return own + (int(np.count_nonzero(~sites(ls, units)[2])) if len(units) else 0)


def node_count(ls: LString) -> int:
    """Internodes the tree's wood stands for: its internode modules, each shoot unit counting its sites."""
    node = ls.sym == INTERNODE
    units = unit_modules(ls)
    return int(np.count_nonzero(node)) + int(np.maximum(np.rint(ls.params[ls.offsets[units] + SITES]) - 1, 0).sum())
