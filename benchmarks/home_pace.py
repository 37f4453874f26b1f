"""A home-pace player over 30 simulated days: seasons, blossoms, fruit and the meters, day by day.

Run: python -m benchmarks.home_pace [DAYS] [WATERINGS_A_DAY]
The player waters twice a day (at 08:00 and 20:00 of the clock, holding the can for 8 s each time)
under the rules' home pace (`pace = "home"` in assets/rules.toml: a day of the sun lasts a day), and
never touches anything else. Steps are 60 s of game time (the meters move by about 1/1000 of their
range per step at this pace) and 1 s while the can is held. One row per day at 13:00: season,
height (m), leaf clusters, blossoms, fruit, both meters, the status and the journal's new entries.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

from arbor.engine.life.plant.journal import METRE
from arbor.engine.life.plant.sim import sun_angle_at
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.garden import Garden
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import load_lsystem

ASSETS = Path(__file__).resolve().parent.parent / "assets"
STEP = 60.0
HOLD = 8.0  # seconds the can is held at each watering


def water(garden: Garden) -> None:
    """Hold the can over the cared-for tree for HOLD seconds (1 s steps: the meter fills fast)."""
    world = garden.world
    world.apply(Action.WATER, 1.0)
    for _ in range(int(HOLD)):
        garden.step(1.0)
    world.apply(Action.WATER, 0.0)


def play(days: int, waterings: int = 2) -> Garden:
    """Play ``days`` days at the home pace, printing the table; returns the garden."""
    rules = load_rules(ASSETS / "rules.toml", pace="home")
    world = World(load_lsystem(ASSETS / "lsystems" / "game_tree.lsys"), rules, seed=3)
    world.sim.state.sun_angle = sun_angle_at(0.0)  # midnight: the sun's noon is the clock's noon
    garden = Garden([world])
    hours = [8 + 12 * k / waterings for k in range(waterings)] if waterings else []
    print(f"{'day':>3} {'season':>7} {'height':>6} {'leaves':>6} {'bloss':>5} {'fruit':>5} {'sun':>5} "
          f"{'water':>5} {'wilt':>4}  {'status':<12} journal")
    seen, start = 0, time.perf_counter()
    clock = 0.0
    for day in range(days):
        for hour in range(24 * 60):
            clock = day * 86400.0 + hour * 60.0
            if any(abs(clock % 86400.0 - h * 3600.0) < STEP / 2 for h in hours):
                water(garden)
            garden.step(STEP)
            if hour == 13 * 60:
                seen = row(day + 1, world, seen)
    print(f"{days} days in {time.perf_counter() - start:.1f} s; modules {len(world.tree.lstring):,}; "
          f"alive {world.sim.state.alive}")
    return garden


def row(day: int, world: World, seen: int) -> int:
    """Print one day's row; returns how many journal entries are printed so far."""
    s, ls = world.sim.state, world.tree.lstring
    leaves = ls.count("L")
    new = [f"{k}{'' if v == 0 else f' {v:g}'}" for _, k, v in world.journal.entries[seen:]]
    print(f"{day:3d} {world.sim.season().name:>7} {world.tree.height / METRE:6.2f} {leaves:6d} {ls.count('K'):5d} "
          f"{ls.count('O'):5d} {s.sun_meter:5.2f} {s.water_meter:5.2f} {s.wilt:4.2f}  {world.status():<12} "
          f"{', '.join(new)}", flush=True)
    return len(world.journal.entries)


if __name__ == "__main__":
    play(int(sys.argv[1]) if len(sys.argv) > 1 else 30, int(sys.argv[2]) if len(sys.argv) > 2 else 2)
