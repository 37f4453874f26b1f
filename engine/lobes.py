"""Lobes (seed 004 section 4): the crown drawn as a few closed strokes, as closed meshes.

Closed strokes drawn around the crown at different heights are ordered along the lobe's axis and
given the same number of points by arc-length interpolation; each loop starts at the point whose
barycentric direction (eq. 2) is closest to the previous loop's start; strips join neighbouring
loops and fans close both ends, every triangle wound outwards: a closed manifold. One silhouette
drawn on a plane becomes a lobe through horizontal rings. Lobes can be moved, scaled, turned,
squeezed and have stroke points dragged, with undo; ``Crossings`` tests points against many lobes.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from engine.history import Undoable
from engine.turtle import unit


def resample_loop(points: np.ndarray, count: int) -> np.ndarray:
    """A closed stroke with ``count`` points evenly spaced along its length."""
    closed = np.concatenate([points, points[:1]])
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(closed, axis=0), axis=1))])
    t = np.linspace(0.0, s[-1], count, endpoint=False)
    return np.stack([np.interp(t, s, closed[:, c]) for c in range(3)], axis=1)


def barycentric_directions(loop: np.ndarray) -> np.ndarray:
    """Eq. 2: for each point p_i, normalize(sum over k != i of (p_k - p_i))."""
    return unit(loop.sum(axis=0)[None, :] - len(loop) * loop)


@dataclass(eq=False)  # lobes compare by identity (their arrays have no single truth value)
class Lobe:
    """A closed triangle mesh around part of the crown: ``rings`` stitched strokes of ``ring_size``
    points each (the first vertices, ring by ring), then the two cap centres."""

    vertices: np.ndarray
    faces: np.ndarray
    ring_size: int = 0

    def transformed(self, move=(0.0, 0.0, 0.0), scale: float = 1.0, turn_deg: float = 0.0) -> Lobe:
        """Moved, scaled about its centre and turned about the vertical through it (lobe editing)."""
        centre = self.vertices.mean(axis=0)
        a = np.radians(turn_deg)
        rot = np.array([[np.cos(a), 0.0, np.sin(a)], [0.0, 1.0, 0.0], [-np.sin(a), 0.0, np.cos(a)]])
        moved = (self.vertices - centre) @ rot.T * scale + centre + np.asarray(move, float)
        return Lobe(moved, self.faces, self.ring_size)

    def squeezed(self, at, radius: float, amount: float) -> Lobe:
        """A local smooth deformation: surface within ``radius`` of ``at`` pulled towards the lobe's
        centre by ``amount`` (0..1; negative pushes out), fading smoothly to nothing at ``radius``."""
        d = np.linalg.norm(self.vertices - np.asarray(at, float), axis=1)
        w = np.clip(1.0 - (d / radius) ** 2, 0.0, 1.0) ** 2
        centre = self.vertices.mean(axis=0)
        return self._with_rings(self.vertices + (amount * w)[:, None] * (centre - self.vertices))

    def dragged(self, ring: int, index: int, to, width: int = 4) -> Lobe:
        """One stroke point dragged to ``to``; its neighbours along the stroke follow on a smooth
        (quadratic Bezier-like) falloff over ``width`` points each side."""
        n = self.ring_size
        rings = self.vertices[:-2].reshape(-1, n, 3).copy()
        offset = np.asarray(to, float) - rings[ring, index]
        k = np.arange(n)
        steps = np.minimum((k - index) % n, (index - k) % n)
        w = np.clip(1.0 - steps / (width + 1.0), 0.0, 1.0) ** 2
        rings[ring] += w[:, None] * offset
        return self._with_rings(np.concatenate([rings.reshape(-1, 3), self.vertices[-2:]]))

    def _with_rings(self, vertices: np.ndarray) -> Lobe:
        """The lobe with new vertices; cap centres follow their rings, triangles stay wound outwards."""
        vertices = vertices.copy()
        if self.ring_size:
            rings = vertices[:-2].reshape(-1, self.ring_size, 3)
            vertices[-2], vertices[-1] = rings[0].mean(axis=0), rings[-1].mean(axis=0)
        return Lobe(vertices, _wind_outwards(vertices, self.faces), self.ring_size)

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


@dataclass
class LobeEditor(Undoable):
    """The crown's lobes while they are being drawn and edited, with undo and redo."""

    HISTORY_OF = "lobes"

    lobes: list[Lobe] = field(default_factory=list)
    undo_stack: list[list[Lobe]] = field(default_factory=list)
    redo_stack: list[list[Lobe]] = field(default_factory=list)

    def set(self, index: int, lobe: Lobe | None) -> None:
        """Replace lobe ``index`` (``len(lobes)`` adds one, None removes it), undoably."""
        lobes = list(self.lobes)
        if lobe is None:
            del lobes[index]
        elif index == len(lobes):
            lobes.append(lobe)
        else:
            lobes[index] = lobe
        self.commit(lobes)


