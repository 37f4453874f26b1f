"""Landscapes and gardens: many trees as instances of a few meshes (Jung et al. sections 5.1 and 6).

Trees of a few presets are meshed once per resolution level; a landscape places instances of them
(position on a gentle terrain, yaw, scale). Each frame, instances outside the view frustum are culled
and the rest pick a level by their distance to the camera (static LOD): all vectorised.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from arbor.engine.geometry.mesh import LOD_LEVELS, TreeMesh


@dataclass
class Instances:
    """Placed trees: which preset, where, turned and scaled how."""

    preset: np.ndarray  # (n,) int
    position: np.ndarray  # (n, 3)
    yaw: np.ndarray  # (n,) radians
    scale: np.ndarray  # (n,)

    def __len__(self) -> int:
        return len(self.preset)

    def matrices(self) -> np.ndarray:
        """(n, 4, 4) model matrices (rotation about +Y, uniform scale, translation)."""
        c, s, k = np.cos(self.yaw), np.sin(self.yaw), self.scale
        m = np.zeros((len(self), 4, 4))
        m[:, 0, 0], m[:, 0, 2] = c * k, s * k
        m[:, 1, 1] = k
        m[:, 2, 0], m[:, 2, 2] = -s * k, c * k
        m[:, :3, 3] = self.position
        m[:, 3, 3] = 1.0
        return m


def terrain_height(x: np.ndarray, z: np.ndarray, size: float) -> np.ndarray:
    """Gentle rolling hills, about 3 % of the landscape's size high."""
    f = 2 * np.pi / size
    return size * 0.012 * (np.sin(x * f * 1.7) * np.cos(z * f * 1.3) + 0.5 * np.sin((x + z) * f * 3.1))


def terrain_mesh(size: float, cells: int = 96) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A square heightfield centred on the origin: positions, normals, triangle indices."""
    g = np.linspace(-size / 2, size / 2, cells + 1)
    x, z = np.meshgrid(g, g, indexing="xy")
    y = terrain_height(x, z, size)
    pos = np.stack([x, y, z], axis=-1).reshape(-1, 3)
    dy_dx = np.gradient(y, g, axis=1)
    dy_dz = np.gradient(y, g, axis=0)
    n = np.stack([-dy_dx, np.ones_like(y), -dy_dz], axis=-1).reshape(-1, 3)
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    i = np.arange(cells)
    a = (i[:, None] * (cells + 1) + i[None, :]).ravel()
    quads = np.stack([a, a + cells + 1, a + 1, a + 1, a + cells + 1, a + cells + 2], axis=1).reshape(-1, 3)
    return pos.astype(np.float32), n.astype(np.float32), quads.astype(np.uint32)


def scatter(count: int, presets: int, size: float, seed: int = 0, min_gap: float = 0.0) -> Instances:
    """``count`` trees of ``presets`` kinds scattered over a square of side ``size``, on the terrain.

    Positions are jittered grid cells (so trees never pile up); same seed, same landscape.
    """
    rng = np.random.default_rng(seed)
    side = int(np.ceil(np.sqrt(count)))
    cell = size / side
    idx = rng.permutation(side * side)[:count]
    gx, gz = idx % side, idx // side
    jitter = rng.uniform(0.15, 0.85, (count, 2)) * cell
    x = -size / 2 + gx * cell + jitter[:, 0]
    z = -size / 2 + gz * cell + jitter[:, 1]
    position = np.stack([x, terrain_height(x, z, size), z], axis=1)
    return Instances(rng.integers(0, presets, count), position, rng.uniform(0, 2 * np.pi, count),
                     rng.uniform(0.8, 1.25, count))


def frustum_planes(view_projection: np.ndarray) -> np.ndarray:
    """The six planes (a, b, c, d) of a view-projection matrix, normalised, pointing inwards."""
    m = view_projection
    planes = np.array([m[3] + m[0], m[3] - m[0], m[3] + m[1], m[3] - m[1], m[3] + m[2], m[3] - m[2]])
    return planes / np.linalg.norm(planes[:, :3], axis=1, keepdims=True)


def visible(centers: np.ndarray, radii: np.ndarray, view_projection: np.ndarray) -> np.ndarray:
    """Bounding spheres at least partly inside the frustum (conservative: never drops a visible tree)."""
    planes = frustum_planes(view_projection)
    dist = centers @ planes[:, :3].T + planes[:, 3]
    return np.all(dist >= -radii[:, None], axis=1)


def lod_levels(centers: np.ndarray, eye: np.ndarray, tree_height: float,
               thresholds: tuple[float, ...] = (4.0, 10.0, 22.0)) -> np.ndarray:
    """Static LOD: level 0 up close, one level coarser past each threshold (in tree heights)."""
    d = np.linalg.norm(centers - eye, axis=1) / max(tree_height, 1e-9)
    return np.searchsorted(np.asarray(thresholds), d, side="right").clip(0, len(LOD_LEVELS) - 1)


@dataclass
class Preset:
    """One kind of tree: its meshes at every LOD level and its size."""

    name: str
    levels: list[TreeMesh]
    height: float
    radius: float  # bounding sphere radius around (0, height / 2, 0)

    @classmethod
    def from_meshes(cls, name: str, levels: list[TreeMesh]) -> Preset:
        """Size taken from the finest level."""
        pts = np.concatenate([levels[0].wood.positions, levels[0].leaves.positions])
        height = float(pts[:, 1].max())
        center = np.array([0.0, height / 2, 0.0])
        return cls(name, levels, height, float(np.linalg.norm(pts - center, axis=1).max()))
