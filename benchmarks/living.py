"""The living tree over 30 simulated days, and what one light reading costs at the module budget.

Run: python -m benchmarks.living [DAYS] [SAVE]
A scripted careful player keeps the water meter between 0.55 and 0.75 under the default rules; the
table has one row per simulated day (126 s at the demo pace): height, trunk girth, modules, leaf
clusters and branches shed that day. It checks that modules never pass the budget and that no day
passes without growth. Then it times one light reading (turtle + light grid + writing the string)
on the grown tree, median of 20, and the light grid's compiled pass against its numpy peer (benchmarks/numpy_light.py).
"""

from __future__ import annotations

import copy
import sys
import time
from pathlib import Path

import numpy as np

from arbor.engine.life.experiment.lab import measure
from arbor.engine.life.plant.light import exposure, optical_depth
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.world import World, sense_light
from arbor.engine.lsystem.lsys import load_lsystem
from benchmarks import median_ms, numpy_light

ASSETS = Path(__file__).resolve().parent.parent / "assets"


def careful_player(days: float, seasons: bool = False) -> World:
    """Grow a tree for ``days`` simulated days, printing the daily table (an endless summer unless
    ``seasons``)."""
    rules = load_rules(ASSETS / "rules.toml", pace="demo")
    rules.seasons.enabled = seasons
    world = World(load_lsystem(ASSETS / "lsystems" / "game_tree.lsys"), rules, seed=3)
    world.sim.state.sun_meter = world.sim.state.water_meter = 0.9
    day = 2 * np.pi / world.sim.state.sun_speed
    per_day = round(day / 0.5)
    budget = world.tree.deriver.budget
    print(f"{'day':>4} {'height':>7} {'girth':>6} {'modules':>8} {'leaves':>7} {'shed':>5}  status")
    last = measure(world)
    peak, flat_days, start = 0, 0, time.perf_counter()
    for d in range(1, int(days) + 1):
        for _ in range(per_day):
            s = world.sim.state
            world.apply(Action.WATER, float(s.water_meter < 0.75 if s.watering else s.water_meter < 0.55))
            world.step(0.5)
            peak = max(peak, len(world.tree.lstring))
        now = measure(world)
        grew = now["height"] > last["height"] + 1e-6 or now["girth"] > last["girth"] + 1e-6
        flat_days += not grew
        print(f"{d:4d} {now['height']:7.2f} {now['girth']:6.3f} {int(now['modules']):8,d} {int(now['leaves']):7d} "
              f"{int(now['shed'] - last['shed']):5d}  {world.status()}")
        last = now
    print(f"{days:g} days in {time.perf_counter() - start:.1f} s; peak modules {peak:,} (budget {budget:,}); "
          f"days without growth: {flat_days}")
    return world


def light_cost(world: World) -> None:
    """Time the parts of one light reading on ``world``'s tree."""
    world.sim.state.sun_angle = np.pi / 2  # noon
    clocks = world.clocks()
    ms_scene, scene = median_ms(lambda: world.tree.light_scene(clocks), 20)
    queries = scene.queries
    self_index = np.concatenate([np.arange(len(scene.leaf_idx)), np.full(len(queries) - len(scene.leaf_idx), -1)])
    ms_light, _ = median_ms(lambda: exposure(scene.leaf_center, scene.leaf_area, queries, world.sim.sun_direction(),
                                             world.rules.light, self_index), 20)
    ms_all, _ = median_ms(lambda: sense_light([world]), 20)
    print(f"light reading on {len(world.tree.lstring):,} modules ({len(scene.leaf_idx):,} leaf clusters, "
          f"{len(queries):,} receivers): turtle {ms_scene:.1f} ms + light grid {ms_light:.1f} ms; "
          f"whole reading (incl. writing the string) {ms_all:.1f} ms")
    sun, cell = world.sim.sun_direction(), world.rules.light.cell
    args = (scene.leaf_center, scene.leaf_area, queries, sun, cell, self_index)
    ms_kernel, ours = median_ms(lambda: optical_depth(*args), 50)
    ms_numpy, theirs = median_ms(lambda: numpy_light.optical_depth(*args), 50)
    print(f"  optical depth, one direction: compiled pass {ms_kernel:.2f} ms, the numpy peer {ms_numpy:.2f} ms "
          f"({ms_numpy / ms_kernel:.1f}x; largest difference {np.abs(ours - theirs).max():.1e} leaf areas per cell)")


def step_cost(world: World, runs: int = 10) -> None:
    """Time one whole growth step on ``world``'s tree: a light reading with its carbon booking, and a
    rewrite paid for by the pool (each on a fresh copy, so every run does the same work)."""
    world.sim.state.sun_angle = np.pi / 2  # noon
    ms_light, _ = median_ms(lambda: sense_light([world]), runs)
    times = []
    for _ in range(runs):
        w = copy.deepcopy(world)
        w.tree.last_rewrite_T = w.sim.state.length_time - w.rules.growth.rewrite_step
        start = time.perf_counter()
        w._rewrite()
        times.append(time.perf_counter() - start)
    ms_rewrite = float(np.median(times)) * 1e3
    print(f"one growth step at {len(world.tree.lstring):,} modules (budget {world.tree.deriver.budget:,}): "
          f"light and carbon {ms_light:.1f} ms + rewrite {ms_rewrite:.1f} ms = {ms_light + ms_rewrite:.1f} ms "
          "(goal <= 15 ms)")


def main() -> None:
    """Run the 30-day table and the light timing; with a save (e.g. `python -m benchmarks.years 3 DIR`'s
    DIR/spring_3.arbor, a tree near the budget), time a light reading and a growth step on its tree instead."""
    if len(sys.argv) > 2:
        from arbor.engine.life.keep.save import read_garden

        world = read_garden(sys.argv[2]).world
        light_cost(world)
        step_cost(world)
        return
    days = float(sys.argv[1]) if len(sys.argv) > 1 else 30.0
    world = careful_player(days)
    light_cost(world)
    step_cost(world)


if __name__ == "__main__":
    main()
