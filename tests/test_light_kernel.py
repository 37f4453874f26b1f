"""The light grid's compiled pass (engine/life/plant/light_kernel.py) on crowded cells: its own merge sort
(plain loops, cheap to compile) must keep a leaf in front of a query at the same distance."""

from __future__ import annotations

import numpy as np
import pytest

from arbor.engine.life.plant.light import _basis, optical_depth


def _by_definition(occ, area, queries, direction, cell):
    """Each query's leaf area per cell area from splats at least as near the light, in its own cell."""
    d, u, v = _basis(direction)
    ox, oy = occ @ u / cell - 0.5, occ @ v / cell - 0.5
    ix, iy = np.floor(ox), np.floor(oy)
    fx, fy = ox - ix, oy - iy
    out = np.zeros(len(queries))
    for j, p in enumerate(queries):
        cx, cy, nearer = np.floor(p @ u / cell), np.floor(p @ v / cell), occ @ d >= p @ d
        for dx, dy, w in ((0, 0, (1 - fx) * (1 - fy)), (1, 0, fx * (1 - fy)), (0, 1, (1 - fx) * fy),
                          (1, 1, fx * fy)):
            out[j] += np.sum((w * area)[nearer & (ix + dx == cx) & (iy + dy == cy)])
    return out / cell**2


@pytest.mark.parametrize("spread", [0.0, 1e4])
def test_a_crowded_cell_of_ties_counts_every_leaf_level_with_a_query(spread):
    """200 leaves on six levels of one column (a cell of 200 splats: merge-sorted in runs) and queries on
    those levels: a query counts the leaves at its own level (they are in front), in a dense grid and in a
    sparse one (a second column 10,000 units away)."""
    rng = np.random.default_rng(5)
    occ = np.c_[np.full(200, 0.2), rng.integers(0, 6, 200).astype(float), np.full(200, 0.3)]
    occ[100:, 0] += spread
    area = rng.uniform(0.1, 2.0, 200)
    queries = occ[rng.permutation(200)[:90]]
    up = np.array([0.0, 1.0, 0.0])
    ours = optical_depth(occ, area, queries, up, 0.9)
    assert ours == pytest.approx(_by_definition(occ, area, queries, up, 0.9), abs=1e-9)
    assert len(np.unique(ours)) >= 5  # the levels shade differently


def test_a_sparse_grid_keeps_every_cell_of_far_apart_crowns_apart():
    """40 small crowns scattered over 100 km (a sparse grid: its cells are hashed, tiles of them sharing
    slots): each leaf's shade comes from its own crown's cells only, as by the definition."""
    rng = np.random.default_rng(8)
    centres = rng.uniform(-5e4, 5e4, (40, 3)) * np.array([1.0, 0.0, 1.0])
    occ = np.repeat(centres, 30, axis=0) + rng.normal(size=(1200, 3))
    area = rng.uniform(0.1, 2.0, 1200)
    queries = occ + rng.normal(size=(1200, 3)) * 0.3
    up = np.array([0.0, 1.0, 0.0])
    ours = optical_depth(occ, area, queries, up, 0.9)
    assert ours == pytest.approx(_by_definition(occ, area, queries, up, 0.9), abs=1e-9)
    assert (ours > 0).mean() > 0.3
