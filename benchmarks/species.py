"""The game's six species side by side (issue 47): the collection of assets/species.toml, one seedling of
each grown by a careful player at the demo pace to the first summer's fullest crown, on into its first
winter and to the second summer's, drawn by the game's renderer (headless) through one camera under one
sun: a row an age, the species side by side at one scale.

    python -m benchmarks.species [--out DIR] [--days D ...] [--species KEY,...]

Prints each species' height, crown width (m), leaf cards, branch pieces and wood density at each age, and
writes DIR/species.png (default docs/).
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np
from PIL import Image

from benchmarks.shots import LOOK, SPRING, _Looks, summer_day

YEAR = 28.0  # days of the sun in a year at the demo pace (SPRING: a day of the second spring)


def grow(system, days: float, seed: int, world=None):
    """A world of ``system`` grown to ``days`` days of the sun by a careful player (demo pace), or ``world``
    grown on to that day."""
    from arbor.engine.life.rules.rules import load_rules
    from arbor.engine.life.world.actions import Action
    from arbor.engine.life.world.world import World
    from arbor.game.paths import ASSETS

    if world is None:
        world = World(system, load_rules(ASSETS / "rules.toml", pace="demo"), seed=seed)
        world.sim.state.sun_meter = world.sim.state.water_meter = 0.9
    while world.sim.state.sun_turns < days:
        world.apply(Action.WATER, float(world.sim.state.water_meter < 0.6))
        world.step(0.5)
    return world


STRIP = 400  # pixels of the picture's width for each species


def row(looks, placed: list, worlds: list, names: list[str]) -> np.ndarray:
    """Each tree drawn alone at the origin through one camera (framing the largest), its middle STRIP
    columns side by side, each named at its foot: the species at one scale under one sun."""
    from PIL import ImageDraw, ImageFont

    from arbor.game.render.renderer import sun_direction

    lo = np.min([np.asarray(p.buffers.view.lo) for p in placed], axis=0)
    hi = np.max([np.asarray(p.buffers.view.hi) for p in placed], axis=0)
    wide = max(hi[0] - lo[0], hi[2] - lo[2])
    lo[0], hi[0], lo[2], hi[2] = -wide / 2, wide / 2, -wide / 2, wide / 2
    camera = looks.camera([placed[0]], 0.0, 6.0, 0.9)
    camera.frame_bounds(lo, hi, LOOK[0] / LOOK[1], fill=0.9)
    strips = []
    for tree, world, name in zip(placed, worlds, names, strict=True):
        looks.renderer.pictures.release()  # (a software GL draws a costly crown as a picture over frames: whole now)
        looks.shot("species_one", camera, sun_direction(80.0, 40.0), [tree], world)
        pixels = np.asarray(Image.open(looks.paths[-1]))
        strip = Image.fromarray(pixels[:, (LOOK[0] - STRIP) // 2:(LOOK[0] + STRIP) // 2].copy())
        ImageDraw.Draw(strip).text((12, LOOK[1] - 44), f"{name}, day {world.sim.state.sun_turns:.1f}",
                                   fill=(255, 255, 255), font=ImageFont.load_default(size=28))
        strips.append(np.asarray(strip))
    looks.paths[-1].unlink()
    return np.concatenate(strips, axis=1)


def main() -> None:
    """Grow, print, draw."""
    import pygame

    from arbor.engine.base.units import METRE
    from arbor.engine.life.lineage.species import load_collection, species_system
    from arbor.game.paths import ASSETS

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=Path("docs"))
    parser.add_argument("--days", type=float, nargs="+", default=None,
                        help="days of the sun, a row each (default: the first summer's fullest crown, the first "
                             "winter, the second summer's)")
    parser.add_argument("--species", default="", help="only these species (keys, comma-separated)")
    args = parser.parse_args()
    pygame.init()
    args.out.mkdir(parents=True, exist_ok=True)
    summer = summer_day()
    ages = args.days or [summer, SPRING - 4.0, summer + YEAR]
    looks = _Looks(args.out)
    looks.renderer.vertex_budget = 10_000_000  # (every tree drawn whole, as a real GPU draws it)
    chosen = [s for s in load_collection(ASSETS / "species.toml", ASSETS / "lsystems")
              if not args.species or s.key in args.species.split(",")]
    worlds = [None] * len(chosen)
    rows = []
    for days in ages:
        placed, names = [], []
        for k, species in enumerate(chosen):
            started = time.perf_counter()
            worlds[k] = world = grow(species_system(species, ASSETS / "lsystems"), days, 3 + k, worlds[k])
            tree = looks.placed(world)
            placed.append(tree)
            names.append(species.name)
            view = tree.buffers.view
            lo, hi = np.asarray(view.lo), np.asarray(view.hi)
            print(f"day {days:g} {species.name:7s} ({species.key}): {world.tree.height / METRE:5.2f} m tall, crown "
                  f"{(hi[0] - lo[0]) / METRE:4.2f} m wide, {len(view.leaves):5,} leaf cards, {len(view.tubes):5,} "
                  f"branch pieces, wood {world.tree.system.constants.get('WD', 650):g} kg/m3 "
                  f"({time.perf_counter() - started:.1f} s to grow)")
        rows.append(row(looks, placed, worlds, names))
    out = args.out / "species.png"
    picture = Image.fromarray(np.concatenate(rows, axis=0))
    picture.resize((picture.width // 2, picture.height // 2), Image.Resampling.LANCZOS).save(out)  # (half size)
    print(f"{out}: the species at {', '.join(f'{d:g}' for d in ages)} days, a row each at one scale, "
          "same camera and sun")
    looks.renderer.release()
    looks.ctx.release()


if __name__ == "__main__":
    main()
