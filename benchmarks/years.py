"""Three simulated years at the home pace: does the crown stay full and shapely as the tree ages?

Run: python -m benchmarks.years [YEARS] [OUTDIR]
The home-pace player of benchmarks.home_pace (the can twice a day, nothing else) raises one tree for YEARS
years of 28 days. One row per season (at its last day, 13:00): height and crown width (m), width/height,
the most leaf clusters the season saw, modules (the most, against the budget), the carbon pool and the
days of the growing seasons (spring, summer) on which the tree did not grow. With OUTDIR, the tree's save
at every summer's end and every year's end (`summer_N.arbor`, `winter_N.arbor`: `arbor render` them).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

from arbor.engine.base.units import METRE
from arbor.engine.life.form.shoot_units import leaf_count
from arbor.engine.life.keep.save import SavedGarden, write_garden
from arbor.engine.life.plant.sim import sun_angle_at
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.garden import Garden
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import load_lsystem
from benchmarks.home_pace import ASSETS, STEP, water


def crown(world: World) -> tuple[float, float]:
    """(height, crown width) in metres from the tree's geometry now; unlike the lab's crown_shape (leaves only)
    the width spans wood and leaves, so a bare winter crown has one."""
    turtle = world.tree.geometry(world.clocks()).turtle
    if not len(turtle.segments):
        return 0.0, 0.0
    pts = np.concatenate([turtle.segments.end, turtle.leaves.position]) if len(turtle.leaves) else turtle.segments.end
    width = float(np.max(pts[:, [0, 2]].max(axis=0) - pts[:, [0, 2]].min(axis=0)))
    return float(turtle.segments.end[:, 1].max()) / METRE, width / METRE


def main(years: int = 3, out: Path | None = None) -> None:
    """Play ``years`` years and print the season table."""
    rules = load_rules(ASSETS / "rules.toml", pace="home")
    world = World(load_lsystem(ASSETS / "lsystems" / "game_tree.lsys"), rules, seed=3)
    world.sim.state.sun_angle = sun_angle_at(0.0)
    garden, budget = Garden([world]), world.tree.deriver.budget
    print(f"{'year':>4} {'season':>7} {'height':>6} {'width':>6} {'w/h':>5} {'leaves':>6} {'modules':>8} "
          f"{'pool g':>8} {'still days':>10}")
    start, peak_leaves, peak_modules, still, leaves_now = time.perf_counter(), 0, 0, 0, 0
    names, year, current = ("spring", "summer", "autumn", "winter"), 1, world.sim.season().index
    for _ in range(years * int(rules.seasons.year_days) + 1):
        season = world.sim.season().index  # the season this day begins in
        if season != current:  # a season has ended: its row
            h, w = crown(world)
            print(f"{year:4d} {names[current]:>7} {h:6.2f} {w:6.2f} {w / max(h, 1e-9):5.2f} {peak_leaves:6d} "
                  f"{peak_modules:8,d} {world.carbon.pool:8.0f} {still:10d}", flush=True)
            if out is not None and current == 1:
                out.mkdir(parents=True, exist_ok=True)
                write_garden(SavedGarden.of(garden, "game_tree.lsys"), out / f"summer_{year}.arbor")
            year += current == 3
            current, peak_leaves, peak_modules, still = season, leaves_now, 0, 0
        before = (world.sim.state.length_time, world.sim.state.girth_time)
        for minute in range(24 * 60):
            if minute in (8 * 60, 20 * 60):
                water(garden)
            garden.step(STEP)
            peak_modules = max(peak_modules, len(world.tree.lstring))
        leaves_now = leaf_count(world.tree.lstring)
        if world.sim.season().index == current:  # (a day that ended in the next season counts there)
            peak_leaves = max(peak_leaves, leaves_now)
            if out is not None and current == 3:  # the bare crown on the year's last day (rewritten daily)
                out.mkdir(parents=True, exist_ok=True)
                write_garden(SavedGarden.of(garden, "game_tree.lsys"), out / f"winter_{year}.arbor")
        still += season in (0, 1) and (world.sim.state.length_time, world.sim.state.girth_time) == before
    print(f"{years} years in {time.perf_counter() - start:.0f} s; budget {budget:,}; alive {world.sim.state.alive}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 3, Path(sys.argv[2]) if len(sys.argv) > 2 else None)
