"""Lobes (Zhang et al. section 4): the crown drawn as a few closed strokes, as closed meshes.

Closed strokes drawn around the crown at different heights are sampled by eq. 1 (key points where they
bend, a smooth curve through them), ordered along the lobe's axis and given the same number of points
by arc-length interpolation; rings tilted past their neighbours are
tilted less so strips cannot fold over; each loop starts at the point whose barycentric direction
(eq. 2) is closest to the previous loop's start; strips join neighbouring loops and fans close both
ends, every triangle wound the same way, outwards: a closed manifold. One silhouette
drawn on a plane becomes a lobe through horizontal rings. Lobes can be moved, scaled, turned,
squeezed and have stroke points dragged, with undo; ``Crossings`` tests points against many lobes.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from arbor.engine.geometry.turtle import unit
from arbor.engine.modeling.strokes import ArcLengthSpline, adaptive_sample


def resample_loop(points: np.ndarray, count: int) -> np.ndarray:
    """A closed stroke with ``count`` points evenly spaced along its length."""
    closed = np.concatenate([points, points[:1]])
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(closed, axis=0), axis=1))])
    t = np.linspace(0.0, s[-1], count, endpoint=False)
    return np.stack([np.interp(t, s, closed[:, c]) for c in range(3)], axis=1)


def sampled_loop(points: np.ndarray) -> np.ndarray:
    """A drawn closed stroke through its key points (Zhang et al. eq. 1: dense where it bends, sparse where
    it runs straight, jitter averaged away) and a smooth curve through them (the first key closes it)."""
    if len(points) < 8:
        return points
    closed = np.concatenate([points, points[:1]])
    keys = closed[adaptive_sample(closed)][:-1]  # (the last key is the first point again)
    if len(keys) < 4:
        return points
    curve = ArcLengthSpline(np.concatenate([keys, keys[:1]]))
    return curve.at(np.linspace(0.0, curve.length, 4 * len(keys), endpoint=False))


def barycentric_directions(loop: np.ndarray) -> np.ndarray:
    """Eq. 2: for each point p_i, normalize(sum over k != i of (p_k - p_i))."""
    return unit(loop.sum(axis=0)[None, :] - len(loop) * loop)


@dataclass(eq=False)  # lobes compare by identity (their arrays have no single truth value)
class Lobe:
    """A closed triangle mesh around part of the crown: ``rings`` stitched strokes of ``ring_size``
    points each (the first vertices, ring by ring), then the two cap centres, then the inner points
    of open strokes that close an end."""

    vertices: np.ndarray
    faces: np.ndarray
    ring_size: int = 0
    rings: int = 0  # vertices: rings x ring_size stroke points, 2 cap centres, then open-stroke points

    @property
    def stroke_rings(self) -> np.ndarray:
        """The closed strokes' points, (rings, ring_size, 3)."""
        return self.vertices[: self.rings * self.ring_size].reshape(self.rings, self.ring_size, 3)

    def transformed(self, move=(0.0, 0.0, 0.0), scale: float = 1.0, turn_deg: float = 0.0) -> Lobe:
        """Moved, scaled about its centre and turned about the vertical through it (lobe editing)."""
        centre = self.vertices.mean(axis=0)
        a = np.radians(turn_deg)
        rot = np.array([[np.cos(a), 0.0, np.sin(a)], [0.0, 1.0, 0.0], [-np.sin(a), 0.0, np.cos(a)]])
        moved = (self.vertices - centre) @ rot.T * scale + centre + np.asarray(move, float)
        return Lobe(moved, self.faces, self.ring_size, self.rings)

    def squeezed(self, at, radius: float, amount: float) -> Lobe:
        """Seed 004's lobe editing as Laplacian surface editing: the surface nearest ``at`` (within a
        third of ``radius``) is pulled towards the lobe's centre by ``amount`` (0..1; negative pushes
        out), the surface beyond ``radius`` stays, and everything between follows so as to keep its
        shape (its Laplacian coordinates), in the least-squares sense."""
        d = np.linalg.norm(self.vertices - np.asarray(at, float), axis=1)
        centre = self.vertices.mean(axis=0)
        handle = np.flatnonzero(d <= radius / 3)
        if not len(handle):
            handle = np.array([int(np.argmin(d))])
        pull = (1.0 - (d[handle] / radius) ** 2)[:, None]
        targets = self.vertices[handle] + amount * pull * (centre - self.vertices[handle])
        fixed = np.flatnonzero(d > radius)
        return self._with_rings(laplacian_edit(self.vertices, self.faces, handle, targets, fixed))

    def dragged(self, ring: int, index: int, to, width: int = 4) -> Lobe:
        """One stroke point dragged to ``to`` by Laplacian surface editing (Zhang et al., as for squeeze):
        the point goes exactly there, the surface farther than the stroke point ``width + 1`` steps
        along its stroke stays, and the surface between follows, keeping its shape as well as it can."""
        n = self.ring_size
        point = ring * n + index
        rings = self.stroke_rings
        reach = max(np.linalg.norm(rings[ring, (index + side * (width + 1)) % n] - rings[ring, index])
                    for side in (-1, 1))
        d = np.linalg.norm(self.vertices - self.vertices[point], axis=1)
        fixed = np.flatnonzero(d > reach)
        moved = laplacian_edit(self.vertices, self.faces, np.array([point]), np.asarray(to, float)[None], fixed)
        return self._with_rings(moved)

    def _with_rings(self, vertices: np.ndarray) -> Lobe:
        """The lobe with new vertices; cap centres follow their rings. The triangles keep their
        (consistent) winding, flipped all together if the edit turned the lobe inside out."""
        vertices = vertices.copy()
        if self.rings:
            cap = self.rings * self.ring_size
            rings = vertices[:cap].reshape(-1, self.ring_size, 3)
            vertices[cap], vertices[cap + 1] = rings[0].mean(axis=0), rings[-1].mean(axis=0)
        tri = vertices[self.faces]
        volume = np.einsum("ij,ij->", tri[:, 0], np.cross(tri[:, 1], tri[:, 2]))
        faces = self.faces if volume >= 0 else self.faces[:, ::-1].copy()
        return Lobe(vertices, faces, self.ring_size, self.rings)

    @cached_property
    def volume(self) -> float:
        """The enclosed volume (divergence theorem over the outward faces), for sharing a budget."""
        a, b, c = (self.vertices[self.faces[:, k]] for k in range(3))
        return abs(float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum()) / 6.0)

    def contains(self, points: np.ndarray) -> np.ndarray:
        """True for points inside the lobe."""
        return self._crossings.inside(points) == 0

    @cached_property
    def _crossings(self) -> Crossings:
        return Crossings([self])  # triangle terms computed once per lobe (lobes are never changed)

    def sample_inside(self, count: int, rng: np.random.Generator) -> np.ndarray:
        """``count`` points uniformly inside (rejection sampling in the bounding box)."""
        lo, hi = self.vertices.min(axis=0), self.vertices.max(axis=0)
        found: list[np.ndarray] = []
        for _ in range(64):
            cand = rng.uniform(lo, hi, (max(2 * count, 64), 3))
            found.append(cand[self.contains(cand)])
            if sum(len(f) for f in found) >= count:
                break
        return np.concatenate(found)[:count]


