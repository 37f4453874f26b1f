"""The numpy wood mesher (n_div = 1) as it was before engine/geometry/mesh_kernel.py."""

from __future__ import annotations

import numpy as np

from arbor.engine.geometry.mesh import Mesh, WoodRings, _normalize, _Rings  # (unchanged: the engine's own)
from benchmarks.numpy_geometry.chains import chain_sum, tree_depths
from benchmarks.numpy_geometry.turtle import Segments


def _row_norms(rows: np.ndarray) -> np.ndarray:
    """Lengths of the column vectors of (3, n) rows (1 where a vector is ~zero, so dividing keeps it)."""
    n = np.sqrt(rows[0] * rows[0] + rows[1] * rows[1] + rows[2] * rows[2])
    return np.where(n > 1e-12, n, 1.0)


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row-wise cross products of (n, 3) arrays (np.cross is several times slower on many short rows)."""
    out = np.empty(np.broadcast_shapes(a.shape, b.shape))
    for i, j, k in ((0, 1, 2), (1, 2, 0), (2, 0, 1)):
        np.subtract(a[:, j] * b[:, k], a[:, k] * b[:, j], out=out[:, i])
    return out


def _directions(segs: Segments) -> np.ndarray:
    d = segs.end - segs.start
    length = np.linalg.norm(d, axis=1)
    heading = segs.frame[:, :, 0]
    return np.where((length > 1e-12)[:, None], d / np.maximum(length, 1e-12)[:, None], heading)


def wood_rings(segs: Segments, tip_taper: float = 0.35) -> WoodRings:
    """Joint rings with twist-free reference directions (see module docstring); the mesher and the
    game's instanced tubes both build on them."""
    m = len(segs)
    d = _directions(segs)
    cont = segs.continues
    child = np.full(m, -1, dtype=np.int64)
    child[segs.parent[cont]] = np.flatnonzero(cont)
    has_child = child >= 0
    x_axis = _transported_x(segs, d)
    # rings: index 0..m-1 = end ring of segment j; m.. = start rings of axis-starting segments
    starts = np.flatnonzero(~cont)
    tangent_end = np.where(has_child[:, None], _normalize(d + d[np.maximum(child, 0)]), d)
    bend = np.einsum("ni,ni->n", d, tangent_end)
    r_end = segs.radius_end / np.clip(bend, 0.5, 1.0)
    r_end = np.where(has_child, r_end, segs.radius_end * tip_taper)
    x_end = np.where(has_child[:, None], x_axis + x_axis[np.maximum(child, 0)], x_axis)
    centers = np.concatenate([segs.end, segs.start[starts]])
    tangents = np.concatenate([tangent_end, d[starts]])
    xs = np.concatenate([x_end, x_axis[starts]])
    radii = np.concatenate([r_end, segs.radius[starts]])
    step = tree_depths(np.where(cont, segs.parent, -1)) + 1.0  # growth steps along the axis
    vs = np.concatenate([step, step[starts] - 1.0])
    start_ring = np.empty(m, dtype=np.int64)
    start_ring[cont] = segs.parent[cont]
    start_ring[starts] = m + np.arange(len(starts))
    return WoodRings(_Rings(centers, tangents, xs, radii, vs), start_ring, np.flatnonzero(~has_child), d)


def wood_mesh(segs: Segments, n_surf: int = 8, n_div: int = 1, tip_taper: float = 0.35) -> Mesh:
    """Generalized-cylinder mesh of all segments (see module docstring)."""
    m = len(segs)
    if m == 0:
        return Mesh.empty()
    wood = wood_rings(segs, tip_taper)
    rings, start_ring, d = wood.rings, wood.start_ring, wood.direction
    ring_seq = np.stack([start_ring, np.arange(m)], axis=1)  # n_div = 1 only
    return _tube_mesh(rings, ring_seq, segs.module, n_surf, tips=wood.tips, tip_dir=d)


def _transported_x(segs: Segments, d: np.ndarray) -> np.ndarray:
    """A ring reference direction per segment, parallel-transported along each axis.

    With x = cos(phi) L + sin(phi) U in each segment's turtle frame, transport across a joint (the
    shortest-arc rotation P from the parent's direction to the child's) only adds the twist
    tau = angle of P(L_parent) in the child's (L, U): so phi is a chain sum of twists, one number
    per joint, instead of a product of rotations.
    """
    cont = segs.continues
    chain = np.where(cont, segs.parent, -1)
    lft, up = segs.frame[:, :, 1], segs.frame[:, :, 2]
    angle = np.zeros(len(segs))
    ci = np.flatnonzero(cont)
    pi_ = segs.parent[ci]
    a, b, carried = d[pi_], d[ci], lft[pi_]
    w = _cross(a, b)
    c = np.einsum("ni,ni->n", a, b)
    ok = c > -1 + 1e-9
    moved = c[:, None] * carried + _cross(w, carried)
    moved += (np.einsum("ni,ni->n", w, carried) / np.where(ok, 1.0 + c, 1.0))[:, None] * w
    if not ok.all():  # opposite directions: a half turn about a perpendicular
        p = _normalize(_cross(a[~ok], np.array([[0.3, 0.5, 0.81]])))
        moved[~ok] = 2 * np.einsum("ni,ni->n", p, carried[~ok])[:, None] * p - carried[~ok]
    angle[ci] = np.arctan2(np.einsum("ni,ni->n", moved, up[ci]), np.einsum("ni,ni->n", moved, lft[ci]))
    phi = chain_sum(chain, angle)
    return np.cos(phi)[:, None] * lft + np.sin(phi)[:, None] * up


