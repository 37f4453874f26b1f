"""Modeler benchmark: one stroke of 2,000 raw points -> L-string -> re-meshed tree.

Run: python -m benchmarks.strokes
Goal (issue 5): <= 16 ms for conversion and re-mesh together. Prints the median of 20 runs for a
trunk stroke on an empty tree, and for a branch stroke that snaps onto (and is checked for collisions
against) an already modeled tree of 8 strokes. Then the jitter figures (issue 48): a straight stroke
with 1 % jitter (5 seeds: how much longer its path is, the median and 90th percentile turn between
pieces; goal: length within 2 %, median turn <= 2 deg) and clean bent strokes (their length and
farthest stray from the drawn curve; goal: within 0.3 %), and short mouse strokes of 60-200 px with a 1.5 px
tremor (the same goals).
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


def turns(path: np.ndarray) -> np.ndarray:
    """The turn between consecutive pieces of a path (degrees)."""
    d = np.diff(path, axis=0)
    d /= np.linalg.norm(d, axis=1)[:, None]
    return np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", d[1:], d[:-1]), -1.0, 1.0)))


def path_length(path: np.ndarray) -> float:
    """The length of a polyline."""
    return float(np.linalg.norm(np.diff(path, axis=0), axis=1).sum())


BENDS = {  # clean strokes with real bends, u in 0..1 (scene units)
    "sine": lambda u: np.stack([1.5 * np.sin(2 * u), 4 * u, 0.5 * u * u], 1),
    "quarter circle": lambda u: np.stack([2 * (1 - np.cos(u * np.pi / 2)), 2 * np.sin(u * np.pi / 2), 0 * u], 1),
    "S": lambda u: np.stack([0.6 * np.sin(2 * np.pi * u), 4 * u, 0 * u], 1),
    "hook": lambda u: np.stack([np.where(u < 0.5, 0.0, (u - 0.5) * 4) ** 2 * 0.5, 4 * u, 0 * u], 1),
}


def jitter_figures(seeds: int = 5, points: int = 120, piece: float = 0.25) -> dict:
    """The jitter figures (see module docstring): ``straight`` (longer, median turn, 90th percentile turn)
    per seed, and per bent stroke (its length's change, its farthest stray), both as fractions of its length."""
    from arbor.engine.modeling.modeler import smooth_path

    u = np.linspace(0, 1, points)
    straight = [(longer, float(np.median(t)), float(np.percentile(t, 90)))
                for longer, t in shaky_lines(seeds, points, 0.01, piece)]
    bends = {}
    dense = np.linspace(0, 1, 4000)
    for name, curve in BENDS.items():
        path, _ = smooth_path(Stroke(curve(u), u), piece)
        drawn = curve(dense)
        stray = np.min(np.linalg.norm(path[:, None] - drawn[None], axis=2), axis=1).max()
        full = path_length(drawn)
        bends[name] = (path_length(path) / full - 1, float(stray / full))
    return {"straight": straight, "bends": bends}


def shaky_lines(seeds: int, points: int, jitter: float, piece: float) -> list[tuple[float, np.ndarray]]:
    """A straight stroke of ``points`` points whose points stray ``jitter`` of its length (one sigma) each way,
    smoothed, per seed: (how much longer its path is than the clean stroke's, the turns between its pieces)."""
    from arbor.engine.modeling.modeler import smooth_path

    u = np.linspace(0, 1, points)
    line = np.stack([0 * u, 4 * u, 0 * u], 1)
    clean, _ = smooth_path(Stroke(line, u), piece)
    out = []
    for seed in range(seeds):
        path, _ = smooth_path(Stroke(line + np.random.default_rng(seed).normal(0, jitter * 4.0, line.shape), u), piece)
        out.append((path_length(path) / path_length(clean) - 1, turns(path)))
    return out


def short_strokes(seeds: int = 5, piece: float = 0.25) -> dict[int, list[tuple[float, float]]]:
    """Short mouse strokes with a 1.5 px tremor (issue 48: "up to +6.4 %, median turn 8.6 deg"): a straight
    stroke of 60, 100 and 200 px (30, 40 and 60 points: a mouse's rate over half a second to a second) whose
    points stray 1.5 px (one sigma) each way; per length, (how much longer its path is, median turn) a seed."""
    return {pixels: [(longer, float(np.median(t))) for longer, t in shaky_lines(seeds, points, 1.5 / pixels, piece)]
            for pixels, points in ((60, 30), (100, 40), (200, 60))}


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
    figures = jitter_figures()
    for seed, (longer, median, p90) in enumerate(figures["straight"]):
        print(f"straight stroke, 1 % jitter, seed {seed}: path {longer:+.2%} longer, median turn {median:.2f} deg, "
              f"90th percentile {p90:.2f} deg (goal: within 2 %, median <= 2 deg)")
    for name, (longer, stray) in figures["bends"].items():
        print(f"clean {name}: length {longer:+.3%}, farthest stray {stray:.3%} of its length (goal: within 0.3 %)")
    for pixels, runs in short_strokes().items():
        print(f"short mouse stroke, {pixels} px, 1.5 px tremor: paths " + ", ".join(f"{a:+.2%}" for a, _ in runs)
              + " longer, median turns " + ", ".join(f"{m:.1f}" for _, m in runs) + " deg (goal: within 2 %, <= 2 deg)")


if __name__ == "__main__":
    main()
