"""The tree as per-segment and per-leaf records for GPU instancing (the game's renderer).

Instead of a mesh of every ring vertex, each segment is one record: its start and end ring (centre,
tangent, twist-free reference direction, radius, bark v coordinate), whether it ends in a tip cone, and
how far it is from the trunk's base (for wind). The vertex shader builds the ring vertices from a small
template; consecutive segments share their joint ring exactly (same centre, tangent, reference and
radius), so tapering is continuous and there are no caps except at tips. A lateral branch's own start
ring is wider (its collar where it leaves its parent) and so is the trunk's foot (the root flare, wider
and reaching higher as the trunk thickens with age: :func:`flare`).
Leaves are one record each (base, axis, normal, size, width). Growth then rewrites a few records, not a mesh.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from arbor.engine.base.units import METRE
from arbor.engine.geometry.chains import chain_sum
from arbor.engine.geometry.mesh import wood_rings
from arbor.engine.geometry.turtle import Leaves, Segments

COLLAR = 1.3  # a branch's start ring is this much wider than the branch: the collar where it leaves its parent
FLARE = (1.3, 1.7)  # and the trunk's foot this much wider than the trunk, a sapling's to an old tree's
FLARE_AGED = (0.01 * METRE, 0.15 * METRE)  # trunk radius (scene units) of a sapling and of an old tree
FLARE_REACH = 0.8  # the flare falls off e-fold every this many trunk radii up
TUBE_FLOATS = 26  # c0 t0 x0 c1 t1 x1 (18), r0 r1, v0 v1, flex0 flex1, cap, order
LEAF_FLOATS = 13  # base (3), axis (3), normal (3), length, width, flex, hash (which leaves a coarse level keeps)


@dataclass
class TubeInstances:
    """One record per segment (see module docstring); ``data`` is (m, TUBE_FLOATS) float32."""

    data: np.ndarray
    module: np.ndarray  # (m,) L-string module of each segment

    def __len__(self) -> int:
        return len(self.data)

    @classmethod
    def empty(cls) -> TubeInstances:
        """No segments."""
        return cls(np.zeros((0, TUBE_FLOATS), np.float32), np.zeros(0, np.int64))


@dataclass
class LeafInstances:
    """One record per leaf or blossom; ``data`` is (k, LEAF_FLOATS) float32."""

    data: np.ndarray

    def __len__(self) -> int:
        return len(self.data)

    @classmethod
    def empty(cls) -> LeafInstances:
        """No leaves."""
        return cls(np.zeros((0, LEAF_FLOATS), np.float32))


def path_distances(segs: Segments) -> tuple[np.ndarray, np.ndarray]:
    """Distance along the branches from the base to each segment's start and end."""
    length = np.linalg.norm(segs.end - segs.start, axis=1)
    end = chain_sum(segs.parent, length) if len(segs) else length
    return end - length, end


def tube_instances(segs: Segments, bark_scale: float = 1.0) -> TubeInstances:
    """Segment records for instanced tubes (radii as set on ``segs``)."""
    m = len(segs)
    if m == 0:
        return TubeInstances.empty()
    wood = wood_rings(segs)
    rings, start = wood.rings, wood.start_ring
    d0, d1 = path_distances(segs)
    reach = max(float(d1.max()), 1e-6)
    data = np.empty((m, TUBE_FLOATS), np.float32)
    data[:, 0:3], data[:, 3:6], data[:, 6:9] = rings.center[start], rings.tangent[start], rings.x[start]
    data[:, 9:12], data[:, 12:15], data[:, 15:18] = rings.center[:m], rings.tangent[:m], rings.x[:m]
    data[:, 18], data[:, 19] = rings.radius[start], rings.radius[:m]
    data[(segs.parent >= 0) & ~segs.continues, 18] *= COLLAR  # (a lateral's start ring is its own)
    roots, trunk = segs.parent < 0, segs.order == 0
    foot, thick = float(segs.start[roots, 1].min()), float(rings.radius[:m][roots].max())  # (its end ring's)
    for col, height in ((18, 1), (19, 10)):  # (a joint's two rings: the same height, the same flare)
        data[trunk, col] *= flare(data[trunk, height] - foot, thick)
    data[:, 20], data[:, 21] = rings.v[start] * bark_scale, rings.v[:m] * bark_scale
    data[:, 22], data[:, 23] = d0 / reach, d1 / reach
    data[:, 24] = 0.0
    data[wood.tips, 24] = 1.0
    data[:, 25] = segs.order
    return TubeInstances(data, segs.module.astype(np.int64))


def flare(height: np.ndarray, radius: float) -> np.ndarray:
    """How much wider than itself the trunk is drawn ``height`` above its foot (scene units), for a trunk
    of ``radius`` there: FLARE[0] at a sapling's foot to FLARE[1] at an old tree's, falling off e-fold
    every FLARE_REACH trunk radii up (a young trunk's flare is a collar at the ground, an old one's
    spreads into its roots)."""
    age = min(max((radius - FLARE_AGED[0]) / (FLARE_AGED[1] - FLARE_AGED[0]), 0.0), 1.0)
    wider = FLARE[0] + (FLARE[1] - FLARE[0]) * age - 1.0
    return (1.0 + wider * np.exp(-np.maximum(height, 0.0) / max(FLARE_REACH * radius, 1e-6))).astype(np.float32)


def leaf_instances(leaves: Leaves, flex: np.ndarray, aspect: float = 0.5) -> LeafInstances:
    """Leaf records: base, axis (H), normal (U), length, width and the wind flex of their twig."""
    k = len(leaves)
    data = np.empty((k, LEAF_FLOATS), np.float32)
    if k == 0:
        return LeafInstances(data)
    data[:, 0:3] = leaves.position
    data[:, 3:6] = leaves.frame[:, :, 0]
    data[:, 6:9] = leaves.frame[:, :, 2]
    data[:, 9] = leaves.size
    data[:, 10] = leaves.size * aspect
    data[:, 11] = flex
    data[:, 12] = np.modf(np.abs(np.sin(leaves.module * 12.9898 + np.arange(k) * 0.618) * 43758.5453))[0]
    return LeafInstances(data)