def _ring_weights(n_surf: int) -> tuple[np.ndarray, np.ndarray]:
    """Matrices that turn per-ring (x, y) and (center, r x, r y) rows into a whole ring's flattened
    vertex normals and positions with one matrix product each (BLAS, not small-array broadcasting)."""
    ang = np.linspace(0.0, 2 * np.pi, n_surf + 1)
    eye = np.eye(3, dtype=np.float32)
    around = np.stack([np.cos(ang), np.sin(ang)]).astype(np.float32)  # (2, per)
    normal_w = np.einsum("kp,cd->kcpd", around, eye).reshape(6, -1)
    pos_w = np.concatenate([np.tile(eye, (1, n_surf + 1)), normal_w])
    return normal_w, pos_w


def _tube_mesh(rings: _Rings, ring_seq: np.ndarray, module: np.ndarray, n_surf: int, tips, tip_dir) -> Mesh:
    """Vertices for every ring, quads between consecutive rings of each segment, cones at tips."""
    n_rings = len(rings.center)
    per = n_surf + 1
    n_tips = len(tips)
    # ring frames on rows (3, n): whole-row operations instead of many 3-vectors
    tan, x = rings.tangent.T.copy(), rings.x.T.copy()
    tan /= _row_norms(tan)
    x -= (x[0] * tan[0] + x[1] * tan[1] + x[2] * tan[2]) * tan
    x /= _row_norms(x)
    rows = np.empty((15, n_rings), np.float32)  # x, y, centre, r x, r y
    rows[0:3] = x
    rows[3:6] = (tan[1] * x[2] - tan[2] * x[1], tan[2] * x[0] - tan[0] * x[2], tan[0] * x[1] - tan[1] * x[0])
    rows[6:9] = rings.center.T
    radius = rings.radius.astype(np.float32)
    np.multiply(rows[0:6], radius, out=rows[9:15])
    normal_w, pos_w = _ring_weights(n_surf)
    positions = np.empty((n_rings * per + n_tips, 3), np.float32)
    normals = np.empty_like(positions)
    np.matmul(rows[0:6].T, normal_w, out=normals[: n_rings * per].reshape(n_rings, per * 3))
    np.matmul(rows[6:15].T, pos_w, out=positions[: n_rings * per].reshape(n_rings, per * 3))
    uvs = np.empty((len(positions), 2), np.float32)
    uv_w = np.zeros((2, per, 2), np.float32)  # (1, v) -> u around the ring, v along the branch
    uv_w[0, :, 0], uv_w[1, :, 1] = np.linspace(0.0, 1.0, per), 1.0
    ones_v = np.stack([np.ones(n_rings, np.float32), rings.v.astype(np.float32)], axis=1)
    np.matmul(ones_v, uv_w.reshape(2, -1), out=uvs[: n_rings * per].reshape(n_rings, per * 2))
    tip_dir = np.take(tip_dir, tips, axis=0)
    positions[n_rings * per :] = np.take(rings.center, tips, axis=0) + tip_dir * (2.0 * rings.radius[tips, None])
    normals[n_rings * per :] = tip_dir
    uvs[n_rings * per :, 0] = 0.5
    uvs[n_rings * per :, 1] = rings.v[tips] + 0.5
    return Mesh(positions, normals, uvs, _tube_indices(ring_seq, n_surf, tips, n_rings * per),
                _face_modules(module, ring_seq, n_surf, tips))


def _tube_indices(ring_seq: np.ndarray, n_surf: int, tips: np.ndarray, tip_base: int) -> np.ndarray:
    """Two triangles per side between consecutive rings, (a, a+1, b+1) and (a, b+1, b), then tip cones."""
    per = n_surf + 1
    seq = ring_seq.astype(np.uint32) * np.uint32(per)
    pairs = np.stack([seq[:, :-1], seq[:, 1:]], axis=-1)  # ring starts (a, b) of every band
    side = np.repeat(np.arange(n_surf, dtype=np.uint32), 6)
    which = np.tile(np.array([0, 0, 1, 0, 1, 1]), n_surf)  # a or b, per corner
    offset = side + np.tile(np.array([0, 1, 1, 0, 1, 0], np.uint32), n_surf)
    n_quads = pairs.shape[0] * pairs.shape[1] * n_surf * 2
    out = np.empty((n_quads + len(tips) * n_surf, 3), np.uint32)
    quads = out[:n_quads].reshape(*pairs.shape[:2], 6 * n_surf)
    np.take(pairs, which, axis=-1, out=quads, mode="clip")  # 'raise' would buffer all of out
    quads += offset
    caps = out[n_quads:].reshape(len(tips), n_surf, 3)
    ring_base = tips.astype(np.uint32)[:, None] * np.uint32(per) + np.arange(n_surf, dtype=np.uint32)
    caps[..., 0] = ring_base
    caps[..., 1] = ring_base + 1
    caps[..., 2] = (tip_base + np.arange(len(tips), dtype=np.uint32))[:, None]
    return out


def _face_modules(module: np.ndarray, ring_seq: np.ndarray, n_surf: int, tips: np.ndarray) -> np.ndarray:
    module = module.astype(np.int32)
    tube = np.repeat(module, 2 * n_surf * (ring_seq.shape[1] - 1))
    return np.concatenate([tube, np.repeat(module[tips], n_surf)])