class Crossings:
    """Inside test for a set of lobes by the parity of crossings along a ray in +x, done as a 2D
    point-in-triangle test in the y-z plane (vectorised over points and all lobes' triangles).

    Triangles are binned on a ``GRID`` x ``GRID`` grid over their y-z boxes, so a point is tested
    only against the triangles of its cell (a few dozen of a thousand).
    """

    GRID = 24

    def __init__(self, lobes: list[Lobe]) -> None:
        tri = np.concatenate([lobe.vertices[lobe.faces] for lobe in lobes])
        self.lobe = np.repeat(np.arange(len(lobes)), [len(lobe.faces) for lobe in lobes])
        self.count = len(lobes)
        self.p0 = tri[:, 0]
        self.e1, self.e2 = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
        det = self.e1[:, 1] * self.e2[:, 2] - self.e1[:, 2] * self.e2[:, 1]
        ok = np.abs(det) > 1e-15  # triangles seen edge-on from the ray are never crossed
        self.inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
        self.tri_lo, self.tri_hi = tri.min(axis=1), tri.max(axis=1)
        self.lo, self.hi = tri.min(axis=(0, 1)), tri.max(axis=(0, 1))
        self.nudge = np.array([3.7e-9, 7.1e-9]) * max(float(np.max(self.hi - self.lo)), 1e-6)
        self._bin(np.flatnonzero(ok))

    def _cells(self, yz: np.ndarray) -> np.ndarray:
        """Grid cell coordinates (clipped) of y-z points, (k, 2)."""
        span = np.maximum(self.hi[1:] - self.lo[1:], 1e-12)
        return np.clip(((yz - self.lo[1:]) / span * self.GRID).astype(np.int64), 0, self.GRID - 1)

    def _bin(self, usable: np.ndarray) -> None:
        """CSR lists of the triangles whose y-z box touches each cell."""
        c0, c1 = self._cells(self.tri_lo[usable, 1:]), self._cells(self.tri_hi[usable, 1:])
        ny, nz = c1[:, 0] - c0[:, 0] + 1, c1[:, 1] - c0[:, 1] + 1
        tri = np.repeat(usable, ny * nz)
        k = _ranges(ny * nz)  # position of each (triangle, cell) pair within its triangle's box
        rep_nz = np.repeat(nz, ny * nz)
        cell = (np.repeat(c0[:, 0], ny * nz) + k // rep_nz) * self.GRID + np.repeat(c0[:, 1], ny * nz) + k % rep_nz
        order = np.argsort(cell, kind="stable")
        self.cell_tris = tri[order]
        self.cell_start = np.searchsorted(cell[order], np.arange(self.GRID * self.GRID + 1))

    def inside(self, points: np.ndarray) -> np.ndarray:
        """Index of a lobe containing each point, -1 for points outside all of them."""
        which = np.full(len(points), -1, np.int64)
        rows = np.flatnonzero(np.all((points >= self.lo) & (points <= self.hi), axis=1))
        if len(rows) == 0:
            return which
        # a tiny odd offset keeps the ray off shared edges and vertices (points on a ring's plane)
        yz = points[rows, 1:] + self.nudge
        cy, cz = self._cells(yz).T
        cell = cy * self.GRID + cz
        count = self.cell_start[cell + 1] - self.cell_start[cell]
        p = np.repeat(np.arange(len(rows)), count)
        t = self.cell_tris[np.repeat(self.cell_start[cell], count) + _ranges(count)]
        y, z = yz[p, 0], yz[p, 1]
        dy, dz = y - self.p0[t, 1], z - self.p0[t, 2]
        u = (dy * self.e2[t, 2] - dz * self.e2[t, 1]) * self.inv[t]
        v = (dz * self.e1[t, 1] - dy * self.e1[t, 2]) * self.inv[t]
        x = self.p0[t, 0] + u * self.e1[t, 0] + v * self.e2[t, 0]
        hit = (u >= 0) & (v >= 0) & (u + v <= 1) & (x > points[rows[p], 0])
        crossings = np.bincount(p[hit] * self.count + self.lobe[t[hit]], minlength=len(rows) * self.count)
        odd = crossings.reshape(len(rows), self.count) % 2 == 1
        which[rows] = np.where(odd.any(axis=1), np.argmax(odd, axis=1), -1)
        return which


def laplacian_edit(vertices: np.ndarray, faces: np.ndarray, handle: np.ndarray, targets: np.ndarray,
                   fixed: np.ndarray) -> np.ndarray:
    """Vertices that keep their uniform Laplacian coordinates (each vertex's offset from the mean of its
    neighbours) as well as possible while ``handle`` goes exactly to ``targets`` and ``fixed`` stays
    (Sorkine et al.'s Laplacian surface editing with hard constraints; a lobe has a few hundred
    vertices, so a dense least-squares solve)."""
    n = len(vertices)
    edges = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    adjacency = np.zeros((n, n))
    adjacency[edges[:, 0], edges[:, 1]] = adjacency[edges[:, 1], edges[:, 0]] = 1.0
    lap = np.eye(n) - adjacency / np.maximum(adjacency.sum(axis=1), 1.0)[:, None]
    known = np.zeros(n, bool)
    known[handle] = known[fixed] = True
    out = vertices.copy()
    out[fixed] = vertices[fixed]
    out[handle] = targets
    free = np.flatnonzero(~known)
    if len(free):
        rhs = lap @ vertices - lap[:, known] @ out[known]
        out[free], *_ = np.linalg.lstsq(lap[:, free], rhs, rcond=None)
    return out


def _ranges(counts: np.ndarray) -> np.ndarray:
    """0, 1, ..., c - 1 for every c in ``counts``, concatenated."""
    total = int(counts.sum())
    return np.arange(total) - np.repeat(np.cumsum(counts) - counts, counts)


def lobe_from_loops(loops: list[np.ndarray], points_per_loop: int = 32,
                    open_strokes: list[np.ndarray] = ()) -> Lobe:
    """Stitch two or more closed strokes into a closed lobe mesh (see module docstring).

    Each of ``open_strokes`` (an arch drawn across an end loop, Zhang et al. condition 2) closes the end
    loop nearest to it instead of a flat fan; the last one drawn at an end wins.
    """
    if len(loops) < 2:
        raise ValueError("a lobe needs at least two closed strokes")
    centers = np.array([np.asarray(loop, float).mean(axis=0) for loop in loops])
    span = centers.max(axis=0) - centers.min(axis=0)
    axis = np.eye(3)[int(np.argmax(span))] if span.max() > 1e-9 else np.array([0.0, 1.0, 0.0])
    order = np.argsort(centers @ axis)
    rings = _stacked([resample_loop(sampled_loop(np.asarray(loops[i], float)), points_per_loop) for i in order],
                     axis)
    rings[0] = _counter_clockwise(rings[0], axis)
    for k in range(1, len(rings)):  # every ring runs the way its neighbour does: strips never twist
        if _normal(rings[k]) @ _normal(rings[k - 1]) < 0:
            rings[k] = rings[k][::-1].copy()
    for k in range(1, len(rings)):  # eq. 2: start where the barycentric directions agree best
        start = barycentric_directions(rings[k - 1])[0]
        rings[k] = np.roll(rings[k], -int(np.argmax(barycentric_directions(rings[k]) @ start)), axis=0)
    n, i = points_per_loop, np.arange(points_per_loop)
    verts = [*rings, [rings[0].mean(axis=0), rings[-1].mean(axis=0)]]
    faces = []
    for k in range(len(rings) - 1):
        a, b, c, d = k * n + i, k * n + (i + 1) % n, (k + 1) * n + i, (k + 1) * n + (i + 1) % n
        faces += [np.stack([a, b, c], 1), np.stack([b, d, c], 1)]
    caps = {}
    for stroke in open_strokes:  # the end whose loop centre is nearest the arch's middle
        mid = np.asarray(stroke, float).mean(axis=0)
        caps[0 if np.linalg.norm(mid - rings[0].mean(axis=0)) <= np.linalg.norm(mid - rings[-1].mean(axis=0))
             else len(rings) - 1] = np.asarray(stroke, float)
    count = len(rings) * n + 2
    for end, centre in ((0, count - 2), (len(rings) - 1, count - 1)):
        if end in caps:
            inner, cap_faces = _arch_cap(rings[end], end * n, caps[end], count)
            verts.append(inner)
            count += len(inner)
            faces.append(cap_faces)
        else:  # a flat fan, wound like the strips
            ring = end * n + i, end * n + (i + 1) % n
            faces.append(np.stack([np.full(n, centre), *(ring[::-1] if end == 0 else ring)], 1))
    all_verts = np.concatenate(verts)
    return Lobe(all_verts, _outwards(all_verts, _consistent(np.concatenate(faces).astype(np.int64))), n, len(rings))


def _arch_cap(ring: np.ndarray, first: int, stroke: np.ndarray, next_index: int) -> tuple[np.ndarray, np.ndarray]:
    """Close a loop with an open stroke across it (Zhang et al. condition 2): the stroke's ends go to the
    loop points whose barycentric directions best match the stroke's directions into itself; the
    loop's two arcs between them are each stitched to the stroke. Returns the stroke's new inner
    points and the cap's triangles (loop points keep their indices, ``first`` + k)."""
    n = len(ring)
    arch = _resample_open(stroke, max(3, n // 2 + 1))
    bary = barycentric_directions(ring)
    i0 = int(np.argmax(bary @ unit(arch[1] - arch[0])))
    into_end = bary @ unit(arch[-2] - arch[-1])
    gap = np.minimum((np.arange(n) - i0) % n, (i0 - np.arange(n)) % n)
    i1 = int(np.argmax(np.where(gap >= 2, into_end, -np.inf)))  # the ends must not be neighbours
    inner = arch[1:-1]
    arch_ids = np.concatenate([[first + i0], next_index + np.arange(len(inner)), [first + i1]])
    arch_pts = np.concatenate([ring[i0:i0 + 1], inner, ring[i1:i1 + 1]])
    forward = (i0 + np.arange((i1 - i0) % n + 1)) % n
    backward = (i0 - np.arange((i0 - i1) % n + 1)) % n
    faces = [_zip_strips(first + arc, ring[arc], arch_ids, arch_pts) for arc in (forward, backward)]
    return inner, np.concatenate(faces)


def _resample_open(points: np.ndarray, count: int) -> np.ndarray:
    """An open stroke with ``count`` points evenly spaced along its length, ends kept."""
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(points, axis=0), axis=1))])
    t = np.linspace(0.0, s[-1], count)
    return np.stack([np.interp(t, s, points[:, c]) for c in range(3)], axis=1)


