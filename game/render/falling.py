"""Shed branches falling to the ground: a short animation of the pieces a tree just dropped."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from arbor.engine.geometry.instances import LeafInstances, TubeInstances, leaf_instances, tube_instances
from arbor.engine.geometry.mesh import TreeMesh, tree_mesh
from arbor.engine.geometry.turtle import Leaves, Segments, TurtleResult
from arbor.engine.life.form.interpret import leaf_clusters as leaves_clustered
from arbor.engine.life.plant.growth import Fallen

FALL_SECONDS = 2.5  # real seconds a shed branch takes to fall


def _rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    axis = axis / max(float(np.linalg.norm(axis)), 1e-12)
    x, y, z = axis
    k = np.array([[0, -z, y], [z, 0, -x], [-y, x, 0]])
    return np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * (k @ k)


@dataclass
class StaticView:
    """Records of a tree part that does not grow (the shape a renderer needs from a view)."""

    tubes: TubeInstances
    leaves: LeafInstances
    blossoms: LeafInstances
    lo: np.ndarray
    hi: np.ndarray
    fruits: LeafInstances = field(default_factory=LeafInstances.empty)
    stones: LeafInstances = field(default_factory=LeafInstances.empty)

    @property
    def young_row(self) -> int:
        """Nothing here grows: no young block."""
        return len(self.tubes)

    @property
    def young_leaf_row(self) -> int:
        """Nothing here grows: no young block."""
        return len(self.leaves)


def falling_view(fallen: Fallen, progress: float) -> StaticView:
    """Instance records of a shed branch at ``progress`` of its fall (see :func:`falling_pieces`)."""
    segs, leaves = falling_pieces(fallen, progress)
    tubes = tube_instances(segs)
    points = np.concatenate([segs.start, segs.end, leaves.position]) if len(segs) else np.zeros((1, 3))
    return StaticView(tubes, leaf_instances(leaves_clustered(leaves), np.ones(3 * len(leaves))),
                      LeafInstances.empty(), points.min(axis=0), points.max(axis=0))


def falling_mesh(fallen: Fallen, progress: float) -> TreeMesh:
    """The branch ``fallen`` at ``progress`` as a mesh (for pictures and tests)."""
    segs, leaves = falling_pieces(fallen, progress)
    return tree_mesh(TurtleResult(segs, leaves, _no_leaves()))


def falling_pieces(fallen: Fallen, progress: float) -> tuple[Segments, Leaves]:
    """The branch ``fallen`` at ``progress`` (0 = where it broke off, 1 = on the ground): it tips over
    outward about its base while it drops, leaves first shrinking away."""
    segs, leaves = fallen.segments, fallen.leaves
    if len(segs) == 0:
        return segs, leaves
    pivot = segs.start[0]
    outward = segs.end.mean(axis=0) - pivot
    outward[1] = 0.0
    if np.linalg.norm(outward) < 1e-6:
        outward = np.array([1.0, 0.0, 0.0])
    turn = _rotation(np.cross(np.array([0.0, 1.0, 0.0]), outward), np.radians(75.0) * progress**2)
    lowest = float(min(((segs.start - pivot) @ turn.T)[:, 1].min(), ((segs.end - pivot) @ turn.T)[:, 1].min()))
    drop = np.array([0.0, -max(float(pivot[1]) + lowest, 0.0) * progress**2, 0.0])  # it lands on the ground
    move = lambda p: (p - pivot) @ turn.T + pivot + drop  # noqa: E731
    frames = np.einsum("ij,kjl->kil", turn, segs.frame)
    moved = Segments(move(segs.start), move(segs.end), segs.radius, segs.radius_end, frames, segs.order,
                     segs.module, segs.parent, segs.continues, segs.colour)
    keep = max(0.0, 1.0 - 1.6 * progress)
    leaf_frames = np.einsum("ij,kjl->kil", turn, leaves.frame) if len(leaves) else leaves.frame
    moved_leaves = Leaves(move(leaves.position) if len(leaves) else leaves.position, leaf_frames,
                          leaves.size * keep, leaves.module)
    return moved, moved_leaves


def _no_leaves() -> Leaves:
    return Leaves(np.zeros((0, 3)), np.zeros((0, 3, 3)), np.zeros(0), np.zeros(0, np.int64))
