"""The compiled loop behind light.optical_depth: entries grouped by grid cell, each cell in order from the light.

A leaf splats its area into the four grid cells around it (bilinear); in every cell, its entries (splats
and query points) are sorted by distance from the light and summed in that order, so a query reads the
leaf area in front of it. ``python -m benchmarks.living``
times it against the numpy version it replaced (a sort of all four splats per leaf, then running sums),
in the same run. Plain loops throughout, no numpy calls on whole arrays: numba compiled np.unique, a
merge-sort argsort and np.concatenate for a second or so each: most of the 8 s this kernel once took
to compile on a first start (now 2 s).
"""

# numba caches this kernel on disk under this module's name (arbor.engine...) and reloads it while
# this file is unchanged: renaming the module needs a change here too, or the cache names a module gone.

from __future__ import annotations

import math

import numba
import numpy as np

SMALL = 24  # a cell with more entries than this is merge-sorted, a smaller one by insertion
DENSE = 0.5  # a grid with at most this many cells per entry is an array; a sparser one (trees far apart) is
# hashed: faster already at 0.7 cells an entry (the game tree at 100k modules: 3.8 against 5.5 ms), and at 4
# (1M modules) 3x faster than walking and zeroing 3M cells, mostly empty
TILE_BITS = 3  # a sparse grid's cells are hashed by tiles of TILE x TILE (small: two full tiles hashed to one
# place make a run of TILE * TILE cells probe past each other's; 8 x 8 measured as fast as 64 x 64)
TILE = 1 << TILE_BITS


@numba.njit(cache=True, nogil=True)
def depths(occ, area, q, own, d, u, v, cell):
    """Leaf area (per cell area) in front of each query in its cell of the grid across ``d`` (``u``,
    ``v``: the grid's axes, ``cell`` its side). ``occ`` (n, 3) with ``area`` cast shade; a query with
    ``own`` set is itself an occluder and sits just in front of its own area. Ties in distance: the
    leaf is in front of the query."""
    n, m = len(occ), len(q)
    total = 4 * n + m  # entries: each leaf's four splats (corner by corner), then the queries
    fx, fy = np.empty(n), np.empty(n)
    xs, ys = np.empty(total, np.int64), np.empty(total, np.int64)  # each entry's grid cell
    key = np.empty(total)  # distance toward the light, negated: ascending = from the light
    for i in range(n):
        ox = (occ[i, 0] * u[0] + occ[i, 1] * u[1] + occ[i, 2] * u[2]) / cell - 0.5
        oy = (occ[i, 0] * v[0] + occ[i, 1] * v[1] + occ[i, 2] * v[2]) / cell - 0.5
        x, y = math.floor(ox), math.floor(oy)
        fx[i], fy[i] = ox - x, oy - y
        s = occ[i, 0] * d[0] + occ[i, 1] * d[1] + occ[i, 2] * d[2]
        for corner in range(4):
            xs[corner * n + i], ys[corner * n + i] = x + corner % 2, y + corner // 2
            key[corner * n + i] = -s
    for i in range(m):
        xs[4 * n + i] = math.floor((q[i, 0] * u[0] + q[i, 1] * u[1] + q[i, 2] * u[2]) / cell)
        ys[4 * n + i] = math.floor((q[i, 0] * v[0] + q[i, 1] * v[1] + q[i, 2] * v[2]) / cell)
        depth = q[i, 0] * d[0] + q[i, 1] * d[1] + q[i, 2] * d[2]
        key[4 * n + i] = -(depth + 1e-9 * (1.0 + abs(depth)) if own[i] else depth)
    cell_of, cells = _cells(xs, ys)
    # entries grouped by cell (a counting sort), then each cell's entries sorted from the light (a leaf
    # before a query at the same distance)
    start = np.zeros(cells + 1, np.int64)
    for e in range(total):
        start[cell_of[e] + 1] += 1
    fill = np.empty(cells, np.int64)
    for c in range(cells):
        start[c + 1] += start[c]
        fill[c] = start[c]
    entry, spare = np.empty(total, np.int64), np.empty(total, np.int64)
    for e in range(total):
        entry[fill[cell_of[e]]] = e
        fill[cell_of[e]] += 1
    out = np.empty(m)
    for c in range(cells):
        _from_light(entry, start[c], start[c + 1], key, spare)
        running = 0.0
        for j in range(start[c], start[c + 1]):
            e = entry[j]
            if e < 4 * n:
                i, corner = e % n, e // n
                wx = fx[i] if corner % 2 else 1 - fx[i]
                wy = fy[i] if corner // 2 else 1 - fy[i]
                running += wx * wy * area[i]
            else:
                out[e - 4 * n] = running / (cell * cell)
    return out


