"""Landscape benchmark (Jung et al. tables 1 and 3): frame time and triangles per second for 1,500 to
6,000 trees, every tree at each single resolution level, and with LOD by distance.

Run: python -m benchmarks.landscape [--counts 1500 3000 4500 6000] [--frames 3]
Headless 1280x720 on whatever GL the machine has (llvmpipe in CI). Goal (issue 8): with LOD at least
3x faster than full resolution at the same tree count. Prints one table row per count and mode.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from arbor.engine.forest.landscape import scatter
from arbor.engine.geometry.mesh import LOD_LEVELS
from arbor.game.commands.landscape import build_presets, landscape_size, overview_camera
from arbor.game.render.landscape import LandscapeRenderer
from arbor.game.render.renderer import headless_context, sun_direction

SIZE = (1280, 720)


def frame_ms(ctx, renderer, fbo, camera, instances, lod, frames: int):
    """Median frame time (ms) after one warm-up frame, and the last frame's statistics."""
    stats = renderer.render(fbo, camera, sun_direction(80, 40), SIZE, instances, lod)
    ctx.finish()
    times = []
    for _ in range(frames):
        start = time.perf_counter()
        stats = renderer.render(fbo, camera, sun_direction(80, 40), SIZE, instances, lod)
        ctx.finish()
        times.append(time.perf_counter() - start)
    return float(np.median(times)) * 1e3, stats


def main(argv: list[str] | None = None) -> None:
    """Print the table."""
    parser = argparse.ArgumentParser()
    parser.add_argument("--counts", type=int, nargs="+", default=[1500, 3000, 4500, 6000])
    parser.add_argument("--frames", type=int, default=3)
    args = parser.parse_args(argv)
    presets = build_presets()
    ctx = headless_context()
    fbo = ctx.framebuffer(color_attachments=[ctx.renderbuffer(SIZE)], depth_attachment=ctx.depth_renderbuffer(SIZE))
    print(f"GL: {ctx.info['GL_RENDERER']}, {SIZE[0]}x{SIZE[1]}")
    tris = [[sum(getattr(p.levels[k], a).n_triangles for a in ("wood", "leaves", "blossoms")) for k in
             range(len(LOD_LEVELS))] for p in presets]
    print("triangles per tree by level: " + "; ".join(f"{p.name} {t}" for p, t in zip(presets, tris, strict=True)))
    print(f"{'trees':>6} {'mode':>6} {'drawn':>6} {'ms/frame':>9} {'fps':>7} {'Mtri/frame':>11} {'Mtri/s':>8}")
    for count in args.counts:
        side = landscape_size(count)
        renderer = LandscapeRenderer(ctx, presets, side)
        instances = scatter(count, len(presets), side, seed=1)
        camera = overview_camera(side)
        full = None
        for lod in [*range(len(LOD_LEVELS)), None]:
            ms, stats = frame_ms(ctx, renderer, fbo, camera, instances, lod, args.frames)
            mode = "LOD" if lod is None else f"L{lod}"
            full = ms if lod == 0 else full
            speedup = f"  {full / ms:.1f}x faster than L0" if lod is None else ""
            print(f"{count:>6} {mode:>6} {stats.drawn:>6} {ms:>9.1f} {1000 / ms:>7.2f} {stats.triangles / 1e6:>11.2f} "
                  f"{stats.triangles / ms / 1e3:>8.1f}{speedup}")
    ctx.release()


if __name__ == "__main__":
    main()
