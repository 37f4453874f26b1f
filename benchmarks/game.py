"""Game benchmark: frame times of the real game loop, headless (EGL), at 1280x720.

Run: python -m benchmarks.game
Scenario (issue 4): 5 simulated minutes at 100x (3 s of real frames at 60 fps), once from a fresh
sapling and once with a tree at its module budget. Each frame = events + fixed steps + geometry
rebuild + 3D render + HUD overlay, timed to ctx.finish(). Also prints the whole-tree rebuild time
(turtle + mesh) alone, to show whether rebuilding every frame fits in a frame.
"""

from __future__ import annotations

import time
from pathlib import Path
from tempfile import TemporaryDirectory

import numpy as np

SIZE = (1280, 720)
FPS = 60


def _frames(game, ctx, fbo, n: int) -> np.ndarray:
    times = []
    for _ in range(n):
        start = time.perf_counter()
        game.act("water", float(game.world.sim.state.water_meter < 0.55))
        game.update(1 / FPS)
        game.draw(fbo)
        ctx.finish()
        times.append(time.perf_counter() - start)
    return np.array(times) * 1e3


def _report(name: str, ms: np.ndarray) -> None:
    p50, p95, p99 = np.percentile(ms, [50, 95, 99])
    print(f"{name:<28} frames {len(ms):>4}  p50 {p50:7.1f} ms  p95 {p95:7.1f} ms  p99 {p99:7.1f} ms  "
          f"max {ms.max():7.1f} ms")


def main() -> None:
    """Run both scenarios and print percentiles."""
    import pygame

    from game.render.renderer import headless_context
    from game.screens.game import Game, GameConfig

    pygame.init()
    pygame.display.set_mode((64, 64))
    ctx = headless_context()
    fbo = ctx.framebuffer(color_attachments=[ctx.renderbuffer(SIZE)], depth_attachment=ctx.depth_renderbuffer(SIZE))
    print(f"GL: {ctx.info['GL_RENDERER']}, {SIZE[0]}x{SIZE[1]}, 5 simulated minutes at 100x = {3 * FPS} frames")
    with TemporaryDirectory() as saves:
        fake = [0.0]
        game = Game(ctx, SIZE, GameConfig(saves=Path(saves), seed=5, resume=False), clock=lambda: fake[0])
        game.set_speed(100.0)
        _report("sapling, 100x", _frames(game, ctx, fbo, 3 * FPS))
        game.world.sim.state.orbit_height = 1.0
        while not game.world.tree.budget_hit:
            game.act("water", float(game.world.sim.state.water_meter < 0.55))
            game.world.step(0.5)
        print(f"mature tree: {len(game.world.tree.lstring):,} modules (budget {game.system.budget:,})")
        _report("tree at budget, 100x", _frames(game, ctx, fbo, 3 * FPS))
        game.set_speed(1.0)
        _report("tree at budget, 1x", _frames(game, ctx, fbo, FPS))
        clocks = game.clocks()
        rebuild = []
        for k in range(20):
            start = time.perf_counter()
            geometry = game.world.tree.geometry(clocks)
            rebuild.append(time.perf_counter() - start)
            clocks.length_time += 0.001 * (k + 1)
        print(f"whole-tree rebuild (turtle + mesh, {len(geometry.turtle.segments):,} segments, "
              f"{geometry.mesh.n_triangles:,} triangles): median {np.median(rebuild) * 1e3:.1f} ms")
    ctx.release()


if __name__ == "__main__":
    main()
