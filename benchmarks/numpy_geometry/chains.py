"""Prefix scans along parent-pointer chains, shared by the turtle and the mesher.

Every element has a parent index (-1 for a root). A scan gives each element the combination of all
values on its path from the root, parent first. Values are stored column-wise, shape (k, n): one row
per component, one column per element, so a combine step is a few whole-row numpy operations (for
rotations: quaternion products, 16 multiplications on rows instead of ``np.matmul`` on (n, 3, 3)).

Trees are walked level by level after sorting the elements into level order, so each level is one
contiguous block of columns and is combined with one numpy call per row operation; when a tree is
deeper than ``LEVEL_LIMIT`` levels (a long unbranched chain), the rest is finished by pointer jumping
in O(n log depth).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from itertools import pairwise

import numpy as np

LEVEL_LIMIT = 192
Combine = Callable[[np.ndarray, np.ndarray], np.ndarray]

@dataclass
class Levels:
    """Elements of a forest sorted by depth (roots first, string order within a depth).

    ``bounds`` are where each walked level starts in ``order``; elements deeper than ``LEVEL_LIMIT``
    follow the last walked level (in index order) and are finished by pointer jumping.
    """

    order: np.ndarray  # (n,) element index at each sorted position
    where: np.ndarray  # (n,) sorted position of each element
    parent: np.ndarray  # (n,) sorted position of the parent of each sorted position (-1 root)
    bounds: list[int]

    @classmethod
    def of(cls, par: np.ndarray) -> Levels:
        """Sort the forest given by parent pointers ``par`` (-1 for roots) into levels."""
        n = len(par)
        depth = np.minimum(tree_depths(par), LEVEL_LIMIT + 1)
        order = np.argsort(depth.astype(np.int16), kind="stable")  # a radix sort on small keys
        where = np.empty(n, dtype=np.int64)
        where[order] = np.arange(n)
        parent_of = par[order]
        parent = np.where(parent_of >= 0, where[np.maximum(parent_of, 0)], -1)
        bounds = np.concatenate([[0], np.cumsum(np.bincount(depth, minlength=1))]).tolist()
        return cls(order, where, parent, bounds)

    def scan(self, acc: np.ndarray, combine: Combine) -> np.ndarray:
        """In place on columns already in level order: acc[:, i] = combine(acc[:, parent[i]], acc[:, i])."""
        deep = len(self.bounds) > LEVEL_LIMIT + 2  # some elements lie below the walked levels
        walked = self.bounds[1:-1] if deep else self.bounds[1:]
        for lo, hi in pairwise(walked):
            acc[:, lo:hi] = combine(np.take(acc, self.parent[lo:hi], axis=1), acc[:, lo:hi])
        if deep:
            done = np.zeros(acc.shape[1], bool)
            done[: walked[-1]] = True
            _finish_by_jumping(self.parent, acc, combine, done)
        return acc


def tree_depths(par: np.ndarray) -> np.ndarray:
    """Number of ancestors of every element (list ranking by pointer jumping, O(n log depth))."""
    depth = (par >= 0).astype(np.int64)
    ptr = par.copy()
    active = np.flatnonzero(ptr >= 0)
    while len(active):
        p = ptr[active]
        depth[active] = depth[active] + depth[p]
        ptr[active] = ptr[p]
        active = active[ptr[active] >= 0]
    return depth


def scan(par: np.ndarray, values: np.ndarray, combine: Combine) -> np.ndarray:
    """Generic chain scan over columns: out[:, i] = combine(out[:, par[i]], values[:, i])."""
    if values.shape[1] == 0:
        return values.copy()
    levels = Levels.of(par)
    acc = levels.scan(np.take(values, levels.order, axis=1), combine)
    return np.take(acc, levels.where, axis=1)


def _finish_by_jumping(par: np.ndarray, acc: np.ndarray, combine: Combine, done: np.ndarray) -> np.ndarray:
    """Pointer jumping for elements not reached by the level walk (their walked ancestors are final)."""
    ptr = np.where(done, -1, par)
    active = np.flatnonzero(ptr >= 0)
    while len(active):
        p = ptr[active]
        acc[:, active] = combine(acc[:, p], acc[:, active])
        ptr[active] = ptr[p]
        active = active[ptr[active] >= 0]
    return acc


def chain_sum(par: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Sum of ``values`` over each element's path from its root, itself included.

    ``values`` is (n,) or column-wise (k, n); the result has the same shape.
    """
    cols = values[None] if values.ndim == 1 else values
    out = scan(par, cols, np.add)
    return out[0] if values.ndim == 1 else out


