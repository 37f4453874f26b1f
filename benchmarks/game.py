"""Game benchmark: frame times of the real game loop, headless (EGL, Mesa llvmpipe here), 1280x720.

Run: python -m benchmarks.game [--quick]
One run, three trees: a fresh sapling, a tree grown 25 simulated days by the living model (under its
12,000-module budget) and a 50,000-segment tree grown by the game's own rules with the budget raised
(every bud woken, no light limits). Each frame = input + fixed steps + record updates + 3D render +
HUD, timed to ctx.finish(). The sapling and the 25-day tree are timed in the look as it is and in the old
look (no edge smoothing, one shadow tap) in alternating blocks of frames, for the ratio. The big tree grows
at full speed (its clocks advance every frame, a rewrite every physiological time unit); light readings
are left out for it (the benchmark is about drawing).
The big tree's crown is drawn at a reduced resolution and over several frames (game/render/layer.py);
the run says how many pictures it showed. Then the cost per growth step against tree size: a full
rebuild of the records (what a rewrite costs, on a worker thread for big trees) against the per-frame
update of the growing parts, and the frame times of two full-rebuild paths for the ratio: the records
rebuilt every frame, and the game's old path (the whole tree meshed at LOD 0, uploaded and drawn twice).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path
from tempfile import TemporaryDirectory

import numpy as np

SIZE = (1280, 720)
FPS = 60
MATURE = 20.0  # physiological time the big tree rests before the frames (its old parts stop growing)


def _frames(game, ctx, fbo, n: int, each=None) -> np.ndarray:
    from arbor.engine.life.world.actions import Action

    times = []
    for i in range(n):
        start = time.perf_counter()
        if each is not None:
            each(i)
        game.act(Action.WATER, float(game.world.sim.state.water_meter < 0.55))
        game.update(1 / FPS)
        game.draw(fbo)
        ctx.finish()
        times.append(time.perf_counter() - start)
    return np.array(times) * 1e3


def _report(name: str, ms: np.ndarray) -> None:
    p50, p95, p99 = np.percentile(ms, [50, 95, 99])
    print(f"{name:<40} frames {len(ms):>4}  p50 {p50:7.1f}  p95 {p95:7.1f}  p99 {p99:7.1f}  max {ms.max():7.1f} ms")


LOOKS = {"new look": (True, 1.0), "old look": (False, 0.0)}  # (edge smoothing, shadow filter texels)


def _looks(game, ctx, fbo, n: int, each, name: str) -> None:
    """Frame times of the look as it is against the old look (no edge smoothing, one shadow tap) in the
    same run: blocks of frames taken in turn, so a machine's changing load falls on both alike."""
    renderer = game.renderer
    kept = renderer.fxaa, renderer.soft_shadows
    times: dict[str, list] = {look: [] for look in LOOKS}
    block = max(n // 6, 10)
    for _ in range(max(n // block // len(LOOKS), 1)):
        for look, (fxaa, soft) in LOOKS.items():
            renderer.fxaa, renderer.soft_shadows = fxaa and kept[0], soft
            times[look].append(_frames(game, ctx, fbo, block, each))
    renderer.fxaa, renderer.soft_shadows = kept
    p50 = {}
    for look, parts in times.items():
        ms = np.concatenate(parts)
        _report(f"{name}, {look}", ms)
        p50[look] = float(np.median(ms))
    print(f"  (new look / old look, p50: {p50['new look'] / p50['old look']:.2f}; edge smoothing "
          f"{'on' if kept[0] else 'off'} here)")


def grown_tree(days: float):
    """A world grown ``days`` simulated days by a careful player (the living model)."""
    from arbor.engine.life.rules.rules import load_rules
    from arbor.engine.life.world.actions import Action
    from arbor.engine.life.world.world import World
    from arbor.engine.lsystem.lsys import load_lsystem
    from arbor.game.paths import ASSETS

    rules = load_rules(ASSETS / "rules.toml", pace="demo")
    world = World(load_lsystem(ASSETS / "lsystems" / "game_tree.lsys"), rules, seed=3)
    world.sim.state.sun_meter = world.sim.state.water_meter = 0.9
    for _ in range(round(days * 2 * np.pi / 0.05 / 0.5)):
        world.apply(Action.WATER, float(world.sim.state.water_meter < 0.6))
        world.step(0.5)
    return world


def big_tree(segments: int):
    """The game tree's rules with the budget raised, every bud woken: rewritten until ``segments``
    internodes exist. Returns the tree and its length time."""
    from arbor.engine.life.plant.growth import GrowingTree
    from arbor.engine.lsystem.lsys import load_lsystem
    from arbor.game.paths import ASSETS

    tree = GrowingTree(load_lsystem(ASSETS / "lsystems" / "game_tree.lsys"), seed=1, budget=5_000_000)
    t = 0.0
    while tree.lstring.count("I") < segments:
        t += 1.0
        tree.rewrite(t, t, 1.0)
    return tree, t


def rebuild_costs(trees) -> None:
    """Full record build vs per-frame update of the growing parts, per tree size."""
    from arbor.engine.life.form.growth_view import GrowthView
    from arbor.engine.life.form.interpret import Clocks

    print("cost per growth step (records of the whole tree) vs per frame (only what grows):")
    for tree, t in trees:
        t += MATURE
        clocks = Clocks(t, t)
        start = time.perf_counter()
        view = GrowthView(tree.lstring, clocks, tree.geometry_constants)
        build = (time.perf_counter() - start) * 1e3
        updates = []
        for k in range(20):
            start = time.perf_counter()
            view.update(Clocks(t + 0.001 * (k + 1), t))
            updates.append(time.perf_counter() - start)
        young = len(view.tubes) - view.young_row
        print(f"  {len(view.tubes):>7,} segments ({young:,} growing): full build {build:7.1f} ms, "
              f"per-frame update {np.median(updates) * 1e3:6.2f} ms  (ratio {build / (np.median(updates) * 1e3):.0f}x)")


def _old_path(tree, t: float, ctx, fbo, camera, n: int) -> np.ndarray:
    """Frame times of the path the game had before instanced records (issue 17's baseline): every
    frame the whole tree through the turtle and the mesher at LOD 0, uploaded, and drawn with a shadow
    pass and a lit pass by the mesh renderer."""
    from arbor.engine.life.form.interpret import Clocks
    from arbor.game.render.renderer import TreeRenderer, sun_direction

    renderer = TreeRenderer(ctx)
    times = []
    for k in range(n):
        start = time.perf_counter()
        renderer.set_tree(tree.geometry(Clocks(t + 0.01 * k, t), lod=0).mesh)
        renderer.render(fbo, camera, sun_direction(), SIZE)
        ctx.finish()
        times.append(time.perf_counter() - start)
    renderer.release_tree()
    return np.array(times) * 1e3


def main() -> None:
    """Run every scenario and print the figures."""
    import pygame

    from arbor.engine.life.form.growth_view import GrowthView
    from arbor.engine.life.form.interpret import Clocks
    from arbor.game.render.renderer import headless_context
    from arbor.game.screens.game import Game, GameConfig

    quick = "--quick" in sys.argv
    pygame.init()
    pygame.display.set_mode((64, 64))
    ctx = headless_context()
    fbo = ctx.framebuffer(color_attachments=[ctx.renderbuffer(SIZE)], depth_attachment=ctx.depth_renderbuffer(SIZE))
    print(f"GL: {ctx.info['GL_RENDERER']}, {SIZE[0]}x{SIZE[1]}")
    n = 60 if quick else 300
    with TemporaryDirectory() as saves:
        clock = [1000.0]
        game = Game(ctx, SIZE, GameConfig(saves=Path(saves), seed=5, resume=False), clock=lambda: clock[0])

        def tick(_):
            clock[0] += 1 / FPS

        _looks(game, ctx, fbo, n, tick, "sapling, 1x")
        game.garden.worlds[0] = grown_tree(6 if quick else 25)
        _looks(game, ctx, fbo, n, tick, f"tree after {'6' if quick else '25'} days, 1x")
        game.set_speed(100.0)
        _report("same tree, 100x", _frames(game, ctx, fbo, n, tick))
        game.set_speed(1.0)
        tree, t = big_tree(5_000 if quick else 50_000)
        world = game.world
        world.tree = tree
        t += MATURE  # its older parts have finished growing; new ones keep coming at the tips
        tree.last_rewrite_T = t - 0.5
        world.sim.state.length_time = world.sim.state.girth_time = t
        world.last_light = float("inf")  # drawing is measured here, not light readings of a huge tree
        game.rules.growth.length_rate = 0.5  # a rewrite every ~2 s of frames: it keeps growing
        game.state.remember()
        game.draw(fbo)
        while game.view.pending:  # the first build of the big tree (on the worker thread)
            time.sleep(0.05)
            game.draw(fbo)
        view = game.view.views[id(world)][1]
        shown = game.renderer.pictures.version
        _report(f"{len(view.tubes):,}-segment tree, growing", _frames(game, ctx, fbo, n, tick))
        shown = game.renderer.pictures.version - shown
        print(f"  (drawn at {game.renderer.last_scale:.2f} of the resolution, over several frames while the camera "
              f"holds still: {shown} pictures in {n} frames, one per {n / max(shown, 1):.1f} frames)")
        detail = game.renderer.last_details[0]
        print(f"  (level of detail {detail.lod}: {detail.tubes:,} grown segments, {detail.leaves:,} grown leaves "
              f"(share {detail.leaf_share:.2f}), {detail.vertices(game.renderer.placed[0].buffers):,} vertices; "
              "rebuilds on the worker thread)")
        full = []
        for k in range(8 if quick else 15):
            start = time.perf_counter()
            clocks = Clocks(t + 0.01 * k, t)
            GrowthView(tree.lstring, clocks, tree.geometry_constants)
            game.draw(fbo)
            ctx.finish()
            full.append(time.perf_counter() - start)
        _report("  same tree, full rebuild every frame", np.array(full) * 1e3)
        _report("  same tree, old path: LOD 0 mesh, draw", _old_path(tree, t, ctx, fbo, game.camera(),
                                                                               4 if quick else 8))
        sizes = [big_tree(s) for s in ((1_000, 3_000) if quick else (1_000, 3_000, 10_000, 25_000, 50_000))]
        rebuild_costs(sizes)
    ctx.release()


if __name__ == "__main__":
    main()