def _zip_strips(ids_a: np.ndarray, pts_a: np.ndarray, ids_b: np.ndarray, pts_b: np.ndarray) -> np.ndarray:
    """Triangles between two polylines that share both end points, advancing along whichever is
    behind in relative arc length (triangles that collapse onto a shared end are left out)."""
    def progress(pts):
        s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
        return s / max(s[-1], 1e-12)

    ta, tb = progress(pts_a), progress(pts_b)
    i = j = 0
    tris = []
    while i < len(ids_a) - 1 or j < len(ids_b) - 1:
        if j == len(ids_b) - 1 or (i < len(ids_a) - 1 and ta[i + 1] <= tb[j + 1]):
            tris.append((ids_a[i], ids_a[i + 1], ids_b[j]))
            i += 1
        else:
            tris.append((ids_a[i], ids_b[j + 1], ids_b[j]))
            j += 1
    tris = np.array(tris, dtype=np.int64)
    return tris[(tris[:, 0] != tris[:, 1]) & (tris[:, 1] != tris[:, 2]) & (tris[:, 0] != tris[:, 2])]


def _counter_clockwise(ring: np.ndarray, axis: np.ndarray) -> np.ndarray:
    return ring if _normal(ring) @ axis > 0 else ring[::-1].copy()


def _normal(ring: np.ndarray) -> np.ndarray:
    """The area vector of a closed ring (its plane's normal, by the way it runs)."""
    c = ring.mean(axis=0)
    return np.cross(ring - c, np.roll(ring, -1, axis=0) - c).sum(axis=0)