def compose_maps(p: np.ndarray, c: np.ndarray, out: np.ndarray | None = None) -> np.ndarray:
    """Column-wise composition of affine scalar maps x -> a x + b, stored as row pairs (a, b, a, b...):
    the parent's map applies first."""
    out = np.empty(np.broadcast_shapes(p.shape, c.shape)) if out is None else out
    a_c = c[0::2]
    out[1::2] = a_c * p[1::2] + c[1::2]
    out[0::2] = a_c * p[0::2]
    return out


def quat_mul(p: np.ndarray, c: np.ndarray, out: np.ndarray | None = None) -> np.ndarray:
    """Column-wise Hamilton products p c of quaternions stored as rows (w, x, y, z): the rotation
    p then c in the rotated frame, as the matrix product R_p R_c."""
    pw, px, py, pz = p
    cw, cx, cy, cz = c
    out = np.empty((4, np.broadcast_shapes(p.shape, c.shape)[1])) if out is None else out
    out[0] = pw * cw - px * cx - py * cy - pz * cz
    out[1] = pw * cx + px * cw + py * cz - pz * cy
    out[2] = pw * cy - px * cz + py * cw + pz * cx
    out[3] = pw * cz + px * cy - py * cx + pz * cw
    return out


def compose_turtle(p: np.ndarray, c: np.ndarray) -> np.ndarray:
    """Column-wise composition of turtle blocks: a quaternion in rows 0-3, then scalar maps."""
    out = np.empty((p.shape[0], c.shape[1]))
    quat_mul(p[:4], c[:4], out[:4])
    compose_maps(p[4:], c[4:], out[4:])
    return out


def quat_entries(q: np.ndarray) -> tuple[tuple[np.ndarray, ...], ...]:
    """The rotation matrix entries (row by row, each an (n,) array) of unit quaternions (4, n)."""
    w, x, y, z = q
    xx, yy, zz, xy, xz, yz, wx, wy, wz = x * x, y * y, z * z, x * y, x * z, y * z, w * x, w * y, w * z
    return ((1 - 2 * (yy + zz), 2 * (xy - wz), 2 * (xz + wy)),
            (2 * (xy + wz), 1 - 2 * (xx + zz), 2 * (yz - wx)),
            (2 * (xz - wy), 2 * (yz + wx), 1 - 2 * (xx + yy)))


def quat_to_rows(q: np.ndarray) -> np.ndarray:
    """Unit quaternions (4, n) as row-major rotation matrices (9, n)."""
    return np.stack([entry for row in quat_entries(q) for entry in row])


def rows_to_quat(rows: np.ndarray) -> np.ndarray:
    """Row-major rotation matrices (9, n) as unit quaternions (4, n), w >= 0 (Shepperd's method: the
    largest of the four squared components picks the well-conditioned formula)."""
    m00, m01, m02, m10, m11, m12, m20, m21, m22 = rows
    squares = np.stack([1 + m00 + m11 + m22, 1 + m00 - m11 - m22, 1 - m00 + m11 - m22, 1 - m00 - m11 + m22])
    pick = np.argmax(squares, axis=0)
    big = 0.5 * np.sqrt(np.maximum(squares[pick, np.arange(rows.shape[1])], 1e-300))
    quarter = 0.25 / big
    q = np.empty((4, rows.shape[1]))
    candidates = (
        (big, (m21 - m12) * quarter, (m02 - m20) * quarter, (m10 - m01) * quarter),
        ((m21 - m12) * quarter, big, (m01 + m10) * quarter, (m02 + m20) * quarter),
        ((m02 - m20) * quarter, (m01 + m10) * quarter, big, (m12 + m21) * quarter),
        ((m10 - m01) * quarter, (m02 + m20) * quarter, (m12 + m21) * quarter, big),
    )
    for k, values in enumerate(candidates):
        sel = pick == k
        for r in range(4):
            q[r, sel] = values[r][sel]
    q *= np.where(q[0] < 0, -1.0, 1.0)
    return q / np.linalg.norm(q, axis=0)


def to_rows(mats: np.ndarray) -> np.ndarray:
    """(n, 3, 3) matrices -> (9, n) row-major columns."""
    return np.ascontiguousarray(mats.reshape(-1, 9).T)
