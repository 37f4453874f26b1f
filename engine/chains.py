"""Prefix scans along parent-pointer chains, shared by the turtle and the mesher.

Every element has a parent index (-1 for a root). A scan gives each element the combination of all
values on its path from the root, parent first. Trees are walked level by level (each element is
combined exactly once, one numpy call per level); when a tree is deeper than ``LEVEL_LIMIT`` levels
(a long unbranched chain), the rest is finished by pointer jumping in O(n log depth).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

LEVEL_LIMIT = 192
Arrays = tuple[np.ndarray, ...]
Combine = Callable[[Arrays, Arrays], Arrays]


def _children_index(par: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """CSR child lists: children of i are order[start[i]:start[i] + count[i]]."""
    order = np.argsort(par, kind="stable")
    count = np.bincount(par + 1, minlength=len(par) + 1)[1:]
    start = np.cumsum(count) - count + int(np.count_nonzero(par < 0))
    return order, start, count


def _gather_children(frontier: np.ndarray, order, start, count) -> np.ndarray:
    c = count[frontier]
    total = int(c.sum())
    if total == 0:
        return frontier[:0]
    ends = np.cumsum(c)
    offsets = np.repeat(start[frontier] - (ends - c), c) + np.arange(total)
    return order[offsets]


def scan(par: np.ndarray, values: Arrays, combine: Combine) -> Arrays:
    """Generic chain scan: out[i] = combine(out[par[i]], values[i]) with out[root] = values[root]."""
    acc = tuple(v.copy() for v in values)
    order, start, count = _children_index(par)
    frontier = np.flatnonzero(par < 0)
    done = par < 0
    for _ in range(LEVEL_LIMIT):
        kids = _gather_children(frontier, order, start, count)
        if len(kids) == 0:
            return acc
        new = combine(tuple(a[par[kids]] for a in acc), tuple(a[kids] for a in acc))
        for a, v in zip(acc, new, strict=True):
            a[kids] = v
        done[kids] = True
        frontier = kids
    return _finish_by_jumping(par, acc, combine, done)


def _finish_by_jumping(par: np.ndarray, acc: Arrays, combine: Combine, done: np.ndarray) -> Arrays:
    """Pointer jumping for elements not reached by the level walk (their walked ancestors are final)."""
    ptr = np.where(done, -1, par)
    active = np.flatnonzero(ptr >= 0)
    while len(active):
        p = ptr[active]
        new = combine(tuple(a[p] for a in acc), tuple(a[active] for a in acc))
        for a, v in zip(acc, new, strict=True):
            a[active] = v
        ptr[active] = ptr[p]
        active = active[ptr[active] >= 0]
    return acc


def chain_sum(par: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Sum of ``values`` over each element's path from its root, itself included."""
    (out,) = scan(par, (values,), lambda p, c: (p[0] + c[0],))
    return out


def _compose(p: Arrays, c: Arrays) -> Arrays:
    rot = np.matmul(p[0], c[0])
    if len(p) == 1:
        return (rot,)
    a_c = c[1][:, :, 0]
    maps = np.empty_like(c[1])
    maps[:, :, 0] = a_c * p[1][:, :, 0]
    maps[:, :, 1] = a_c * p[1][:, :, 1] + c[1][:, :, 1]
    return rot, maps


def chain_compose(par: np.ndarray, rot: np.ndarray, scalars: np.ndarray | None = None):
    """Products of 3x3 rotations (parent on the left) and affine scalar maps along each path.

    ``scalars`` has shape (n, k, 2): maps x -> a x + b, composed so the parent's map applies first.
    Returns (rotations, scalars) — scalars is None when not given.
    """
    if scalars is None:
        (out,) = scan(par, (rot,), _compose)
        return out, None
    return scan(par, (rot, scalars), _compose)