def _stacked(rings: list[np.ndarray], axis: np.ndarray) -> list[np.ndarray]:
    """Rings tilted so far that they would reach past their neighbours along the lobe's axis are
    tilted less (their points' offsets along the axis shrink about the ring's centre) until each
    keeps to its own slab: stitched strips then never fold over (drawn rings at 90 deg included)."""
    centres = np.array([r.mean(axis=0) @ axis for r in rings])
    gaps = np.diff(centres)
    out = []
    for k, ring in enumerate(rings):
        room = min(gaps[k - 1] if k > 0 else np.inf, gaps[k] if k < len(gaps) else np.inf)
        along = (ring - ring.mean(axis=0)) @ axis
        reach = float(np.abs(along).max())
        shrink = 1.0 if not np.isfinite(room) or reach <= 0.45 * room else 0.45 * room / reach
        out.append(ring - ((1.0 - shrink) * along)[:, None] * axis)
    return out


def _consistent(faces: np.ndarray) -> np.ndarray:
    """Faces flipped where needed so every shared edge is crossed in opposite directions (a walk over
    the faces from the first; a lobe has a few hundred)."""
    faces = faces.copy()
    edges: dict[tuple[int, int], list[int]] = {}
    for f, (a, b, c) in enumerate(faces.tolist()):
        for u, v in ((a, b), (b, c), (c, a)):
            edges.setdefault((min(u, v), max(u, v)), []).append(f)
    seen = np.zeros(len(faces), bool)
    for first in range(len(faces)):
        if seen[first]:
            continue
        seen[first], todo = True, [first]
        while todo:
            f = todo.pop()
            a, b, c = faces[f].tolist()
            for u, v in ((a, b), (b, c), (c, a)):
                for g in edges[(min(u, v), max(u, v))]:
                    if seen[g]:
                        continue
                    ga, gb, gc = faces[g].tolist()
                    if (u, v) in ((ga, gb), (gb, gc), (gc, ga)):  # the same direction: flip it
                        faces[g] = faces[g][::-1]
                    seen[g] = True
                    todo.append(g)
    return faces


