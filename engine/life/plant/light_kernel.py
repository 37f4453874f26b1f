"""The compiled loop behind light.optical_depth: entries grouped by grid cell, each cell in order from the light.

A leaf splats its area into the four grid cells around it (bilinear); in every cell, its entries (splats
and query points) are sorted by distance from the light and summed in that order, so a query reads the
leaf area in front of it. ``python -m benchmarks.living``
times it against the numpy version it replaced (a sort of all four splats per leaf, then running sums),
in the same run.
"""

# numba caches this kernel on disk under this module's name (arbor.engine...) and reloads it while
# this file is unchanged: renaming the module needs a change here too, or the cache names a module gone.

from __future__ import annotations

import math

import numba
import numpy as np

SMALL = 24  # a cell with more entries than this is merge-sorted, a smaller one by insertion
DENSE = 4  # a grid with at most this many cells per point is an array; a sparser one (trees far apart) is indexed


@numba.njit(cache=True, nogil=True)
def depths(occ, area, q, own, d, u, v, cell):
    """Leaf area (per cell area) in front of each query in its cell of the grid across ``d`` (``u``,
    ``v``: the grid's axes, ``cell`` its side). ``occ`` (n, 3) with ``area`` cast shade; a query with
    ``own`` set is itself an occluder and sits just in front of its own area. Ties in distance: the
    leaf is in front of the query."""
    n, m = len(occ), len(q)
    ix, iy = np.empty(n, np.int64), np.empty(n, np.int64)
    fx, fy = np.empty(n), np.empty(n)
    qx, qy = np.empty(m, np.int64), np.empty(m, np.int64)
    s = np.empty(n + m)
    for i in range(n):
        ox = (occ[i, 0] * u[0] + occ[i, 1] * u[1] + occ[i, 2] * u[2]) / cell - 0.5
        oy = (occ[i, 0] * v[0] + occ[i, 1] * v[1] + occ[i, 2] * v[2]) / cell - 0.5
        ix[i], iy[i] = math.floor(ox), math.floor(oy)
        fx[i], fy[i] = ox - ix[i], oy - iy[i]
        s[i] = occ[i, 0] * d[0] + occ[i, 1] * d[1] + occ[i, 2] * d[2]
    for i in range(m):
        qx[i] = math.floor((q[i, 0] * u[0] + q[i, 1] * u[1] + q[i, 2] * u[2]) / cell)
        qy[i] = math.floor((q[i, 0] * v[0] + q[i, 1] * v[1] + q[i, 2] * v[2]) / cell)
        depth = q[i, 0] * d[0] + q[i, 1] * d[1] + q[i, 2] * d[2]
        s[n + i] = depth + 1e-9 * (1.0 + abs(depth)) if own[i] else depth
    occ_cell, q_cell, cells = _cells(ix, iy, qx, qy)
    # every splat and query as an entry of its cell; entries grouped by cell (a counting sort), then
    # each cell's entries sorted from the light (a leaf before a query at the same distance)
    total = 4 * n + m
    cell_of = np.concatenate((occ_cell[:, 0], occ_cell[:, 1], occ_cell[:, 2], occ_cell[:, 3], q_cell))
    start = np.zeros(cells + 1, np.int64)
    for e in range(total):
        start[cell_of[e] + 1] += 1
    start = np.cumsum(start)
    fill = start[:-1].copy()
    entry = np.empty(total, np.int64)
    for e in range(total):
        entry[fill[cell_of[e]]] = e
        fill[cell_of[e]] += 1
    key = np.empty(total)  # distance toward the light, negated: ascending = from the light
    for e in range(total):
        key[e] = -s[e % n] if e < 4 * n else -s[e - 3 * n]
    out = np.empty(m)
    for c in range(cells):
        group = entry[start[c]:start[c + 1]]
        _from_light(group, key)
        running = 0.0
        for e in group:
            if e < 4 * n:
                i, corner = e % n, e // n
                wx = fx[i] if corner % 2 else 1 - fx[i]
                wy = fy[i] if corner // 2 else 1 - fy[i]
                running += wx * wy * area[i]
            else:
                out[e - 4 * n] = running / (cell * cell)
    return out


@numba.njit(cache=True, nogil=True)
def _from_light(group, key):
    """Sort a cell's entries in place by ``key``, stably (entries come numbered, leaves' splats first: a
    leaf is in front of a query at the same distance): insertion for the few entries a cell has, else
    a merge sort."""
    if len(group) > SMALL:
        group[:] = group[np.argsort(key[group], kind="mergesort")]
        return
    for j in range(1, len(group)):
        e = group[j]
        k = key[e]
        i = j - 1
        while i >= 0 and key[group[i]] > k:
            group[i + 1] = group[i]
            i -= 1
        group[i + 1] = e


@numba.njit(cache=True, nogil=True)
def _cells(ix, iy, qx, qy):
    """Each leaf's four cells (n, 4), each query's cell, and how many cells: the cells spanned, numbered
    row by row, or (a sparse grid: trees far apart, far-flung points) only the cells in use, numbered
    in order."""
    n = len(ix)
    xs = np.concatenate((ix, ix + 1, ix, ix + 1, qx))
    ys = np.concatenate((iy, iy, iy + 1, iy + 1, qy))
    x0, y0 = xs.min(), ys.min()
    cols, rows = xs.max() - x0 + 1, ys.max() - y0 + 1
    if float(cols) * float(rows) <= DENSE * len(xs):
        key = (xs - x0) * rows + (ys - y0)
        cells = cols * rows
    else:  # rank the columns and rows in use first: no product of far-apart numbers can overflow
        ux, uy = np.unique(xs), np.unique(ys)
        key = np.searchsorted(ux, xs) * len(uy) + np.searchsorted(uy, ys)
        used = np.unique(key)
        key = np.searchsorted(used, key)
        cells = len(used)
    occ_cell = np.empty((n, 4), np.int64)
    for c in range(4):
        occ_cell[:, c] = key[c * n:(c + 1) * n]
    return occ_cell, key[4 * n:], cells
