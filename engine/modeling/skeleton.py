"""A branch skeleton (nodes with parents) and the L-string that draws it, built as arrays.

The crown grown into lobes is a skeleton; it joins the tree as ordinary modules: per node a turn
``+``, a pitch ``&``, a width ``!`` where it changes, and a drawn piece ``F(length, start, heading, up,
variation)`` as the modeler writes strokes; side branches in brackets, a tip (a leaf) at every end.
The frames are solved level by level in numpy; the modules are gathered from per-node tables (no text
is written and parsed back); only the order of the pieces is walked, with an explicit stack.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from arbor.engine.geometry.turtle import INITIAL_FRAME, unit
from arbor.engine.lsystem.lstring import LString, concat, parse_lstring, ragged_arange

_KINDS = np.frombuffer(b"+&!F", np.uint8)  # a piece's modules, in this order
_KIND_PARAMS = np.array([1, 1, 1, 11])
_OPEN, _CLOSE, _TIP = -1, -2, -3  # tokens of the piece order besides node ids


@dataclass
class Skeleton:
    """Branch nodes: position, parent (-1 for the root), heading of the branch into the node."""

    position: np.ndarray
    parent: np.ndarray
    heading: np.ndarray
    active: np.ndarray

    @classmethod
    def from_trunk(cls, points: np.ndarray) -> Skeleton:
        """A chain of nodes (a drawn trunk); only its tip grows."""
        points = np.asarray(points, float)
        heading = np.vstack([[0.0, 1.0, 0.0], unit(np.diff(points, axis=0))])
        active = np.zeros(len(points), bool)
        active[-1] = True
        return cls(points, np.arange(len(points)) - 1, heading, active)


def skeleton_text(skeleton: Skeleton, root: int = 0, frame: np.ndarray = INITIAL_FRAME,
                  diameters: np.ndarray | None = None, tip: str = "") -> str:
    """The skeleton from node ``root`` on, for a turtle standing there with ``frame``, as ordinary
    L-string text (see skeleton_lstrings)."""
    tip_ls = parse_lstring(tip) if tip else None
    return skeleton_lstrings(skeleton, np.array([root]), np.array(frame, float)[None], diameters, tip_ls)[0].to_text()


def skeleton_lstrings(skeleton: Skeleton, roots: np.ndarray, frames: np.ndarray,
                      diameters: np.ndarray | None = None, tip: LString | None = None) -> list[LString]:
    """The sub-tree below each of ``roots`` (the turtle at a root has its ``frames``) as an L-string:
    the first child of a node continues its axis, the others go in brackets before it; each piece gets
    its diameter from ``diameters`` (per node; written only where it changes, as the turtle carries it
    on), or none (then the pipe model sets the radii); ``tip`` ends every branch (e.g. a leaf)."""
    roots = np.asarray(roots, np.int64)
    library, starts, counts = _piece_library(skeleton, roots, np.asarray(frames, float), diameters, tip)
    order = np.argsort(skeleton.parent, kind="stable")
    first_child = np.searchsorted(skeleton.parent[order], np.arange(len(skeleton.parent) + 1))
    out = []
    for root in roots.tolist():
        tokens = np.array(_piece_order(root, order, first_child), np.int64)
        picks = np.where(tokens >= 0, tokens, len(skeleton.parent) - 1 - tokens)
        out.append(_gather(library, ragged_arange(starts[picks], counts[picks])))
    return out


def _piece_order(root: int, order: np.ndarray, first_child: np.ndarray) -> list[int]:
    """The pieces below ``root`` in L-string order: node ids, with _OPEN/_CLOSE around side branches and
    _TIP at each branch end."""
    out: list[int] = []
    stack = [root]
    while stack:
        item = stack.pop()
        if item != root:
            out.append(item)  # a bracket, or the piece into a node (then the node's branches)
        if item < 0:
            continue
        kids = order[first_child[item] : first_child[item + 1]].tolist()
        if not kids:
            out.append(_TIP)
            continue
        first, *sides = kids
        tokens: list[int] = []
        for side in sides:
            tokens += [_OPEN, side, _CLOSE]
        tokens.append(first)
        stack.extend(reversed(tokens))
    return out


def _piece_library(skeleton: Skeleton, roots: np.ndarray, frames: np.ndarray, diameters: np.ndarray | None,
                   tip: LString | None) -> tuple[LString, np.ndarray, np.ndarray]:
    """Every node's piece, then ``[``, ``]`` and the tip, as one L-string, with where each starts and
    how many modules it has (node ids first, then the _OPEN, _CLOSE, _TIP tokens)."""
    turn, pitch, moving, values = _piece_values(skeleton, roots, frames)
    n = len(skeleton.parent)
    parent = skeleton.parent
    if diameters is None:
        width = np.zeros(n, bool)
    else:
        diameters = np.asarray(diameters, float)
        from_root = np.isin(parent, roots)
        width = from_root | (diameters != diameters[np.maximum(parent, 0)])
        values[:, 2, 0] = diameters
    has = np.stack([np.abs(turn) > 1e-9, np.abs(pitch) > 1e-9, width, np.ones(n, bool)], axis=1) & moving[:, None]
    node, kind = np.nonzero(has)
    wanted = has[:, :, None] & (np.arange(11) < _KIND_PARAMS[:, None])[None]
    pieces = LString.from_arrays(_KINDS[kind], _KIND_PARAMS[kind], values[wanted])
    extras = [parse_lstring("["), parse_lstring("]"), tip if tip is not None else LString.empty()]
    counts = np.concatenate([np.bincount(node, minlength=n), [len(e) for e in extras]]).astype(np.int64)
    starts = np.concatenate([[0], np.cumsum(counts)[:-1]])
    return concat(pieces, *extras), starts, counts


def _piece_values(skeleton: Skeleton, roots: np.ndarray, frames: np.ndarray):
    """Per node below ``roots``: the turn and pitch (degrees) that aim the turtle (whose frame is the end
    frame of the piece into the parent) at the node, whether the piece moves at all, and the parameter
    table (n, 4, 11) of its + & ! F modules (F: length, start, heading, up, variation)."""
    parent, pos = skeleton.parent, skeleton.position
    n = len(parent)
    depth = np.full(n, -1)
    depth[roots] = 0
    for _ in range(n):  # parents come before children: levels settle in (tree depth) passes
        below = (depth < 0) & (parent >= 0)
        below &= depth[np.maximum(parent, 0)] >= 0
        if not below.any():
            break
        depth[below] = depth[parent[below]] + 1
    ends = np.zeros((n, 3, 3))
    ends[roots] = frames
    turn, pitch, moving = np.zeros(n), np.zeros(n), np.zeros(n, bool)
    values = np.zeros((n, 4, 11))
    for level in range(1, int(depth.max()) + 1):
        nodes = np.flatnonzero(depth == level)
        start = ends[parent[nodes]]
        vec = pos[nodes] - pos[parent[nodes]]
        length = np.linalg.norm(vec, axis=1)
        d = vec / np.maximum(length, 1e-300)[:, None]
        turn[nodes] = np.degrees(np.arctan2(_dot(d, start[:, :, 1]), _dot(d, start[:, :, 0])))
        turned = np.einsum("kij,kjl->kil", start, _rotations(turn[nodes], 2))
        pitch[nodes] = np.degrees(np.arctan2(-_dot(d, turned[:, :, 2]), _dot(d, turned[:, :, 0])))
        end = np.einsum("kij,kjl->kil", turned, _rotations(pitch[nodes], 1))
        up = unit(end[:, :, 2] - _dot(end[:, :, 2], d)[:, None] * d)
        end = np.stack([d, np.cross(up, d), up], axis=2)
        variation = np.degrees(np.arccos(np.clip(_dot(start[:, :, 0], d), -1.0, 1.0)))
        moving[nodes] = length > 1e-12  # a zero-length piece draws nothing and keeps the frame
        ends[nodes] = np.where(moving[nodes][:, None, None], end, start)
        values[nodes, 3] = np.column_stack([length, pos[parent[nodes]], d, up, variation])
    values[:, 0, 0], values[:, 1, 0] = turn, pitch
    return turn, pitch, moving, values


def _gather(ls: LString, idx: np.ndarray) -> LString:
    """The modules ``idx`` of ``ls`` (in that order, repeats allowed) as a new L-string."""
    params = ls.params[ragged_arange(ls.offsets[idx], ls.nparams[idx].astype(np.int64))]
    return LString.from_arrays(ls.sym[idx], ls.nparams[idx], params)


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.einsum("ki,ki->k", a, b)


def _rotations(deg: np.ndarray, axis: int) -> np.ndarray:
    """Rotation matrices about the turtle's U (axis 2, turns) or L (axis 1, pitches), one per angle."""
    a = np.radians(deg)
    c, s = np.cos(a), np.sin(a)
    r = np.zeros((len(a), 3, 3))
    i, j = (0, 1) if axis == 2 else (2, 0)
    r[:, axis, axis] = 1.0
    r[:, i, i], r[:, j, j], r[:, i, j], r[:, j, i] = c, c, -s, s
    return r
