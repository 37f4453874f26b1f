"""Lobe benchmark: three drawn lobes -> attractors -> seed 004 growth -> L-string.

Run: python -m benchmarks.lobes
Prints the median of 10 runs for: stitching the lobes from 5 closed strokes each, growing a crown
from a drawn trunk into ~5,000 attractors, and writing the skeleton as L-string text.
"""

from __future__ import annotations

import numpy as np

from arbor.engine.modeling.crown import Skeleton, grow_into_lobes, skeleton_text
from arbor.engine.modeling.lobes import Crossings, lobe_from_loops
from benchmarks import median_ms


def _ring(center, radius: float, phase: int, n: int = 80) -> np.ndarray:
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    r = radius * (1 + 0.1 * np.sin(3 * a + phase))
    return np.stack([center[0] + r * np.cos(a), np.full(n, center[1]), center[2] + r * np.sin(a)], 1)


def _lobes() -> list:
    specs = [((0.0, 4.0, 0.0), 2.5, 4.0), ((2.4, 3.2, 0.5), 1.6, 3.0), ((-2.2, 3.5, -0.5), 1.6, 3.0)]
    return [lobe_from_loops([_ring((x, y + k * h / 4, z), r * np.sin(np.pi * (k + 0.5) / 5) + 0.2, k)
                             for k in range(5)]) for (x, y, z), r, h in specs]



def main() -> None:
    """Print timings and sizes."""
    ms, lobes = median_ms(_lobes)
    print(f"stitch 3 lobes from 15 strokes: {ms:.1f} ms")
    rng = np.random.default_rng(0)
    attractors = np.concatenate([lobe.vertices for lobe in lobes] + [lobe.sample_inside(1500, rng) for lobe in lobes])
    trunk = np.array([[0.0, 0.0, 0.0], [0.0, 1.5, 0.0], [0.0, 3.2, 0.0]])
    ms, skeleton = median_ms(lambda: grow_into_lobes(Skeleton.from_trunk(trunk), lobes, attractors))
    print(f"grow into {len(attractors)} attractors: {ms:.1f} ms, {len(skeleton.parent)} nodes")
    inside = Crossings(lobes).inside(skeleton.position) >= 0
    print(f"grown nodes outside every lobe: {int((~inside[len(trunk):]).sum())} (branches from the trunk tip that"
          " have not yet entered a lobe; none once inside)")
    ms, text = median_ms(lambda: skeleton_text(skeleton))
    print(f"skeleton -> L-string: {ms:.1f} ms, {len(text)} characters")


if __name__ == "__main__":
    main()
