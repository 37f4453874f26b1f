"""The compiled loops behind mesh.wood_rings and the tube mesher: one pass per segment or ring."""

# numba caches these kernels on disk under this module's name (arbor.engine...) and reloads them while
# this file is unchanged: renaming the module needs a change here too, or the cache names a module gone.

from __future__ import annotations

import math

import numba
import numpy as np


@numba.njit(cache=True, nogil=True, inline="always")
def _unit3(x: float, y: float, z: float) -> tuple[float, float, float]:
    n = math.sqrt(x * x + y * y + z * z)
    return (x / n, y / n, z / n) if n > 1e-12 else (x, y, z)


@numba.njit(cache=True, nogil=True)
def directions(start, end, frame):
    """Unit direction of every segment (its heading where it has no length)."""
    d = np.empty_like(start)
    for j in range(len(start)):
        x, y, z = end[j, 0] - start[j, 0], end[j, 1] - start[j, 1], end[j, 2] - start[j, 2]
        n = math.sqrt(x * x + y * y + z * z)
        if n > 1e-12:
            d[j, 0], d[j, 1], d[j, 2] = x / n, y / n, z / n
        else:  # (row by row: numba's array-to-array assignment is slow to compile, see turtle_kernel.py)
            d[j, 0], d[j, 1], d[j, 2] = frame[j, 0, 0], frame[j, 1, 0], frame[j, 2, 0]
    return d


@numba.njit(cache=True, nogil=True)
def transported_x(d, frame, parent, cont):
    """A ring reference direction per segment, parallel-transported along each axis.

    With x = cos(phi) L + sin(phi) U in each segment's turtle frame, transport across a joint (the
    shortest-arc rotation P from the parent's direction to the child's) only adds the twist
    tau = angle of P(L_parent) in the child's (L, U): so phi is a sum of twists along the axis, one
    number per joint, instead of a product of rotations (parents come before their children)."""
    m = len(d)
    phi, x = np.zeros(m), np.empty((m, 3))
    for j in range(m):
        if cont[j]:
            p = parent[j]
            ax, ay, az, bx, by, bz = d[p, 0], d[p, 1], d[p, 2], d[j, 0], d[j, 1], d[j, 2]
            cx, cy, cz = frame[p, 0, 1], frame[p, 1, 1], frame[p, 2, 1]  # the parent's L, carried
            c = ax * bx + ay * by + az * bz
            if c > -1 + 1e-9:  # the shortest-arc rotation from a to b, applied to the carried L
                wx, wy, wz = ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx
                k = (wx * cx + wy * cy + wz * cz) / (1.0 + c)
                mx = c * cx + (wy * cz - wz * cy) + k * wx
                my = c * cy + (wz * cx - wx * cz) + k * wy
                mz = c * cz + (wx * cy - wy * cx) + k * wz
            else:  # opposite directions: a half turn about a perpendicular
                px, py, pz = _unit3(ay * 0.81 - az * 0.5, az * 0.3 - ax * 0.81, ax * 0.5 - ay * 0.3)
                k = 2 * (px * cx + py * cy + pz * cz)
                mx, my, mz = k * px - cx, k * py - cy, k * pz - cz
            along_l = mx * frame[j, 0, 1] + my * frame[j, 1, 1] + mz * frame[j, 2, 1]
            along_u = mx * frame[j, 0, 2] + my * frame[j, 1, 2] + mz * frame[j, 2, 2]
            phi[j] = phi[p] + math.atan2(along_u, along_l)
        c, s = math.cos(phi[j]), math.sin(phi[j])
        for r in range(3):
            x[j, r] = c * frame[j, r, 1] + s * frame[j, r, 2]
    return x


