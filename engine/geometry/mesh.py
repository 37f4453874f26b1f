"""Tree meshes from turtle segments: generalized cylinders, leaf quads, multi-resolution levels.

Wood is one tube per axis: one ring of ``n_surf`` vertices per joint, shared by the two segments that
meet there, so there are no hidden caps inside the wood (the tamagotchi thesis, 6.7); only branch tips get a cap.
Ring frames are parallel-transported along each axis (products of minimal rotations, in one compiled
pass: engine.geometry.mesh_kernel), so tubes do not twist when the turtle rolls. With ``n_div`` > 1
each segment is a cubic Bezier whose control points sit a third of the way along, bent to match the
joint tangents (the form of Jung et al. eq. 2). UVs: u around the branch, v along it, one unit per growth step.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from arbor.engine.geometry.chains import chain_sum
from arbor.engine.geometry.turtle import Leaves, Segments, TurtleResult


@dataclass
class Mesh:
    """An indexed triangle mesh; ``face_module`` maps each triangle back to its L-string module."""

    positions: np.ndarray  # (V, 3) float32
    normals: np.ndarray  # (V, 3) float32
    uvs: np.ndarray  # (V, 2) float32
    indices: np.ndarray  # (F, 3) uint32
    face_module: np.ndarray  # (F,) int32 (module indices; strings stay far below 2^31 modules)

    @property
    def n_triangles(self) -> int:
        """Number of triangles."""
        return len(self.indices)

    @classmethod
    def empty(cls) -> Mesh:
        """A mesh with nothing in it."""
        z = np.zeros((0, 3), np.float32)
        return cls(z, z.copy(), np.zeros((0, 2), np.float32), np.zeros((0, 3), np.uint32), np.zeros(0, np.int32))


@dataclass
class TreeMesh:
    """The meshes of one tree: wood, leaves and blossoms (separate materials)."""

    wood: Mesh
    leaves: Mesh
    blossoms: Mesh

    @property
    def n_triangles(self) -> int:
        """Triangles over all parts."""
        return self.wood.n_triangles + self.leaves.n_triangles + self.blossoms.n_triangles


@dataclass(frozen=True)
class LodLevel:
    """One resolution level (Jung et al., 5.1): sides per ring, Bezier steps, thinnest twig kept."""

    n_surf: int
    n_div: int
    min_radius_fraction: float  # twigs thinner than this fraction of the trunk radius are dropped
    leaf_fraction: float = 1.0  # share of leaves kept (kept leaves grow to cover the same area)


LOD_LEVELS = (
    LodLevel(8, 3, 0.0),
    LodLevel(6, 2, 0.02),
    LodLevel(4, 1, 0.05, 0.5),
    LodLevel(3, 1, 0.12, 0.25),
)


def lod_level(lod: int) -> LodLevel:
    """The mesh level for LOD ``lod`` (0 the finest), clamped to the levels there are: the one place a level
    number becomes a :class:`LodLevel` (build_geometry, grow_geometry, a save's roots)."""
    return LOD_LEVELS[max(0, min(int(lod), len(LOD_LEVELS) - 1))]


def _normalize(v: np.ndarray) -> np.ndarray:
    n = np.sqrt(np.einsum("...i,...i->...", v, v))[..., None]
    return v / np.where(n > 1e-12, n, 1.0)


def prune_thin(segs: Segments, min_radius: float) -> Segments:
    """Segments with radius >= min_radius whose whole path to the root is kept (no floating twigs)."""
    if min_radius <= 0:
        return segs
    dropped = (segs.radius < min_radius).astype(np.int64)
    keep = chain_sum(segs.parent, dropped) == 0
    new_index = np.cumsum(keep) - 1
    parent = np.where(segs.parent[keep] >= 0, new_index[np.maximum(segs.parent[keep], 0)], -1)
    fields = {name: getattr(segs, name)[keep] for name in segs.__dataclass_fields__}
    fields["parent"] = parent
    return Segments(**fields)


@dataclass
class WoodRings:
    """Every joint ring of the wood, shared by the segments that meet there: ring j (< m) is segment j's
    end ring; ``start_ring[j]`` is its start ring (its parent's end ring when it continues that axis)."""

    rings: _Rings
    start_ring: np.ndarray  # (m,)
    tips: np.ndarray  # segments whose end is a branch tip (they get a cone)
    direction: np.ndarray  # (m, 3) unit direction of each segment


def wood_rings(segs: Segments, tip_taper: float = 0.35) -> WoodRings:
    """Joint rings with twist-free reference directions (see module docstring); the mesher and the
    game's instanced tubes both build on them."""
    from arbor.engine.geometry.mesh_kernel import directions, joint_rings, transported_x

    d = directions(segs.start, segs.end, segs.frame)
    x_axis = transported_x(d, segs.frame, segs.parent, segs.continues)
    *ring_rows, start_ring, tips = joint_rings(segs.start, segs.end, d, x_axis, segs.radius, segs.radius_end,
                                               segs.parent, segs.continues, tip_taper)
    return WoodRings(_Rings(*ring_rows), start_ring, tips, d)


def wood_mesh(segs: Segments, n_surf: int = 8, n_div: int = 1, tip_taper: float = 0.35) -> Mesh:
    """Generalized-cylinder mesh of all segments (see module docstring)."""
    m = len(segs)
    if m == 0:
        return Mesh.empty()
    wood = wood_rings(segs, tip_taper)
    rings, start_ring, d = wood.rings, wood.start_ring, wood.direction
    if n_div > 1:
        ring_seq = _bezier_rings(rings, start_ring, np.arange(m), n_div)
    else:
        ring_seq = np.stack([start_ring, np.arange(m)], axis=1)
    return _tube_mesh(rings, ring_seq, segs.module, n_surf, tips=wood.tips, tip_dir=d)


@dataclass
class _Rings:
    center: np.ndarray
    tangent: np.ndarray
    x: np.ndarray
    radius: np.ndarray
    v: np.ndarray

    def extend(self, other: _Rings) -> int:
        base = len(self.center)
        for name in ("center", "tangent", "x", "radius", "v"):
            setattr(self, name, np.concatenate([getattr(self, name), getattr(other, name)]))
        return base


def _bezier_rings(rings: _Rings, start_ring: np.ndarray, end_ring: np.ndarray, n_div: int) -> np.ndarray:
    """Insert n_div-1 rings per segment along a cubic Bezier; returns (m, n_div+1) ring indices."""
    p0, p3 = rings.center[start_ring], rings.center[end_ring]
    length = np.linalg.norm(p3 - p0, axis=1)[:, None]
    t0, t3 = rings.tangent[start_ring], rings.tangent[end_ring]
    p1, p2 = p0 + t0 * length / 3, p3 - t3 * length / 3
    t = (np.arange(1, n_div) / n_div)[None, :, None]
    s = 1 - t
    pts = s**3 * p0[:, None] + 3 * s * s * t * p1[:, None] + 3 * s * t * t * p2[:, None] + t**3 * p3[:, None]
    tan = 3 * s * s * (p1 - p0)[:, None] + 6 * s * t * (p2 - p1)[:, None] + 3 * t * t * (p3 - p2)[:, None]
    tan = _normalize(np.where(length[:, None] > 1e-12, tan, t0[:, None]))
    tt = t[..., 0]
    x = (1 - tt)[..., None] * rings.x[start_ring][:, None] + tt[..., None] * rings.x[end_ring][:, None]
    r = (1 - tt) * rings.radius[start_ring][:, None] + tt * rings.radius[end_ring][:, None]
    v = (1 - tt) * rings.v[start_ring][:, None] + tt * rings.v[end_ring][:, None]
    inner = _Rings(pts.reshape(-1, 3), tan.reshape(-1, 3), x.reshape(-1, 3), r.ravel(), v.ravel())
    base = rings.extend(inner)
    m = len(start_ring)
    mid = base + np.arange(m * (n_div - 1)).reshape(m, n_div - 1)
    return np.concatenate([start_ring[:, None], mid, end_ring[:, None]], axis=1)


def _tube_mesh(rings: _Rings, ring_seq: np.ndarray, module: np.ndarray, n_surf: int, tips, tip_dir) -> Mesh:
    """Vertices for every ring, quads between consecutive rings of each segment, cones at tips."""
    from arbor.engine.geometry.mesh_kernel import ring_vertices, tube_faces

    n_rings = len(rings.center)
    ring_end = n_rings * (n_surf + 1)
    positions = np.empty((ring_end + len(tips), 3), np.float32)
    normals, uvs = np.empty_like(positions), np.empty((len(positions), 2), np.float32)
    ring_vertices(rings.center, rings.tangent, rings.x, rings.radius, rings.v, n_surf, positions, normals, uvs)
    tip_dir = np.take(tip_dir, tips, axis=0)
    positions[ring_end:] = np.take(rings.center, tips, axis=0) + tip_dir * (2.0 * rings.radius[tips, None])
    normals[ring_end:] = tip_dir
    uvs[ring_end:, 0] = 0.5
    uvs[ring_end:, 1] = rings.v[tips] + 0.5
    n_faces = (ring_seq.shape[0] * (ring_seq.shape[1] - 1) * 2 + len(tips)) * n_surf
    indices, face_module = np.empty((n_faces, 3), np.uint32), np.empty(n_faces, np.int32)
    tube_faces(ring_seq.astype(np.int64), module.astype(np.int32), n_surf, tips, ring_end, indices, face_module)
    return Mesh(positions, normals, uvs, indices, face_module)


def leaf_mesh(leaves: Leaves, aspect: float = 0.5, fraction: float = 1.0, seed: int = 0) -> Mesh:
    """One textured quad per leaf: from the leaf's base along H, as wide as ``aspect`` x its size.

    With ``fraction`` < 1 a deterministic subset is kept and grown so the crown covers the same area.
    """
    if fraction < 1.0 and len(leaves):
        keep = np.random.default_rng(seed).random(len(leaves)) < fraction
        scale = 1.0 / np.sqrt(fraction)
        leaves = Leaves(leaves.position[keep], leaves.frame[keep], leaves.size[keep] * scale, leaves.module[keep])
    k = len(leaves)
    if k == 0:
        return Mesh.empty()
    h, lft, up = leaves.frame[:, :, 0], leaves.frame[:, :, 1], leaves.frame[:, :, 2]
    s = leaves.size[:, None]
    half = lft * s * aspect * 0.5
    p = leaves.position
    corners = np.stack([p - half, p + half, p + half + h * s, p - half + h * s], axis=1)
    normals = np.repeat(up[:, None], 4, axis=1)
    uvs = np.broadcast_to(np.array([[0, 0], [1, 0], [1, 1], [0, 1]], np.float32), (k, 4, 2))
    base = (np.arange(k) * 4)[:, None]
    idx = np.concatenate([base + np.array([0, 1, 2]), base + np.array([0, 2, 3])], axis=1).reshape(-1, 3)
    return Mesh(corners.reshape(-1, 3).astype(np.float32), normals.reshape(-1, 3).astype(np.float32),
                uvs.reshape(-1, 2).astype(np.float32), idx.astype(np.uint32),
                np.repeat(leaves.module.astype(np.int32), 2))


def tree_mesh(result: TurtleResult, level: LodLevel = LOD_LEVELS[0]) -> TreeMesh:
    """All meshes of a tree at one resolution level."""
    segs = result.segments
    trunk = float(segs.radius.max(initial=0.0))
    segs = prune_thin(segs, level.min_radius_fraction * trunk)
    return TreeMesh(
        wood_mesh(segs, level.n_surf, level.n_div),
        leaf_mesh(result.leaves, fraction=level.leaf_fraction),
        leaf_mesh(result.blossoms, aspect=1.0, fraction=level.leaf_fraction, seed=1),
    )


def merge_meshes(meshes: list[Mesh], offsets: list[np.ndarray]) -> Mesh:
    """One mesh from several, each moved by its offset (several trees drawn as one)."""
    base = np.cumsum([0] + [len(m.positions) for m in meshes[:-1]])
    return Mesh(
        np.concatenate([m.positions + np.asarray(o, np.float32) for m, o in zip(meshes, offsets, strict=True)]),
        np.concatenate([m.normals for m in meshes]),
        np.concatenate([m.uvs for m in meshes]),
        np.concatenate([m.indices + np.uint32(b) for m, b in zip(meshes, base, strict=True)]),
        np.concatenate([m.face_module for m in meshes]),
    )


def merge_trees(trees: list[TreeMesh], offsets: list[np.ndarray]) -> TreeMesh:
    """Several trees' meshes as one scene's (wood with wood, leaves with leaves)."""
    return TreeMesh(*(merge_meshes([getattr(t, part) for t in trees], offsets)
                      for part in ("wood", "leaves", "blossoms")))
