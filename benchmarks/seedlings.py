"""Seedlings differ: one species, one regime, many seeds; how much do the trees vary?

Run: python -m benchmarks.seedlings [SEEDS] [DAYS] [SPECIES]
Each seed grows its own genome (engine/life/plant/genome.py) for DAYS simulated days under the default
sun, watered by a careful player between 0.55 and 0.75, in an endless summer. Prints height and crown width
(metres) per seed and their coefficients of variation (the plant-model issue asks for 3-10 % in height and
5-15 % in crown width over 20 seeds).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

from arbor.engine.base.units import METRE
from arbor.engine.life.experiment.measure import crown_shape
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import load_lsystem

ASSETS = Path(__file__).resolve().parent.parent / "assets"


def grown(species: str, seed: int, days: int) -> World:
    """One seedling of ``species`` grown ``days`` days by the careful player."""
    rules = load_rules(ASSETS / "rules.toml", pace="demo")
    rules.seasons.enabled = False
    world = World(load_lsystem(ASSETS / "lsystems" / f"{species}.lsys"), rules, seed=seed)
    world.sim.state.sun_meter = world.sim.state.water_meter = 0.9
    for _ in range(round(days * 2 * np.pi / world.sim.state.sun_speed / 0.5)):
        s = world.sim.state
        world.apply(Action.WATER, float(s.water_meter < 0.75 if s.watering else s.water_meter < 0.55))
        world.step(0.5)
    return world


def size(world: World) -> tuple[float, float]:
    """(height, crown width) in metres, as the lab measures them (experiment/measure.crown_shape)."""
    turtle = world.tree.geometry(world.clocks()).turtle
    shape = crown_shape(turtle.segments, turtle.leaves)
    return shape["height"] / METRE, shape["width"] / METRE


def main(seeds: int = 20, days: int = 20, species: str = "game_tree") -> None:
    """Grow ``seeds`` seedlings and print their sizes and the coefficients of variation."""
    start, rows = time.perf_counter(), []
    print(f"{species}, {days} days, default sun, careful watering")
    print(f"{'seed':>4} {'height m':>9} {'width m':>8} {'leaves':>7}  genome")
    for seed in range(1, seeds + 1):
        world = grown(species, seed, days)
        h, w = size(world)
        leaves = int(np.count_nonzero(world.tree.lstring.sym == ord("L")))
        rows.append((h, w))
        traits = " ".join(f"{k}={v:.3g}" for k, v in world.genome.items())
        print(f"{seed:4d} {h:9.2f} {w:8.2f} {leaves:7d}  {traits}", flush=True)
    h, w = np.array(rows).T
    cv = lambda x: 100 * x.std(ddof=1) / x.mean()  # noqa: E731
    print(f"height {h.mean():.2f} m, CV {cv(h):.1f} % (goal 3-10); crown width {w.mean():.2f} m, CV {cv(w):.1f} % "
          f"(goal 5-15); {time.perf_counter() - start:.0f} s")


if __name__ == "__main__":
    args = sys.argv[1:]
    main(int(args[0]) if args else 20, int(args[1]) if len(args) > 1 else 20, args[2] if len(args) > 2 else "game_tree")