class Crossings:
    """Inside test for a set of lobes by the parity of crossings along a ray in +x, done as a 2D
    point-in-triangle test in the y-z plane (vectorised over points and all lobes' triangles)."""

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
        self.tri_lo[~ok] = np.inf
        self.lo, self.hi = tri.min(axis=(0, 1)), tri.max(axis=(0, 1))
        self.nudge = np.array([3.7e-9, 7.1e-9]) * max(float(np.max(self.hi - self.lo)), 1e-6)

    def inside(self, points: np.ndarray) -> np.ndarray:
        """Index of a lobe containing each point, -1 for points outside all of them."""
        which = np.full(len(points), -1, np.int64)
        rows = np.flatnonzero(np.all((points >= self.lo) & (points <= self.hi), axis=1))
        for start in range(0, len(rows), 1024):
            chunk = rows[start : start + 1024]
            # a tiny odd offset keeps the ray off shared edges and vertices (points on a ring's plane)
            y, z = points[chunk, 1:2] + self.nudge[0], points[chunk, 2:3] + self.nudge[1]
            near = ((y >= self.tri_lo[:, 1]) & (y <= self.tri_hi[:, 1])
                    & (z >= self.tri_lo[:, 2]) & (z <= self.tri_hi[:, 2]))
            p, t = np.nonzero(near)  # only triangles whose y-z box holds the point can be crossed
            dy, dz = y[p, 0] - self.p0[t, 1], z[p, 0] - self.p0[t, 2]
            u = (dy * self.e2[t, 2] - dz * self.e2[t, 1]) * self.inv[t]
            v = (dz * self.e1[t, 1] - dy * self.e1[t, 2]) * self.inv[t]
            x = self.p0[t, 0] + u * self.e1[t, 0] + v * self.e2[t, 0]
            hit = (u >= 0) & (v >= 0) & (u + v <= 1) & (x > points[chunk[p], 0])
            crossings = np.bincount(p[hit] * self.count + self.lobe[t[hit]], minlength=len(chunk) * self.count)
            odd = crossings.reshape(len(chunk), self.count) % 2 == 1
            which[chunk] = np.where(odd.any(axis=1), np.argmax(odd, axis=1), -1)
        return which


def lobe_from_loops(loops: list[np.ndarray], points_per_loop: int = 32) -> Lobe:
    """Stitch two or more closed strokes into a closed lobe mesh (see module docstring)."""
    if len(loops) < 2:
        raise ValueError("a lobe needs at least two closed strokes")
    centers = np.array([np.asarray(loop, float).mean(axis=0) for loop in loops])
    span = centers.max(axis=0) - centers.min(axis=0)
    axis = np.eye(3)[int(np.argmax(span))] if span.max() > 1e-9 else np.array([0.0, 1.0, 0.0])
    order = np.argsort(centers @ axis)
    rings = [_counter_clockwise(resample_loop(np.asarray(loops[i], float), points_per_loop), axis) for i in order]
    for k in range(1, len(rings)):  # eq. 2: start where the barycentric directions agree best
        start = barycentric_directions(rings[k - 1])[0]
        rings[k] = np.roll(rings[k], -int(np.argmax(barycentric_directions(rings[k]) @ start)), axis=0)
    n, i = points_per_loop, np.arange(points_per_loop)
    verts = np.concatenate([*rings, [rings[0].mean(axis=0), rings[-1].mean(axis=0)]])
    faces = []
    for k in range(len(rings) - 1):
        a, b, c, d = k * n + i, k * n + (i + 1) % n, (k + 1) * n + i, (k + 1) * n + (i + 1) % n
        faces += [np.stack([a, b, c], 1), np.stack([b, d, c], 1)]
    bottom, top, last = len(verts) - 2, len(verts) - 1, (len(rings) - 1) * n
    faces.append(np.stack([np.full(n, bottom), (i + 1) % n, i], 1))
    faces.append(np.stack([np.full(n, top), last + i, last + (i + 1) % n], 1))
    return Lobe(verts, _wind_outwards(verts, np.concatenate(faces).astype(np.int64)), points_per_loop)


def _counter_clockwise(ring: np.ndarray, axis: np.ndarray) -> np.ndarray:
    c = ring.mean(axis=0)
    normal = np.cross(ring - c, np.roll(ring, -1, axis=0) - c).sum(axis=0)
    return ring if normal @ axis > 0 else ring[::-1].copy()


def _wind_outwards(verts: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Flip any triangle whose normal points towards the lobe's centre (lobes are star-shaped)."""
    tri = verts[faces]
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    inward = np.einsum("ij,ij->i", normal, tri.mean(axis=1) - verts.mean(axis=0)) < 0
    faces = faces.copy()
    faces[inward] = faces[inward][:, ::-1]
    return faces


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
