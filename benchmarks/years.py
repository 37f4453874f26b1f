"""Years at the home pace: does the crown keep getting grander, shaped by light and never by the budget?

Run: python -m benchmarks.years [YEARS] [OUTDIR] [SPECIES]   (default 3 years of game_tree.lsys; the issue's
run is 30; SPECIES another of assets/lsystems, e.g. game_poplar.lsys)
The home-pace player of benchmarks.home_pace (the can twice a day, nothing else) raises one tree for YEARS
years of 28 days. One row per season (at its last day, 13:00): height and crown width (m), width/height,
the trunk's diameter at breast height (1.3 m, or at its foot while shorter; cm), the most leaf clusters the
season saw, modules (the most, against the budget), the carbon pool, the days of the growing seasons
(spring, summer) on which the tree did not grow, the crown's base (the foot of the lowest living limb on the trunk,
m) and the scars of limbs shed (stubs). With OUTDIR, the tree's save at every summer's end and
every year's end (`summer_N.arbor`, `winter_N.arbor`: `arbor render` them) and OUTDIR/years.png: every
summer's tree side by side at one scale, six a row, each with a metre bar.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

from arbor.engine.base.units import METRE
from arbor.engine.life.form.interpret import INTERNODE
from arbor.engine.life.form.shoot_units import leaf_count
from arbor.engine.life.keep.save import SavedGarden, read_garden, write_garden
from arbor.engine.life.plant.journal import turtle_size
from arbor.engine.life.plant.sim import sun_angle_at
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.garden import Garden
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lstring import params_where
from arbor.engine.lsystem.lsys import load_lsystem
from benchmarks.home_pace import ASSETS, STEP, water

BREAST = 1.3  # m: where a trunk's diameter is measured (d.b.h.)


def crown(world: World) -> tuple[float, float, float]:
    """(height m, crown width m, trunk diameter at breast height cm) from the tree's geometry now; unlike the
    lab's crown_shape (leaves only) the width spans wood and leaves (journal.turtle_size), so a bare winter
    crown has one."""
    turtle = world.tree.geometry(world.clocks()).turtle
    segs = turtle.segments
    if not len(segs):
        return 0.0, 0.0, 0.0
    height, width = turtle_size(turtle)
    trunk = np.flatnonzero(segs.order == 0)
    at = min(BREAST * METRE, float(segs.end[trunk, 1].max()) * 0.5)
    spans = trunk[(segs.start[trunk, 1] <= at) & (segs.end[trunk, 1] >= at)]
    radius = float(segs.radius[spans[0]]) if len(spans) else float(segs.radius[trunk[0]])
    return height, width, 200.0 * radius / METRE


def crown_base(world: World) -> tuple[float, int]:
    """(the foot of the lowest living limb on the trunk m, the scars: stubs of limbs shed; see
    engine/life/plant/shedding.py): the crown's base rises as the lower limbs that pay no more die and fall."""
    ls, turtle = world.tree.lstring, world.tree.geometry(world.clocks()).turtle
    segs = turtle.segments
    internode = (ls.sym[segs.module] == INTERNODE) & (ls.nparams[segs.module] >= 5)
    shade = params_where(ls.params, internode, ls.offsets[segs.module] + 3)
    order = params_where(ls.params, internode, ls.offsets[segs.module] + 2)
    limb = internode & (order == 1) & ~segs.continues & (segs.parent >= 0)
    alive = limb & (shade >= 0) & (shade <= world.tree.geometry_constants["SHED"])
    base = float(segs.start[alive, 1].min()) / METRE if alive.any() else float("nan")
    return base, int(np.count_nonzero(limb & (shade < 0)))


