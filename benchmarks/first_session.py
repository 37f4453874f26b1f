"""A new garden's first session at the home pace (issue 47): does the player see their tree grow?

A new game on a fresh saves folder at the home pace, headless (SDL dummy video, an EGL context), played
for ``--minutes`` of a fake clock in frames of ``--frame`` real seconds. The player does what the HUD asks:
when the status says the tree is thirsty they hold the watering can until the blue meter is comfortable
(the rules' health.comfort), and nothing else. Printed, once a real minute: the tree's height (m) and
modules, its meters, the HUD's status line and its age and speed line. ``--out DIR`` writes the frame at
the start and at the end (``first_session_00min.png``, ``first_session_NNmin.png``).

    python -m benchmarks.first_session [--minutes 10] [--out DIR] [--start-hour 20.25] [--never-water]
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
from pathlib import Path

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("SDL_AUDIODRIVER", "dummy")

import numpy as np

SIZE = (1280, 720)


def start_time(hour: float) -> float:
    """Wall-clock seconds of today at ``hour`` o'clock local time (the home pace's sun follows the clock)."""
    day = time.localtime()
    midnight = time.mktime((day.tm_year, day.tm_mon, day.tm_mday, 0, 0, 0, 0, 0, -1))
    return midnight + hour * 3600.0


def new_game(ctx, hour: float):
    """A fresh home-pace game whose wall clock starts at ``hour`` o'clock; returns (game, its fake clock)."""
    from arbor.game.screens.game import Game, GameConfig

    clock = type("Clock", (), {"t": 100.0, "__call__": lambda self: self.t})()
    wall = start_time(hour)
    game = Game(ctx, SIZE, GameConfig(saves=Path(tempfile.mkdtemp()), seed=5, resume=False, pace="home",
                                      title=False), clock=clock, wall_clock=lambda: wall + clock.t - 100.0)
    return game, clock


def tend(game, water: bool) -> None:
    """The player: holds the can while the tree is thirsty, lets go once the meter is comfortable."""
    from arbor.engine.life.world.actions import Action
    from arbor.engine.life.world.status import water_low

    world = game.world
    if not water:
        return
    if water_low(world):
        game.act(Action.WATER, 1.0)
    elif world.sim.state.watering and world.sim.state.water_meter >= game.rules.health.comfort:
        game.act(Action.WATER, 0.0)


def row(game, minute: float) -> str:
    """One line of the table: what a player sees after ``minute`` real minutes."""
    from arbor.engine.base.units import METRE

    info, world = game.hud_info(), game.world
    s = world.sim.state
    return (f"{minute:5.1f} {world.tree.height / METRE:6.3f} {len(world.tree.lstring):5d} {s.sun_meter:4.2f} "
            f"{s.water_meter:4.2f}  {info.status[:58]:<58}  {'' if not info.speed_note else info.speed_note}")


def run(minutes: float, frame: float, hour: float, water: bool, out: Path | None) -> dict:
    """Play the first ``minutes``; returns the figures (height and modules after the first minute and at the
    end, the first minute the tree stood 1 cm taller than after the first minute)."""
    import pygame

    from arbor.engine.base.units import METRE
    from arbor.game.render.renderer import headless_context, save_png

    pygame.init()
    pygame.display.set_mode((64, 64))
    ctx = headless_context()
    game, clock = new_game(ctx, hour)
    fbo = ctx.framebuffer(color_attachments=[ctx.renderbuffer(SIZE)], depth_attachment=ctx.depth_renderbuffer(SIZE))
    draw_hud = game.hud.draw
    game.hud.draw = lambda camera: (fbo.use(), draw_hud(camera))  # (headless, the HUD goes over this target)

    def shot(minute: int) -> None:
        if out is not None:
            game.draw(fbo)
            pixels = np.frombuffer(fbo.read(components=3), np.uint8).reshape(SIZE[1], SIZE[0], 3)[::-1]
            save_png(pixels, out / f"first_session_{minute:02d}min.png")

    print(f"{'min':>5} {'height':>6} {'mods':>5} {'sun':>4} {'water':>4}  {'status':<58}  first day")
    print(row(game, 0.0))
    shot(0)
    grew_at, frames, minute = None, round(minutes * 60 / frame), round(60 / frame)
    start = (0.0, 0)
    for k in range(1, frames + 1):
        tend(game, water)
        game.update(frame)
        clock.t += frame
        if k == minute:  # (the sapling's height is measured at its first light reading: after a minute, from it)
            start = (game.world.tree.height / METRE, len(game.world.tree.lstring))
        if k > minute and grew_at is None and game.world.tree.height / METRE > start[0] + 0.01:
            grew_at = k * frame / 60
        if k % minute == 0:
            print(row(game, k * frame / 60))
    shot(round(minutes))
    end = (game.world.tree.height / METRE, len(game.world.tree.lstring))
    return {"start": start, "end": end, "grew_at": grew_at, "age_h": game.world.sim.state.time / 3600}


def main() -> None:
    """Parse the arguments, run, print."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--minutes", type=float, default=10.0, help="real minutes to play")
    parser.add_argument("--frame", type=float, default=0.25, help="real seconds a frame")
    parser.add_argument("--start-hour", type=float, default=20.25, help="the wall clock's hour at the start")
    parser.add_argument("--never-water", action="store_true", help="a player who never waters")
    parser.add_argument("--out", type=Path, help="folder for the pictures")
    args = parser.parse_args()
    if args.out:
        args.out.mkdir(parents=True, exist_ok=True)
    f = run(args.minutes, args.frame, args.start_hour, not args.never_water, args.out)
    grew = "never" if f["grew_at"] is None else f"after {f['grew_at']:.1f} min"
    print(f"after 1 min -> the end: height {f['start'][0]:.3f} -> {f['end'][0]:.3f} m, modules {f['start'][1]} -> "
          f"{f['end'][1]}; first 1 cm taller {grew}; the tree's age {f['age_h']:.1f} h of game time")


if __name__ == "__main__":
    main()
