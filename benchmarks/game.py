"""Game benchmark: frame times of the real game loop on the trees players see, headless (EGL, Mesa
llvmpipe here), 1280x720.

Run: python -m benchmarks.game [--quick] [--home] [--years DIR]
The first frames (shaders compiled, textures and the first tree uploaded) are timed apart as the warm-up.
Then, each at the default zoom and close up (the camera at its nearest), with the level of detail the
game itself picks: a fresh sapling; a leafy summer tree grown 25 days at the demo pace (its calendar set
so that day 25 is midsummer: at the demo pace with seasons the 25th day fell in winter, with no leaves);
the home pace's tree in the summer of its first, third, tenth and thirtieth year (the saves `python -m
benchmarks.years 30 DIR` writes, when --years DIR is given: those found; seen at 13:00, the saves being
written at the season's end, at night), each also drawn whole every frame as the game drew it before it
drew costly trees as a picture over frames (the old figure beside the new, same run); and a
50,000-segment tree grown by the game's own rules with the budget raised (every bud woken, no light
limits, growing on at its tips). `--home` runs the home pace's trees alone. Each frame = input + fixed
steps + record updates + 3D render + HUD, timed to ctx.finish(): wall time and CPU time (this process,
all its threads: llvmpipe's too), the load average printed first and last. Beside every figure: the
tree's leaf clusters, and the level of detail, segments and leaves the renderer drew, and whether it drew
the trees whole or as a layer's picture over frames (game/render/garden.py: LAYER_COST) and in how many
shares of leaves; after each home pace tree, its frames while the camera turns round it and what a rewrite
of it costs the frame it shows in (its records
built anew and sorted for upload). Then a growing tree's cost per frame: a full rebuild of its records against the
incremental update of the same growth (the parts that grew since the last rewrite), per tree size.
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path
from tempfile import TemporaryDirectory

import numpy as np

SIZE = (1280, 720)
FPS = 60
HOME_YEARS = (1, 3, 10, 30)  # the home pace's summers drawn (benchmarks.years' saves)
MATURE = 20.0  # physiological time the big tree rests before the frames (its old parts stop growing)


def _frames(game, ctx, fbo, n: int, each=None) -> tuple[np.ndarray, np.ndarray]:
    """Wall and CPU milliseconds of ``n`` frames of the game loop (CPU: this process, all its threads)."""
    from arbor.engine.life.world.actions import Action

    wall, cpu = [], []
    for i in range(n):
        start, start_cpu = time.perf_counter(), time.process_time()
        if each is not None:
            each(i)
        game.act(Action.WATER, float(game.world.sim.state.water_meter < 0.55))
        game.update(1 / FPS)
        game.draw(fbo)
        ctx.finish()
        wall.append(time.perf_counter() - start)
        cpu.append(time.process_time() - start_cpu)
    return np.array(wall) * 1e3, np.array(cpu) * 1e3


def _report(name: str, times: tuple[np.ndarray, np.ndarray], note: str = "") -> None:
    wall, cpu = times
    p50, p95, p99 = np.percentile(wall, [50, 95, 99])
    c50, c95 = np.percentile(cpu, [50, 95])
    print(f"{name:<34} {len(wall):>4} frames  wall p50 {p50:6.1f} p95 {p95:6.1f} p99 {p99:6.1f}  "
          f"CPU p50 {c50:6.1f} p95 {c95:6.1f} ms  {note}", flush=True)


def _drawn(game) -> str:
    """The cared-for tree's leaf clusters, and what the renderer drew of it in the last frame."""
    world = game.world
    entry = game.view.views.get(id(world))  # (its leaf records: shoot units hold leaves no L module shows)
    leaves = len(entry[1].leaves) if entry is not None else int(np.count_nonzero(world.tree.lstring.sym == ord("L")))
    details = game.renderer.last_details
    if not details:
        return f"({leaves:,} leaf clusters; nothing drawn)"
    d = details[0]
    r = game.renderer
    how = f"a picture over frames, leaves in {r.leaf_steps} shares" if r.last_layered else "whole every frame"
    return (f"({leaves:,} leaf clusters; drawn: LOD {d.lod}, {d.tubes:,} grown segments, {d.leaves:,} grown "
            f"leaf cards, share {d.leaf_share:.2f}, at {r.last_scale:.2f} of the resolution, {how})")


