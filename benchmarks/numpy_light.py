"""The whole-array numpy version of the light grid's optical depth (one float sort key per splat and
query, then running sums), kept as the peer that engine/life/plant/light_kernel.py's compiled pass is
measured against (``python -m benchmarks.living``). It loses precision where points lie far apart: its
sort key packs the cell and the depth into one float."""

from __future__ import annotations

import numpy as np

from arbor.engine.life.plant.light import _basis


def optical_depth(occluders: np.ndarray, area: np.ndarray, queries: np.ndarray, direction: np.ndarray,
                  cell: float, self_index: np.ndarray | None = None) -> np.ndarray:
    """Leaf area (per cell area) between each query point and the light coming from ``direction``.

    ``occluders`` (n, 3) with ``area`` (n,) cast shade; ``queries`` (m, 3) receive it. A query that is
    itself occluder ``self_index[i]`` (or -1) is not shaded by its own area (ties go to the query).
    """
    m = len(queries)
    if m == 0:
        return np.zeros(0)
    d, u, v = _basis(direction)
    if self_index is None:
        self_index = np.full(m, -1, dtype=np.int64)
    occ = np.asarray(occluders, float).reshape(-1, 3)
    # occluders: bilinear splat into the 4 cells around their position (cell k covers [k, k + 1))
    ox, oy = occ @ u / cell - 0.5, occ @ v / cell - 0.5
    ix, iy = np.floor(ox), np.floor(oy)
    fx, fy = ox - ix, oy - iy
    corners = [(0, 0, (1 - fx) * (1 - fy)), (1, 0, fx * (1 - fy)), (0, 1, (1 - fx) * fy), (1, 1, fx * fy)]
    occ_cx = np.concatenate([ix + dx for dx, _, _ in corners])
    occ_cy = np.concatenate([iy + dy for _, dy, _ in corners])
    occ_w = np.concatenate([w for _, _, w in corners]) * np.tile(np.asarray(area, float), 4)
    occ_s = np.tile(occ @ d, 4)
    q = np.asarray(queries, float).reshape(-1, 3)
    q_cx, q_cy, q_s = np.floor(q @ u / cell), np.floor(q @ v / cell), q @ d
    # a query that is also an occluder sits exactly at its own depth: nudge it forward so its own area
    # (and only area at the very same depth) is not counted in front of it
    own = self_index >= 0
    q_s = np.where(own, q_s + 1e-9 * (1.0 + np.abs(q_s)), q_s)
    cx = np.concatenate([occ_cx, q_cx])
    cy = np.concatenate([occ_cy, q_cy])
    s = np.concatenate([occ_s, q_s])
    w = np.concatenate([occ_w, np.zeros(m)])
    key = (cx - cx.min()) * (cy.max() - cy.min() + 1) + (cy - cy.min())
    span = max(float(s.max() - s.min()), 1e-12)
    # one float sort key: the cell, then from the sun downwards within it (s scaled into [0, 0.5])
    order = np.argsort(key + 0.5 * (s.max() - s) / span, kind="stable")
    ws = w[order]
    before = np.cumsum(ws) - ws  # area strictly earlier in the sort
    ks = key[order]
    first = np.r_[True, ks[1:] != ks[:-1]]
    group_start = np.maximum.accumulate(np.where(first, np.arange(len(ks)), 0))
    depth = before - before[group_start]
    out = np.empty(len(order))
    out[order] = depth
    return out[len(occ_w):] / (cell * cell)
