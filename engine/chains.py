"""Prefix scans along parent-pointer chains (pointer jumping), shared by the turtle and the mesher.

Every element has a parent index (-1 for a root). A scan gives each element the combination of all
values on its path from the root, parent first, in O(n log depth) numpy operations.
"""

from __future__ import annotations

import numpy as np


def chain_sum(par: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Sum of ``values`` over each element's path from its root, itself included."""
    acc = values.copy()
    ptr = par.copy()
    active = np.flatnonzero(ptr >= 0)
    while len(active):
        p = ptr[active]
        acc[active] += acc[p]
        ptr[active] = ptr[p]
        active = active[ptr[active] >= 0]
    return acc


def chain_compose(par: np.ndarray, rot: np.ndarray, scalars: np.ndarray | None = None):
    """Products of 3x3 rotations (parent on the left) and affine scalar maps along each path.

    ``scalars`` has shape (n, k, 2): maps x -> a x + b, composed so the parent's map applies first.
    Returns (rotations, scalars) — scalars is None when not given.
    """
    acc_r = rot.copy()
    acc_s = None if scalars is None else scalars.copy()
    ptr = par.copy()
    active = np.flatnonzero(ptr >= 0)
    while len(active):
        p = ptr[active]
        acc_r[active] = np.matmul(acc_r[p], acc_r[active])
        if acc_s is not None:
            a_i = acc_s[active, :, 0]
            acc_s[active, :, 1] = a_i * acc_s[p, :, 1] + acc_s[active, :, 1]
            acc_s[active, :, 0] = a_i * acc_s[p, :, 0]
        ptr[active] = ptr[p]
        active = active[ptr[active] >= 0]
    return acc_r, acc_s