ZOOMS = {"default": 1.0, "close": None}  # camera distance factor (close: the game's nearest)


def _zooms(game, ctx, fbo, n: int, each, name: str) -> None:
    """The tree at the default zoom and close up, the level of detail left to the game."""
    kept = game.control.distance
    for zoom, factor in ZOOMS.items():
        game.control.distance = game.control.min_distance if factor is None else factor
        game.state.remember()
        times = _frames(game, ctx, fbo, n, each)
        _report(f"{name}, {zoom} zoom", times, _drawn(game))
    game.control.distance = kept


def grown_tree(days: float, summer: bool = False):
    """A world grown ``days`` simulated days by a careful player (the living model); with ``summer`` its
    calendar starts so that the last day is midsummer (full leaves)."""
    from arbor.engine.life.rules.rules import load_rules
    from arbor.engine.life.world.actions import Action
    from arbor.engine.life.world.world import World
    from arbor.engine.lsystem.lsys import load_lsystem
    from arbor.game.paths import ASSETS

    rules = load_rules(ASSETS / "rules.toml", pace="demo")
    world = World(load_lsystem(ASSETS / "lsystems" / "game_tree.lsys"), rules, seed=3)
    world.sim.state.sun_meter = world.sim.state.water_meter = 0.9
    if summer and rules.seasons.enabled:  # a year's 0.375 (midsummer) on the last day
        year = rules.seasons.year_days
        world.sim.state.sun_turns = ((0.375 - rules.seasons.start) * year - days) % year
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
    """A growing tree's records: a full rebuild against the incremental update of the same growth, per
    tree size, just after a rewrite (so its newest parts are growing: updating nothing proves nothing)."""
    from arbor.engine.life.form.growth_view import GrowthView
    from arbor.engine.life.form.interpret import Clocks

    print("a growing tree's records, per frame: full rebuild vs incremental update of what grows (CPU ms):")
    for tree, t in trees:
        t += 0.05  # just after the last rewrite: its new parts grow
        view = GrowthView(tree.lstring, Clocks(t, t), tree.geometry_constants)
        builds, updates = [], []
        for k in range(1, 11):
            clocks = Clocks(t + 0.002 * k, t)
            start = time.process_time()
            GrowthView(tree.lstring, clocks, tree.geometry_constants)
            builds.append(time.process_time() - start)
            start = time.process_time()
            view.update(clocks)
            updates.append(time.process_time() - start)
        young = len(view.tubes) - view.young_row
        build, update = np.median(builds) * 1e3, np.median(updates) * 1e3
        print(f"  {len(view.tubes):>7,} segments ({young:,} growing): full rebuild {build:7.1f} ms, "
              f"incremental update {update:6.2f} ms  (ratio {build / max(update, 1e-6):.0f}x)", flush=True)


def _home_pace(folder: Path | None) -> list:
    """The home pace's tree in the summer of its first, third, tenth and thirtieth year (benchmarks.years'
    saves), those found, each in the early afternoon (the saves are written at night)."""
    from arbor.engine.life.keep.save import read_garden
    from arbor.engine.life.plant.sim import sun_angle_at

    found = []
    for year in HOME_YEARS:
        path = None if folder is None else folder / f"summer_{year}.arbor"
        if path is not None and path.exists():
            world = read_garden(path, budget_slack=2.0).worlds[0]
            world.sim.state.sun_angle = sun_angle_at(13 * 3600)
            found.append((f"home pace, year {year} summer", world))
        else:
            print(f"(home pace, year {year}: no summer_{year}.arbor; run python -m benchmarks.years {year} DIR, "
                  "then --years DIR)")
    return found


def _home_trees(game, ctx, fbo, n: int, tick, folder: Path | None) -> None:
    """The home pace's trees at both zooms, drawn as the game draws them and (the old way) whole every frame."""
    from arbor.game.render import garden

    for name, world in _home_pace(folder):
        game.garden.worlds[0] = world
        game.state.remember()
        _frames(game, ctx, fbo, 5, tick)
        kept = garden.LAYER_COST
        try:
            garden.LAYER_COST = float("inf")  # (scale < 1, the biggest crowns close up, stays layered)
            _zooms(game, ctx, fbo, n, tick, f"{name}, whole every frame")
        finally:
            garden.LAYER_COST = kept
        _zooms(game, ctx, fbo, n, tick, name)
        _turning(game, ctx, fbo, n, tick, name)
        _rebuild(world)


