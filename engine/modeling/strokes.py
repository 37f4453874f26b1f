"""Strokes: time-stamped 3D point sequences from a pointer, sampled and smoothed for the modeler.

* Curvature-adaptive sampling (Zhang et al., eq. 1): from point i the next key point is
  i + floor(k * log2(2 + 1/rho)), rho = max(kappa_i, 0.01), k = 2, so steps run from 2 (sharp bends)
  to 13 (straight parts).
* An arc-length spline through the key points (Wakabayashi & Durikovic): a centripetal Catmull-Rom curve, tabulated
  densely and inverted so it can be resampled at even arc-length steps.
* Speed along the stroke (arc length over time), for the trunk width.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

SAMPLE_K = 2.0
STRAY = 0.003  # of the stroke's length: how far it may leave the chord between two key points
MIN_RHO = 0.01
TABLE_PER_SPAN = 12  # spline evaluations per span for the arc-length table


@dataclass
class Stroke:
    """Raw pointer samples: positions (n, 3) in scene units and times (n,) in seconds."""

    points: np.ndarray
    times: np.ndarray

    def __post_init__(self) -> None:
        self.points = np.asarray(self.points, dtype=np.float64).reshape(-1, 3)
        self.times = np.asarray(self.times, dtype=np.float64).reshape(-1)
        if len(self.points) != len(self.times):
            raise ValueError("a stroke needs one time per point")

    @property
    def length(self) -> float:
        """Polyline length of the raw samples."""
        return float(np.linalg.norm(np.diff(self.points, axis=0), axis=1).sum()) if len(self.points) > 1 else 0.0

    def deduplicated(self, min_step: float = 1e-9) -> Stroke:
        """Drop samples that did not move (a still pointer repeats its position)."""
        if len(self.points) < 2:
            return self
        step = np.linalg.norm(np.diff(self.points, axis=0), axis=1)
        keep = np.concatenate([[True], step > min_step])
        return Stroke(self.points[keep], self.times[keep])


def curvature(points: np.ndarray) -> np.ndarray:
    """Discrete curvature at every point: turning angle over the mean length of the two edges."""
    n = len(points)
    kappa = np.zeros(n)
    if n < 3:
        return kappa
    a, b = points[1:-1] - points[:-2], points[2:] - points[1:-1]
    la, lb = np.linalg.norm(a, axis=1), np.linalg.norm(b, axis=1)
    cos = np.einsum("ij,ij->i", a, b) / np.maximum(la * lb, 1e-300)
    angle = np.arccos(np.clip(cos, -1.0, 1.0))
    kappa[1:-1] = angle / np.maximum(0.5 * (la + lb), 1e-12)
    kappa[0], kappa[-1] = kappa[1], kappa[-2]
    return kappa


def sample_steps(kappa: np.ndarray, k: float = SAMPLE_K) -> np.ndarray:
    """Seed 004 eq. 1: the index step taken from each point."""
    rho = np.maximum(kappa, MIN_RHO)
    return np.floor(k * np.log2(2.0 + 1.0 / rho)).astype(np.int64)


def denoised(points: np.ndarray, width: int = 5) -> np.ndarray:
    """A moving average over ``width`` points (ends held), so a shaky hand does not read as curvature."""
    if len(points) <= width:
        return points
    half = width // 2
    padded = np.concatenate([np.repeat(points[:1], half, axis=0), points, np.repeat(points[-1:], half, axis=0)])
    sums = np.cumsum(np.concatenate([np.zeros((1, points.shape[1])), padded]), axis=0)
    return (sums[width:] - sums[:-width]) / width


def adaptive_sample(points: np.ndarray, k: float = SAMPLE_K) -> np.ndarray:
    """Indices of key points: from the first point, step by eq. 1 with the curvature of the stroke as
    drawn (its jitter averaged away); the last point is always kept."""
    n = len(points)
    if n <= 2:
        return np.arange(n)
    steps = sample_steps(curvature(denoised(points, max(5, (n // 40) | 1))), k)
    idx = [0]
    i = 0
    while True:
        i += int(steps[i])
        if i >= n - 1:
            break
        idx.append(i)
    idx.append(n - 1)
    return _kept_close(points, np.array(idx, dtype=np.int64))


def _kept_close(points: np.ndarray, idx: np.ndarray, tolerance: float = STRAY) -> np.ndarray:
    """Key points added where the stroke strays from the chord between two key points by more than
    ``tolerance`` of its length (the farthest point of such a stretch becomes a key point): a wiggle
    the averaged curvature missed is still drawn."""
    limit = tolerance * float(np.linalg.norm(np.diff(points, axis=0), axis=1).sum())
    for _ in range(64):
        span = np.searchsorted(idx, np.arange(len(points)), side="right") - 1
        span = np.minimum(span, len(idx) - 2)
        a, b = points[idx[span]], points[idx[span + 1]]
        ab = b - a
        t = np.clip(np.einsum("ij,ij->i", points - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300), 0, 1)
        dist = np.linalg.norm(points - a - ab * t[:, None], axis=1)
        worst = np.maximum.reduceat(dist, idx[:-1])
        far = np.flatnonzero(worst > limit)
        if not len(far):
            break
        first = np.flatnonzero((dist == worst[span]) & np.isin(span, far))
        _, at = np.unique(span[first], return_index=True)
        idx = np.union1d(idx, first[at])
    return idx


class ArcLengthSpline:
    """A centripetal Catmull-Rom curve through key points, parametrised by arc length."""

    def __init__(self, keys: np.ndarray) -> None:
        keys = np.asarray(keys, dtype=np.float64)
        if len(keys) < 2:
            raise ValueError("a spline needs at least two points")
        self.keys = keys
        ext = np.concatenate([[2 * keys[0] - keys[1]], keys, [2 * keys[-1] - keys[-2]]])
        t = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(ext, axis=0), axis=1) ** 0.5)])
        t = np.maximum.accumulate(t + np.arange(len(t)) * 1e-12)
        u = np.linspace(0.0, 1.0, TABLE_PER_SPAN + 1)[:-1]
        spans = len(keys) - 1
        pts = _catmull_rom(ext, t, np.repeat(np.arange(spans), len(u)), np.tile(u, spans))
        self.table = np.concatenate([pts, keys[-1:]])
        seg = np.linalg.norm(np.diff(self.table, axis=0), axis=1)
        self.s = np.concatenate([[0.0], np.cumsum(seg)])

    @property
    def length(self) -> float:
        """Arc length of the curve."""
        return float(self.s[-1])

    def at(self, s: np.ndarray) -> np.ndarray:
        """Points at arc lengths ``s`` (linear between the dense table entries)."""
        s = np.clip(np.asarray(s, dtype=np.float64), 0.0, self.length)
        return np.stack([np.interp(s, self.s, self.table[:, c]) for c in range(3)], axis=1)

    def resample(self, spacing: float) -> np.ndarray:
        """Points at even arc-length steps of about ``spacing``, first and last point included."""
        count = max(int(np.ceil(self.length / max(spacing, 1e-9))), 1)
        return self.at(np.linspace(0.0, self.length, count + 1))


def _catmull_rom(p: np.ndarray, t: np.ndarray, span: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Barry-Goldman evaluation of a centripetal Catmull-Rom curve; span i runs from p[i+1] to p[i+2]."""
    p0, p1, p2, p3 = p[span], p[span + 1], p[span + 2], p[span + 3]
    t0, t1, t2, t3 = t[span], t[span + 1], t[span + 2], t[span + 3]
    tt = (t1 + u * (t2 - t1))[:, None]

    def lerp(a, b, ta, tb):
        w = ((tt - ta[:, None]) / np.maximum(tb - ta, 1e-300)[:, None])
        return a + (b - a) * w

    a1, a2, a3 = lerp(p0, p1, t0, t1), lerp(p1, p2, t1, t2), lerp(p2, p3, t2, t3)
    b1, b2 = lerp(a1, a2, t0, t2), lerp(a2, a3, t1, t3)
    return lerp(b1, b2, t1, t2)


def speeds_at(stroke: Stroke, s_query: np.ndarray, window: float) -> np.ndarray:
    """Pointer speed (arc length per second) around arc lengths ``s_query``, averaged over ``window``."""
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(stroke.points, axis=0), axis=1))])
    if s[-1] <= 0 or stroke.times[-1] <= stroke.times[0]:
        return np.full(len(s_query), np.inf)
    a = np.clip(s_query - window / 2, 0, s[-1])
    b = np.clip(s_query + window / 2, 0, s[-1])
    dt = np.interp(b, s, stroke.times) - np.interp(a, s, stroke.times)
    return (b - a) / np.maximum(dt, 1e-6)