@numba.njit(cache=True, nogil=True)
def _from_light(entry, lo, hi, key, spare):
    """Sort ``entry[lo:hi]`` in place by ``key``, stably (entries come numbered, leaves' splats first: a
    leaf is in front of a query at the same distance): insertion for the few entries a cell has, else
    runs of SMALL by insertion merged pairwise through ``spare`` (a merge sort in plain loops: numba's
    own argsort took a second of compile)."""
    for a in range(lo, hi, SMALL):
        _insertion(entry, a, min(a + SMALL, hi), key)
    width, swapped = np.int64(SMALL), False  # (not the literal SMALL: _merge_pass compiled once, not twice)
    while width < hi - lo:
        if swapped:
            _merge_pass(spare, entry, lo, hi, width, key)
        else:
            _merge_pass(entry, spare, lo, hi, width, key)
        width, swapped = 2 * width, not swapped
    if swapped:
        for k in range(lo, hi):
            entry[k] = spare[k]


@numba.njit(cache=True, nogil=True)
def _merge_pass(src, dst, lo, hi, width, key):
    """Merge each two neighbouring sorted runs of ``width`` in ``src[lo:hi]`` into ``dst`` (stably)."""
    for a in range(lo, hi, 2 * width):
        i, mid, end = a, min(a + width, hi), min(a + 2 * width, hi)
        j = mid
        for k in range(a, end):
            if j < end and (i >= mid or key[src[j]] < key[src[i]]):
                dst[k] = src[j]
                j += 1
            else:
                dst[k] = src[i]
                i += 1


@numba.njit(cache=True, nogil=True)
def _insertion(entry, lo, hi, key):
    """Sort ``entry[lo:hi]`` in place by ``key``, stably, by insertion."""
    for j in range(lo + 1, hi):
        e = entry[j]
        k = key[e]
        i = j - 1
        while i >= lo and key[entry[i]] > k:
            entry[i + 1] = entry[i]
            i -= 1
        entry[i + 1] = e


@numba.njit(cache=True, nogil=True)
def _cells(xs, ys):
    """Each entry's cell and how many cells: the cells spanned, numbered row by row, or (a sparse grid:
    trees far apart, far-flung points) only the cells in use, numbered as they first come."""
    x0, x1, y0, y1 = xs[0], xs[0], ys[0], ys[0]
    for e in range(len(xs)):
        x0, x1, y0, y1 = min(x0, xs[e]), max(x1, xs[e]), min(y0, ys[e]), max(y1, ys[e])
    cols, rows = x1 - x0 + 1, y1 - y0 + 1
    if float(cols) * float(rows) > DENSE * len(xs):
        return _numbered(xs, ys)
    key = np.empty(len(xs), np.int64)
    for e in range(len(xs)):
        key[e] = (xs[e] - x0) * rows + (ys[e] - y0)
    return key, cols * rows


@numba.njit(cache=True, nogil=True)
def _numbered(xs, ys):
    """The cells in use numbered as they first come, through a hash table of them (open addressing, linear
    probing; linear time however far apart they lie): tiles of TILE x TILE cells go to hashed places (the
    mix of splitmix64; integer products wrap), a tile's cells lie side by side in its place, so a run of
    nearby entries reads nearby slots. Each entry's number, and how many."""
    size = 1 << 12
    while size < 2 * len(xs):
        size *= 2
    cell_x, cell_y, number = np.empty(size, np.int64), np.empty(size, np.int64), np.empty(size, np.int64)
    for slot in range(size):
        number[slot] = -1
    key, cells = np.empty(len(xs), np.int64), 0
    for e in range(len(xs)):
        x, y = xs[e], ys[e]
        tile = (x >> TILE_BITS) * -7046029254386353131 + (y >> TILE_BITS) * -4417276706812531889
        tile = (tile ^ (tile >> 32)) * -4658895280553007687
        slot = ((tile ^ (tile >> 29)) << (2 * TILE_BITS) | (x & TILE - 1) << TILE_BITS | (y & TILE - 1)) & (size - 1)
        while number[slot] >= 0 and (cell_x[slot] != x or cell_y[slot] != y):
            slot = (slot + 1) & (size - 1)
        if number[slot] < 0:
            cell_x[slot], cell_y[slot], number[slot] = x, y, cells
            cells += 1
        key[e] = number[slot]
    return key, cells
