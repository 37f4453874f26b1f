"""Roots (drawn only in the cut-away view, where the ground turns to soil) and rocks as instance records."""

from __future__ import annotations

import numpy as np

from arbor.engine.geometry.instances import LEAF_FLOATS, LeafInstances, TubeInstances, tube_instances
from arbor.engine.life.plant.roots import Roots
from arbor.game.render.falling import StaticView


def roots_view(roots: Roots) -> StaticView:
    """Records of a tree's roots, below its foot (tubes only)."""
    segs = roots.segments()
    lo, hi = roots.bounds()
    return StaticView(tube_instances(segs), LeafInstances.empty(), LeafInstances.empty(), np.asarray(lo),
                      np.asarray(hi))


def rocks_view(rocks: list[tuple[float, float, float, float]]) -> StaticView:
    """The garden's rocks (x, y, z, radius) as ball records (the shaders' kind 4)."""
    data = np.zeros((len(rocks), LEAF_FLOATS), np.float32)
    arr = np.asarray(rocks, np.float32).reshape(-1, 4)
    data[:, 0:3], data[:, 4], data[:, 8], data[:, 9] = arr[:, :3], 1.0, 1.0, 2 * arr[:, 3]
    lo, hi = (arr[:, :3] - arr[:, 3:]).min(axis=0), (arr[:, :3] + arr[:, 3:]).max(axis=0)
    return StaticView(TubeInstances.empty(), LeafInstances.empty(), LeafInstances.empty(), lo, hi,
                      stones=LeafInstances(data))