def _turning(game, ctx, fbo, n: int, tick, name: str) -> None:
    """The tree at the default zoom while the camera turns round it (0.6 degrees a frame: a slow drag), where
    no picture is reused: sky, ground and trees drawn anew every frame."""
    game.control.distance = 1.0
    game.state.remember()

    def turn(i: int) -> None:
        tick(i)
        game.control.yaw += 0.6

    yaw = game.control.yaw
    _report(f"{name}, default zoom, camera turning", _frames(game, ctx, fbo, n, turn), _drawn(game))
    game.control.yaw = yaw


def _rebuild(world) -> None:
    """What a rewrite of ``world``'s tree costs the frame it shows in: its records built anew and sorted
    for upload (median CPU ms of 5)."""
    from arbor.engine.life.form.growth_view import GrowthView
    from arbor.game.render.instanced import prepare_upload

    costs = []
    for _ in range(5):
        start = time.process_time()
        prepare_upload(GrowthView(world.tree.lstring, world.clocks(), world.tree.geometry_constants))
        costs.append(time.process_time() - start)
    print(f"  a rewrite's records ({len(world.tree.lstring):,} modules): built and sorted in "
          f"{np.median(costs) * 1e3:.1f} ms CPU", flush=True)


def main() -> None:
    """Run every scenario and print the figures."""
    import pygame

    from arbor.game.render.renderer import headless_context
    from arbor.game.screens.game import Game, GameConfig

    quick, home = "--quick" in sys.argv, "--home" in sys.argv
    years = Path(sys.argv[sys.argv.index("--years") + 1]) if "--years" in sys.argv else None
    pygame.init()
    pygame.display.set_mode((64, 64))
    ctx = headless_context()
    fbo = ctx.framebuffer(color_attachments=[ctx.renderbuffer(SIZE)], depth_attachment=ctx.depth_renderbuffer(SIZE))
    print(f"GL: {ctx.info['GL_RENDERER']}, {SIZE[0]}x{SIZE[1]}; load average "
          + " ".join(f"{x:.2f}" for x in os.getloadavg()))
    n = 60 if quick else 240
    with TemporaryDirectory() as saves:
        clock = [1000.0]
        game = Game(ctx, SIZE, GameConfig(saves=Path(saves), seed=5, resume=False), clock=lambda: clock[0])

        def tick(_):
            clock[0] += 1 / FPS

        _report("warm-up (first frames: compiles, uploads)", _frames(game, ctx, fbo, 30, tick), _drawn(game))
        if home:
            _home_trees(game, ctx, fbo, n, tick, years)
        else:
            _everything(game, ctx, fbo, n, tick, years, quick)
    print("load average " + " ".join(f"{x:.2f}" for x in os.getloadavg()))
    ctx.release()


def _everything(game, ctx, fbo, n: int, tick, years: Path | None, quick: bool) -> None:
    """Every scenario after the warm-up (see the module docstring)."""
    _zooms(game, ctx, fbo, n, tick, "sapling")
    days = 6 if quick else 25
    game.garden.worlds[0] = grown_tree(days, summer=True)
    _frames(game, ctx, fbo, 5, tick)  # (its first upload, apart)
    _zooms(game, ctx, fbo, n, tick, f"summer tree, {days} days")
    _home_trees(game, ctx, fbo, n, tick, years)
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
    while game.view.pending:  # the first build of the big tree (on the worker thread), apart
        time.sleep(0.05)
        game.draw(fbo)
    _zooms(game, ctx, fbo, n, tick, f"{tree.lstring.count('I'):,}-internode tree, growing")
    sizes = [big_tree(s) for s in ((1_000, 3_000) if quick else (1_000, 3_000, 10_000, 25_000, 50_000))]
    rebuild_costs(sizes)


if __name__ == "__main__":
    main()
