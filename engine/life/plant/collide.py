"""Collisions (the tamagotchi thesis, 6.3): grown shoots bend away from obstacles and other trees' wood, or stop.

Obstacles are capsules (a segment with a radius; a rock is a capsule of zero length): the wood of the
neighbouring trees and the garden's rocks. At every light reading each growing apex looks one
lookahead ahead along its heading; where that point comes within ``margin`` of an obstacle, the apex
is turned away from it (engine/life/plant/growth.py adds the push to its target direction) and an apex
already touching one stops growing. The test is vectorised over all apices and obstacles at once
(obstacles far from every apex are dropped first by their bounding boxes; the rest go in chunks).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

CHUNK = 4096  # obstacles compared with all points at once
LOOKAHEAD, MARGIN = 2.5, 1.5  # an apex looks this many internodes ahead, for obstacles this near (x IL)


@dataclass
class Obstacles:
    """Capsules: ``start`` and ``end`` (m, 3), ``radius`` (m,)."""

    start: np.ndarray
    end: np.ndarray
    radius: np.ndarray

    @classmethod
    def empty(cls) -> Obstacles:
        """No obstacles."""
        return cls(np.zeros((0, 3)), np.zeros((0, 3)), np.zeros(0))

    @classmethod
    def join(cls, parts: list[Obstacles]) -> Obstacles:
        """All capsules of several sets."""
        parts = [p for p in parts if len(p)]
        if not parts:
            return cls.empty()
        return cls(np.concatenate([p.start for p in parts]), np.concatenate([p.end for p in parts]),
                   np.concatenate([p.radius for p in parts]))

    def moved(self, offset: np.ndarray) -> Obstacles:
        """The same capsules shifted by ``offset``."""
        return Obstacles(self.start + offset, self.end + offset, self.radius)

    def __len__(self) -> int:
        return len(self.radius)

    def gaps(self, points: np.ndarray, margin: float) -> tuple[np.ndarray, np.ndarray]:
        """For every point: the gap to the nearest obstacle surface (negative inside; +inf when none is
        within ``margin``) and the unit direction from that surface to the point (zero when none)."""
        k = len(points)
        gap, away = np.full(k, np.inf), np.zeros((k, 3))
        if k == 0 or len(self) == 0:
            return gap, away
        lo, hi = points.min(axis=0) - margin, points.max(axis=0) + margin
        box_lo = np.minimum(self.start, self.end) - self.radius[:, None]
        box_hi = np.maximum(self.start, self.end) + self.radius[:, None]
        near = np.flatnonzero(np.all(box_hi >= lo, axis=1) & np.all(box_lo <= hi, axis=1))
        for first in range(0, len(near), CHUNK):
            pick = near[first:first + CHUNK]
            a, d = self.start[pick], self.end[pick] - self.start[pick]
            rel = points[:, None, :] - a[None]  # (k, c, 3)
            t = np.clip(np.einsum("kcj,cj->kc", rel, d) / np.maximum((d * d).sum(axis=1), 1e-12), 0.0, 1.0)
            diff = rel - t[:, :, None] * d[None]
            dist = np.linalg.norm(diff, axis=2)
            surface = dist - self.radius[pick][None]
            best = np.argmin(surface, axis=1)
            rows = np.arange(k)
            better = surface[rows, best] < gap
            gap[better] = surface[rows, best][better]
            chosen = diff[rows, best] / np.maximum(dist[rows, best], 1e-9)[:, None]
            away[better] = chosen[better]
        away[gap > margin] = 0.0
        gap[gap > margin] = np.inf
        return gap, away


def rocks(rows: list[tuple[float, float, float, float]]) -> Obstacles:
    """Rocks (x, y, z, radius) as capsules of zero length."""
    if not rows:
        return Obstacles.empty()
    arr = np.asarray(rows, float).reshape(-1, 4)
    return Obstacles(arr[:, :3].copy(), arr[:, :3].copy(), arr[:, 3].copy())


def wood(segments, offset: np.ndarray) -> Obstacles:
    """A tree's wood (turtle segments, moved by ``offset``) as capsules."""
    if not len(segments):
        return Obstacles.empty()
    return Obstacles(segments.start + offset, segments.end + offset, np.maximum(segments.radius, 0.02))


def avoidance(position: np.ndarray, frames: np.ndarray, step: np.ndarray, unit: float,
              obstacles: Obstacles | None) -> tuple[np.ndarray, np.ndarray]:
    """For apices at ``position`` with turtle ``frames`` (H, L, U) and internodes ``step`` long: a push
    away from the obstacle ahead (0..1 times a unit vector, sideways round it rather than back), and
    which apices already touch one (they stop). ``unit`` (the trunk's internode length) scales the
    margin."""
    k = len(position)
    push, touching = np.zeros((k, 3)), np.zeros(k, bool)
    if obstacles is None or not len(obstacles) or not k:
        return push, touching
    margin = MARGIN * unit
    heading = frames[:, :, 0]
    gap, away = obstacles.gaps(position + heading * (LOOKAHEAD * step)[:, None], margin)
    strength = np.where(np.isfinite(gap), np.clip((margin - gap) / margin, 0.0, 1.0), 0.0)
    side = away - heading * np.einsum("ki,ki->k", away, heading)[:, None]  # around it, not back
    side = np.where((np.linalg.norm(side, axis=1) < 0.2)[:, None], frames[:, :, 1], side)  # head-on: sideways
    push = side / np.maximum(np.linalg.norm(side, axis=1, keepdims=True), 1e-9) * strength[:, None]
    touching = np.isfinite(obstacles.gaps(position, 0.05)[0])
    return push, touching