def _outwards(verts: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """All faces flipped together if the (consistently wound) mesh encloses a negative volume."""
    tri = verts[faces]
    volume = np.einsum("ij,ij->", tri[:, 0], np.cross(tri[:, 1], tri[:, 2]))
    return faces if volume >= 0 else faces[:, ::-1].copy()


def lobe_from_outline(outline: np.ndarray, depth: float = 1.0, rings: int = 7) -> Lobe:
    """A lobe from one closed silhouette drawn on a vertical plane (a finger or the mouse): at
    ``rings`` heights the outline's left and right edges give a horizontal ring (an ellipse whose
    depth is ``depth`` times its width), and the rings are stitched like drawn closed strokes."""
    outline = np.asarray(outline, float)
    flat = outline - outline.mean(axis=0)
    across = np.linalg.svd(flat[:, [0, 2]], full_matrices=False)[2][0]  # the plane's horizontal axis
    side = np.array([across[0], 0.0, across[1]])
    normal = np.cross(side, [0.0, 1.0, 0.0])
    closed = np.concatenate([outline, outline[:1]])
    y0, y1 = outline[:, 1].min(), outline[:, 1].max()
    if y1 - y0 < 1e-6:
        raise ValueError("a silhouette needs some height")
    a = np.linspace(0, 2 * np.pi, 32, endpoint=False)[:, None]
    loops = []
    for y in y0 + (y1 - y0) * (np.arange(rings) + 0.5) / rings:
        a_y, b_y = closed[:-1, 1], closed[1:, 1]
        cross = (a_y - y) * (b_y - y) <= 0  # outline pieces that cross this height
        f = (y - a_y[cross]) / np.where(b_y[cross] == a_y[cross], 1.0, b_y[cross] - a_y[cross])
        points = closed[:-1][cross] + f[:, None] * (closed[1:][cross] - closed[:-1][cross])
        along = points @ side
        centre = points[np.argmin(along)] + (along.max() - along.min()) / 2 * side
        radius = max((along.max() - along.min()) / 2, 1e-3)
        loops.append(np.array([centre[0], y, centre[2]]) + radius * (np.cos(a) * side + depth * np.sin(a) * normal))
    return lobe_from_loops(loops)