def main(years: int = 3, out: Path | None = None, species: str = "game_tree.lsys") -> None:
    """Play ``years`` years and print the season table."""
    rules = load_rules(ASSETS / "rules.toml", pace="home")
    world = World(load_lsystem(ASSETS / "lsystems" / species), rules, seed=3)
    world.sim.state.sun_angle = sun_angle_at(0.0)
    garden, budget = Garden([world]), world.tree.deriver.budget
    print(f"{'year':>4} {'season':>7} {'height':>6} {'width':>6} {'w/h':>5} {'dbh cm':>6} {'leaves':>6} "
          f"{'modules':>8} {'pool g':>8} {'still days':>10} {'base m':>6} {'scars':>5}")
    start, peak_leaves, peak_modules, still, leaves_now = time.perf_counter(), 0, 0, 0, 0
    names, year, current = ("spring", "summer", "autumn", "winter"), 1, world.sim.season().index
    for _ in range(years * int(rules.seasons.year_days) + 1):
        season = world.sim.season().index  # the season this day begins in
        if season != current:  # a season has ended: its row
            h, w, dbh = crown(world)
            base, scars = crown_base(world)
            print(f"{year:4d} {names[current]:>7} {h:6.2f} {w:6.2f} {w / max(h, 1e-9):5.2f} {dbh:6.2f} "
                  f"{peak_leaves:6d} {peak_modules:8,d} {world.carbon.pool:8.0f} {still:10d} {base:6.2f} {scars:5d}",
                  flush=True)
            if out is not None and current == 1:
                out.mkdir(parents=True, exist_ok=True)
                write_garden(SavedGarden.of(garden, species), out / f"summer_{year}.arbor")
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
                write_garden(SavedGarden.of(garden, species), out / f"winter_{year}.arbor")
        still += season in (0, 1) and (world.sim.state.length_time, world.sim.state.girth_time) == before
    print(f"{years} years in {time.perf_counter() - start:.0f} s; budget {budget:,}; alive {world.sim.state.alive}")
    if out is not None:
        print(f"{strip(out, years)}: each summer's end at one scale (the bar at the left of each)")


def _extent(geometry) -> float:
    """A tree's height, or its crown's reach from the trunk x 1.3 if more (m): what a frame must hold (a tile
    is 1.6 x as wide as high: it shows 0.8 frames either side of the trunk)."""
    ends = geometry.turtle.segments.end
    reach = float(np.abs(ends[:, [0, 2]]).max()) if len(ends) else 0.0
    return max(float(ends[:, 1].max(initial=0.0)), 1.3 * reach) / METRE


def strip(out: Path, years: int, tile: tuple[int, int] = (400, 250), per_row: int = 6) -> Path:
    """``out``/years.png: the tree at each summer's end (its save ``summer_N.arbor``), side by side at one
    scale (the frame of the tallest or widest), six a row, each with its metre bar and its year."""
    import moderngl
    import pygame

    from arbor.game.render.renderer import save_png
    from arbor.game.render.scale_bar import frame_for, render_to_scale

    worlds = [read_garden(out / f"summer_{y}.arbor").world for y in range(1, years + 1)]
    geometries = [w.tree.geometry(w.clocks()) for w in worlds]
    frame = frame_for(max(_extent(g) for g in geometries))  # (the tallest, or the widest, fits)
    ctx = moderngl.create_standalone_context(backend="egl")
    pygame.font.init()
    font = pygame.font.Font(None, 28)
    rows = -(-years // per_row)
    picture = np.full((rows * tile[1], min(years, per_row) * tile[0], 3), 255, np.uint8)
    for k, geometry in enumerate(geometries):
        pixels = render_to_scale(geometry.mesh, tile, frame, ctx=ctx)
        label = pygame.surfarray.array3d(font.render(f"year {k + 1}", True, (20, 20, 20), (235, 235, 235)))
        label = label.swapaxes(0, 1)
        pixels[4:4 + label.shape[0], tile[0] - label.shape[1] - 4:tile[0] - 4] = label
        r, c = divmod(k, per_row)
        picture[r * tile[1]:(r + 1) * tile[1], c * tile[0]:(c + 1) * tile[0]] = pixels
    ctx.release()
    save_png(picture, out / "years.png")
    return out / "years.png"


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 3, Path(sys.argv[2]) if len(sys.argv) > 2 else None,
         sys.argv[3] if len(sys.argv) > 3 else "game_tree.lsys")