@numba.njit(cache=True, nogil=True)
def joint_rings(start, end, d, x_axis, radius, radius_end, parent, cont, tip_taper):
    """Every joint ring (see mesh.WoodRings): centre, tangent, reference x, radius and v of ring j < m
    (segment j's end) and of the start rings of axis-starting segments after them; each segment's
    start ring, and the segments that end in a tip."""
    m = len(start)
    child = np.full(m, -1, np.int64)
    n_starts = 0
    for j in range(m):
        if cont[j]:
            child[parent[j]] = j
        else:
            n_starts += 1
    n = m + n_starts
    center, tangent, xs = np.empty((n, 3)), np.empty((n, 3)), np.empty((n, 3))
    radii, vs, step = np.empty(n), np.empty(n), np.empty(m)
    start_ring, tips = np.empty(m, np.int64), np.empty(m, np.int64)
    n_tips, ring = 0, m
    for j in range(m):
        step[j] = step[parent[j]] + 1.0 if cont[j] else 1.0
        for r in range(3):  # (element by element: see turtle_kernel.py)
            center[j, r] = end[j, r]
        c = child[j]
        if c >= 0:
            tx, ty, tz = _unit3(d[j, 0] + d[c, 0], d[j, 1] + d[c, 1], d[j, 2] + d[c, 2])
            bend = d[j, 0] * tx + d[j, 1] * ty + d[j, 2] * tz
            radii[j] = radius_end[j] / min(max(bend, 0.5), 1.0)  # the joint's cut is oblique
            tangent[j, 0], tangent[j, 1], tangent[j, 2] = tx, ty, tz
            for r in range(3):
                xs[j, r] = x_axis[j, r] + x_axis[c, r]
        else:
            radii[j] = radius_end[j] * tip_taper
            for r in range(3):
                tangent[j, r], xs[j, r] = d[j, r], x_axis[j, r]
            tips[n_tips] = j
            n_tips += 1
        vs[j] = step[j]
        if cont[j]:
            start_ring[j] = parent[j]
        else:
            start_ring[j] = ring
            for r in range(3):
                center[ring, r], tangent[ring, r], xs[ring, r] = start[j, r], d[j, r], x_axis[j, r]
            radii[ring], vs[ring] = radius[j], step[j] - 1.0
            ring += 1
    return center, tangent, xs, radii, vs, start_ring, tips[:n_tips]


@numba.njit(cache=True, nogil=True)
def ring_vertices(center, tangent, x, radius, v, n_surf, positions, normals, uvs):
    """``n_surf`` + 1 vertices around every ring (the last repeats the first with u = 1): x made
    perpendicular to the tangent, y = tangent x x, normals pointing out."""
    per = n_surf + 1
    cos, sin = np.empty(per), np.empty(per)
    for k in range(per):
        cos[k], sin[k] = math.cos(2 * math.pi * k / n_surf), math.sin(2 * math.pi * k / n_surf)
    for i in range(len(center)):
        tx, ty, tz = _unit3(tangent[i, 0], tangent[i, 1], tangent[i, 2])
        along = x[i, 0] * tx + x[i, 1] * ty + x[i, 2] * tz
        xx, xy, xz = _unit3(x[i, 0] - along * tx, x[i, 1] - along * ty, x[i, 2] - along * tz)
        yx, yy, yz = ty * xz - tz * xy, tz * xx - tx * xz, tx * xy - ty * xx
        r = radius[i]
        for k in range(per):
            row = i * per + k
            nx, ny, nz = cos[k] * xx + sin[k] * yx, cos[k] * xy + sin[k] * yy, cos[k] * xz + sin[k] * yz
            normals[row, 0], normals[row, 1], normals[row, 2] = nx, ny, nz
            positions[row, 0] = center[i, 0] + r * nx
            positions[row, 1] = center[i, 1] + r * ny
            positions[row, 2] = center[i, 2] + r * nz
            uvs[row, 0], uvs[row, 1] = k / n_surf, v[i]


@numba.njit(cache=True, nogil=True)
def tube_faces(ring_seq, module, n_surf, tips, tip_base, indices, face_module):
    """Two triangles per side between consecutive rings of each segment, (a, a+1, b+1) and
    (a, b+1, b), then a cone of ``n_surf`` triangles from each tip's end ring to its tip vertex."""
    per = n_surf + 1
    f = 0
    for j in range(ring_seq.shape[0]):
        for band in range(ring_seq.shape[1] - 1):
            a, b = ring_seq[j, band] * per, ring_seq[j, band + 1] * per
            for k in range(n_surf):
                indices[f, 0], indices[f, 1], indices[f, 2] = a + k, a + k + 1, b + k + 1
                indices[f + 1, 0], indices[f + 1, 1], indices[f + 1, 2] = a + k, b + k + 1, b + k
                face_module[f] = face_module[f + 1] = module[j]
                f += 2
    for t in range(len(tips)):
        a = tips[t] * per
        for k in range(n_surf):
            indices[f, 0], indices[f, 1], indices[f, 2] = a + k, a + k + 1, tip_base + t
            face_module[f] = module[tips[t]]
            f += 1
