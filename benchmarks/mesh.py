"""Geometry benchmark: a tree of >= 100k segments through the turtle and the mesher, then rendered.

Run: python -m benchmarks.mesh
Goal (issues 3 and 17): turtle + mesh <= 0.1 s together at n_surf = 8. In the same run, the whole-array
numpy turtle and mesher they replaced (benchmarks/numpy_geometry) on the same tree, the ratio, and the
largest difference between the two results. Also prints the headless frame time at 1280x720 on
whatever GL the machine has (llvmpipe in CI) and the triangle count of every LOD level.
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from arbor.engine.base.memory import keep_freed_memory
from arbor.engine.geometry.mesh import LOD_LEVELS, tree_mesh, wood_mesh
from arbor.engine.geometry.turtle import TurtleConfig, interpret
from arbor.engine.lsystem.derive import derive
from arbor.engine.lsystem.lsys import load_lsystem
from benchmarks.numpy_geometry import mesh as numpy_mesh
from benchmarks.numpy_geometry import turtle as numpy_turtle

SOURCE = Path(__file__).resolve().parent.parent / "assets" / "lsystems" / "abop_2_8_tree.lsys"


def best_of(fn, repeats: int = 7) -> tuple[float, object]:
    """Fastest wall time of ``repeats`` calls, and the last result."""
    times, result = timed(fn, repeats)
    return min(times), result


def timed(fn, repeats: int) -> tuple[list[float], object]:
    """Wall times of ``repeats`` calls, and the last result."""
    times, result = [], None
    for _ in range(repeats):
        start = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - start)
    return times, result


def main() -> None:
    """Print turtle/mesh timings against the numpy peer, LOD triangle counts and render frame times."""
    keep_freed_memory()
    system = load_lsystem(SOURCE)
    ls = derive(system, 10)
    cfg = TurtleConfig.from_system(system)
    runs = {}
    for name, turtle, mesher in (("compiled", interpret, wood_mesh),
                                 ("numpy peer", numpy_turtle.interpret, numpy_mesh.wood_mesh)):
        turtle_times, result = timed(lambda turtle=turtle: turtle(ls, cfg), 9)
        mesh_times, wood = timed(lambda mesher=mesher, r=result: mesher(r.segments, n_surf=8, n_div=1), 9)
        runs[name] = (turtle_times, mesh_times, result, wood)
    turtle_times, mesh_times, result, wood = runs["compiled"]
    segs = result.segments
    print(f"tree: {len(ls):,} modules, {len(segs):,} segments, {len(result.leaves):,} leaves")
    print("                      best   median (9 runs)")
    for name, (t_times, m_times, _, _) in runs.items():
        both = [a + b for a, b in zip(t_times, m_times, strict=True)]
        for part, times in (("turtle", t_times), ("wood mesh", m_times), ("together", both)):
            print(f"{name:<10} {part:<10} {min(times) * 1e3:8.1f} {np.median(times) * 1e3:8.1f} ms")
    best = {name: min(a + b for a, b in zip(r[0], r[1], strict=True)) for name, r in runs.items()}
    print(f"compiled vs numpy peer: x{best['numpy peer'] / best['compiled']:.1f} (best together)")
    print(f"(n_surf=8, n_div=1: {wood.n_triangles:,} triangles; goal: together <= 100 ms)")
    print_agreement(runs["compiled"][2:], runs["numpy peer"][2:])
    print("\nLOD levels (same tree):")
    header = ("level", "n_surf", "n_div", "min r", "leaves", "wood tris", "leaf tris", "ms")
    print("{:>5} {:>6} {:>5} {:>6} {:>6} {:>11} {:>10} {:>8}".format(*header))
    meshes = []
    for i, level in enumerate(LOD_LEVELS):
        t, tm = best_of(lambda level=level: tree_mesh(result, level), repeats=1)
        meshes.append(tm)
        print(f"{i:>5} {level.n_surf:>6} {level.n_div:>5} {level.min_radius_fraction:>6.2f} "
              f"{level.leaf_fraction:>6.2f} {tm.wood.n_triangles:>11,} {tm.leaves.n_triangles:>10,} {t * 1e3:>8.1f}")
    render_frames(meshes)


def print_agreement(compiled, peer) -> None:
    """Largest differences between the compiled and the numpy results (they must draw the same tree)."""
    (r1, w1), (r2, w2) = compiled, peer
    rows = {"segment ends": (r1.segments.end, r2.segments.end), "frames": (r1.segments.frame, r2.segments.frame),
            "leaf frames": (r1.leaves.frame, r2.leaves.frame), "vertices": (w1.positions, w2.positions),
            "normals": (w1.normals, w2.normals)}
    diffs = ", ".join(f"{name} {float(np.abs(a - b).max()):.1e}" for name, (a, b) in rows.items())
    same = np.array_equal(w1.indices, w2.indices) and np.array_equal(w1.face_module, w2.face_module)
    print(f"largest difference: {diffs}; triangles {'identical' if same else 'DIFFER'}")


def render_frames(meshes) -> None:
    """Headless frame time at 1280x720 for each LOD level (median of 5 frames after a warm-up)."""
    try:
        from arbor.game.render.camera import OrbitCamera
        from arbor.game.render.renderer import TreeRenderer, headless_context, sun_direction
    except ImportError as exc:  # pragma: no cover - game extras missing
        print(f"render skipped: {exc}")
        return
    ctx = headless_context()
    size = (1280, 720)
    fbo = ctx.framebuffer(color_attachments=[ctx.renderbuffer(size)], depth_attachment=ctx.depth_renderbuffer(size))
    renderer = TreeRenderer(ctx)
    print(f"\nheadless frame time at 1280x720 on {ctx.info['GL_RENDERER']}:")
    for i, tm in enumerate(meshes):
        renderer.set_tree(tm)
        camera = OrbitCamera()
        camera.frame_bounds(renderer.lo, renderer.hi, size[0] / size[1])
        times = []
        for _ in range(6):
            start = time.perf_counter()
            renderer.render(fbo, camera, sun_direction(85, 48), size)
            ctx.finish()
            times.append(time.perf_counter() - start)
        print(f"  lod {i}: {np.median(times[1:]) * 1e3:8.1f} ms/frame  ({tm.n_triangles:,} triangles)")


if __name__ == "__main__":
    main()
