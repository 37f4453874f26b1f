"""Breeding: 100 crosses of the two game species, each grown for 10 simulated days, and the traits.

Run: python -m benchmarks.breeding [CROSSES]
Crosses game_tree x game_poplar with seeds 0..N-1; every child must parse and grow for 10 days (demo
pace, endless summer, a careful player) without error. Prints how many grew, the time, and the traits
a player sees: branching angle BA and internode length IL (the child's constants) and the measured
crown width and height at 10 days, for both parents and the children (mean and range).
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import numpy as np

from arbor.engine.life.experiment.lab import measure
from arbor.engine.life.lineage.breed import cross
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import load_lsystem

ASSETS = Path(__file__).resolve().parent.parent / "assets"
DAYS = 10


def grown(system, seed: int) -> dict[str, float]:
    """The tree ``system`` grows in DAYS days under a careful player: its measures."""
    rules = load_rules(ASSETS / "rules.toml", pace="demo")
    rules.seasons.enabled = False
    world = World(system, rules, seed=seed)
    world.sim.state.sun_meter = world.sim.state.water_meter = 0.9
    for _ in range(int(DAYS * 2 * math.pi / world.sim.state.sun_speed / 0.5)):
        s = world.sim.state
        world.apply(Action.WATER, float(s.water_meter < 0.75 if s.watering else s.water_meter < 0.55))
        world.step(0.5)
    out = measure(world)
    out["alive"] = float(world.sim.state.alive)
    return out


def main(count: int) -> None:
    """Cross, grow, report."""
    mother, father = (load_lsystem(ASSETS / "lsystems" / f"{n}.lsys") for n in ("game_tree", "game_poplar"))
    rows = {"game_tree": [grown(mother, 3)], "game_poplar": [grown(father, 3)]}
    consts = {"game_tree": [mother.constants], "game_poplar": [father.constants]}
    start, failures, children = time.perf_counter(), 0, []
    for seed in range(count):
        try:
            child = cross(mother, father, seed)
            children.append(grown(child.system, 3))
            consts.setdefault("children", []).append(child.constants)
        except Exception as exc:  # a benchmark counts every failure, of any kind
            failures += 1
            print(f"seed {seed}: {type(exc).__name__}: {exc}")
    rows["children"] = children
    grew = sum(1 for c in children if c["alive"] and c["modules"] > 500)
    print(f"{count} crosses in {time.perf_counter() - start:.0f} s: {failures} failed, {grew} grew past 500 modules "
          f"in {DAYS} days (all alive: {all(c['alive'] for c in children)})")
    print(f"{'':12} {'BA (deg)':>18} {'IL':>16} {'width':>18} {'height':>18}")
    for name, measured in rows.items():
        ba = np.array([c["BA"] for c in consts[name]])
        il = np.array([c["IL"] for c in consts[name]])
        width = np.array([m["width"] for m in measured])
        height = np.array([m["height"] for m in measured])
        print(f"{name:12} " + " ".join(f"{v.mean():6.2f} [{v.min():5.2f}-{v.max():5.2f}]"
                                       for v in (ba, il, width, height)))


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 100)
