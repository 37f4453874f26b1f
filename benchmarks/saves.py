"""Save and load of big trees: 100k-module saves, written and read back (best and median of 5).

Run: python -m benchmarks.saves            (the table below)
     python -m benchmarks.saves scaling    (save, load and a light reading at 10k, 100k and 1M modules)
Trees of about 100,000 modules: the game tree (its living state: birth times, light, wood; most
parameters are full-precision floats; the grown tree's string repeated, so values repeat), the same
with every number made distinct (the writer's worst case), and the ABOP fig. 2.8 tree (short
numbers). For each: save (text, temp file, fsync, rename), the first load of the file (it parses the
embedded .lsys too; later loads reuse it), load (read, TOML, the L-string, checks), and the time
spent turning the L-string into text and back alone.
"""

from __future__ import annotations

import math
import os
import sys
import tempfile
import time
import tracemalloc
from pathlib import Path

import numpy as np

from arbor.engine.base.memory import keep_freed_memory
from arbor.engine.life.keep.save import SavedGarden, read_garden, write_garden
from arbor.engine.life.plant.light import exposure
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.derive import Deriver
from arbor.engine.lsystem.lstring import concat, parse_lstring
from arbor.engine.lsystem.lsys import load_lsystem

ASSETS = Path(__file__).resolve().parent.parent / "assets"
TARGET = 100_000


def _times(fn, runs: int = 5) -> tuple[float, float]:
    out = []
    for _ in range(runs):
        start = time.perf_counter()
        fn()
        out.append((time.perf_counter() - start) * 1e3)
    return min(out), float(np.median(out))


