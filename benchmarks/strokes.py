"""Modeler benchmark: one stroke of 2,000 raw points -> L-string -> re-meshed tree.

Run: python -m benchmarks.strokes
Goal (issue 5): <= 16 ms for conversion and re-mesh together. Prints the median of 20 runs for a
trunk stroke on an empty tree, and for a branch stroke that snaps onto (and is checked for collisions
against) an already modeled tree of 8 strokes.
"""

from __future__ import annotations

import numpy as np

from arbor.engine.geometry.mesh import tree_mesh
from arbor.engine.geometry.turtle import TurtleConfig, interpret
from arbor.engine.modeling.modeler import Modeler
from arbor.engine.modeling.strokes import Stroke
from benchmarks import median_ms

RAW_POINTS = 2000


def wavy(start, direction, length, n=RAW_POINTS, seconds=2.0, seed=0) -> Stroke:
    """A hand-like stroke: a gentle curve with tremor."""
    rng = np.random.default_rng(seed)
    u = np.linspace(0, 1, n)[:, None]
    side = np.cross(direction, [0.0, 0.0, 1.0])
    pts = (np.asarray(start) + u * length * np.asarray(direction) + np.sin(u * 5) * 0.3 * side
           + rng.normal(0, 0.002, (n, 3)))
    return Stroke(pts, np.linspace(0, seconds, n))


def _remesh(modeler: Modeler) -> int:
    result = interpret(modeler.lstring, TurtleConfig(pipe_model=False, leaves_at_tips=0))
    return tree_mesh(result).n_triangles



def main() -> None:
    """Print conversion + re-mesh times."""
    trunk = wavy([0, 0, 0], np.array([0.0, 1.0, 0.0]), 6.0)

    def first():
        m = Modeler()
        m.add_stroke(trunk)
        return m, _remesh(m)

    ms, (m, tris) = median_ms(first)
    print(f"trunk stroke ({RAW_POINTS:,} raw points) -> {len(m.lstring):,} modules + mesh ({tris:,} triangles): "
          f"{ms:.1f} ms median (goal <= 16 ms)")
    base = Modeler()
    base.add_stroke(trunk)
    for k in range(7):
        angle = k * 2.4
        base.add_stroke(wavy([0.0, 2.0 + 0.5 * k, 0.0], np.array([np.cos(angle), 0.6, np.sin(angle)]) / 1.17, 2.5,
                             seed=k + 1))
    branch = wavy([0.05, 4.7, 0.0], np.array([0.8, 0.6, 0.0]), 3.0, seed=9)

    def onto_tree():
        m = Modeler(lstring=base.lstring)
        result = m.add_stroke(branch)
        return result, _remesh(m)

    ms, (result, tris) = median_ms(onto_tree)
    print(f"branch stroke onto an 8-stroke tree (snapped: {result.snapped_to is not None}, "
          f"bypassed {result.bypassed} points) + mesh ({tris:,} triangles): {ms:.1f} ms median")


if __name__ == "__main__":
    main()