def game_world(rules, target: int = TARGET) -> World:
    """The game tree after 3,000 steps of a careful player, its string repeated to ``target`` modules."""
    world = World(load_lsystem(ASSETS / "lsystems" / "game_tree.lsys"), rules, seed=3)
    for _ in range(3000):
        world.apply(Action.WATER, float(world.sim.state.water_meter < 0.6))
        world.step(0.5)
    ls = world.tree.lstring
    world.tree.lstring = concat(*([ls] * (target // len(ls) + 1)))
    return world


def distinct_world(rules) -> World:
    """The game tree with every parameter made distinct (a tiny offset each): the worst case for the
    writer, which formats each distinct value once."""
    world = game_world(rules)
    ls = world.tree.lstring
    ls.params = ls.params + np.arange(len(ls.params)) * 1e-9
    return world


def abop_world(rules) -> World:
    """The ABOP fig. 2.8 tree derived past TARGET modules, in a world."""
    system = load_lsystem(ASSETS / "lsystems" / "abop_2_8_tree.lsys")
    world = World(system, rules, seed=1)
    ls = system.axiom
    deriver = Deriver(system)
    while len(ls) < TARGET:
        ls, _ = deriver.step(ls)
    world.tree.lstring = ls
    return world


def main() -> None:
    """Print the table (with the allocator set as `arbor` sets it)."""
    keep_freed_memory()
    rules = load_rules(ASSETS / "rules.toml", pace="demo")
    print(f"{'tree':10} {'modules':>8} {'numbers':>8} {'file MB':>8} {'save ms':>14} {'first load':>10} "
          f"{'load ms':>14} {'to_text ms':>14} {'parse ms':>14}")
    with tempfile.TemporaryDirectory() as folder:
        for name, world in (("game", game_world(rules)), ("distinct", distinct_world(rules)),
                            ("abop 2.8", abop_world(rules))):
            ls = world.tree.lstring
            path = Path(folder) / f"{name}.arbor"
            save = _times(lambda world=world, path=path: write_garden(SavedGarden([world]), path))
            slack = 2 * len(ls) / (world.system.budget or len(ls))  # (past the tree's own budget: allowed here)
            start = time.perf_counter()
            read_garden(path, rules, budget_slack=slack)  # the first load parses the embedded .lsys too
            first = (time.perf_counter() - start) * 1e3
            load = _times(lambda path=path, slack=slack: read_garden(path, rules, budget_slack=slack))
            text = ls.to_text()
            write = _times(ls.to_text)
            read = _times(lambda text=text: parse_lstring(text))
            print(f"{name:10} {len(ls):8,} {len(ls.params):8,} {path.stat().st_size / 1e6:8.2f} "
                  f"{save[0]:6.0f} /{save[1]:6.0f} {first:10.0f} "
                  + " ".join(f"{b:6.0f} /{m:6.0f}" for b, m in (load, write, read)))





SIZES = (10_000, 100_000, 1_000_000)
NAMES = ("save", "load", "scene", "grid")


def _cpu(fn, runs: int) -> float:
    """Best CPU seconds of ``runs`` calls (CPU time: the machine may be shared)."""
    best = math.inf
    for _ in range(runs):
        start = time.process_time()
        fn()
        best = min(best, time.process_time() - start)
    return best


def _peak(fn) -> int:
    """Peak bytes traced while ``fn`` runs (numpy's buffers included)."""
    tracemalloc.start()
    try:
        fn()
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def _arrays_file(ls, path: Path) -> tuple:
    """The L-string's arrays through np.savez and np.load: the floor a text save is measured against."""
    def save():
        np.savez(path, sym=ls.sym, nparams=ls.nparams, offsets=ls.offsets, params=ls.params)

    def load():
        with np.load(path) as data:
            return [data[k] for k in ("sym", "nparams", "offsets", "params")]
    return save, load


def _light(world):
    """One light reading's parts: the turtle's scene and the light grid (exposure) on it."""
    clocks = world.clocks()
    scene = world.tree.light_scene(clocks)
    queries = scene.queries
    own = np.concatenate([np.arange(len(scene.leaf_idx)), np.full(len(queries) - len(scene.leaf_idx), -1)])
    return (lambda: world.tree.light_scene(clocks),
            lambda: exposure(scene.leaf_center, scene.leaf_area, queries, world.sim.sun_direction(),
                             world.rules.light, own), len(scene.leaf_idx))


def scaling(runs: int = 3) -> None:
    """Save, load and one light reading of the game tree at 10k, 100k and 1M modules: CPU time, the growth
    per 10x modules, and the peak memory of save and load (tracemalloc) over the tree's bytes."""
    keep_freed_memory()
    rules = load_rules(ASSETS / "rules.toml", pace="demo")
    world = game_world(rules, 0)
    world.sim.state.sun_angle = np.pi / 2  # noon: the light reading does its work
    grown = world.tree.lstring
    print(f"load average {' '.join(f'{x:.2f}' for x in os.getloadavg())}; CPU ms, best of {runs}")
    print(f"{'modules':>9} {'tree MB':>7} {'save':>8} {'/savez':>6} {'load':>8} {'/np.load':>8} "
          f"{'peak save':>9} {'peak load':>9} {'scene':>7} {'grid':>7} {'leaves':>8}")
    last = None
    with tempfile.TemporaryDirectory() as folder:
        for size in SIZES:
            world.tree.lstring = concat(*([grown] * max(1, round(size / len(grown)))))  # whole trees
            ls = world.tree.lstring
            path, arrays = Path(folder) / "tree.arbor", Path(folder) / "tree.npz"
            slack = 2 * len(ls) / (world.system.budget or len(ls))
            saved = SavedGarden([world])
            save = _cpu(lambda saved=saved, path=path: write_garden(saved, path), runs)
            read_garden(path, rules, budget_slack=slack)
            load = _cpu(lambda path=path, slack=slack: read_garden(path, rules, budget_slack=slack), runs)
            np_save, np_load = _arrays_file(ls, arrays)
            floor_save, floor_load = _cpu(np_save, runs), _cpu(np_load, runs)
            peak_save = _peak(lambda saved=saved, path=path: write_garden(saved, path)) / ls.nbytes
            peak_load = _peak(lambda path=path, slack=slack: read_garden(path, rules, budget_slack=slack)) / ls.nbytes
            scene_fn, grid_fn, leaves = _light(world)
            scene, grid = _cpu(scene_fn, runs), _cpu(grid_fn, runs)
            now = (len(ls), save, load, scene, grid)
            print(f"{len(ls):9,} {ls.nbytes / 1e6:7.1f} {save * 1e3:8.1f} {save / floor_save:6.1f} {load * 1e3:8.1f} "
                  f"{load / floor_load:8.1f} {peak_save:8.1f}x {peak_load:8.1f}x {scene * 1e3:7.1f} {grid * 1e3:7.1f} "
                  f"{leaves:8,}", flush=True)
            if last is not None:  # growth scaled to exactly 10x modules
                power = math.log(10) / math.log(now[0] / last[0])
                print("    x per 10x modules: " + ", ".join(
                    f"{name} {(b / a) ** power:.1f}" for name, a, b in zip(NAMES, last[1:], now[1:], strict=True)))
            last = now


if __name__ == "__main__":
    scaling() if "scaling" in sys.argv[1:] else main()
