"""A player who only holds fast-forward: the guardian must keep every tree of the garden alive (issue 28).

The real game (headless: SDL dummy video, an EGL context, nothing drawn) with a garden of two trees
runs at 100x for 30 days of the sun, at the demo and the home pace; each time the guardian stops time
the scripted player presses "go on" (G) and nothing else. Printed per pace: the guardian's stops by
need, thirst episodes (a water meter at or under the need line) and how many came without a stop for
that tree's water before them, the lowest water and sun meters, the most wilt, and whether every tree is
alive at the end. At the home pace the fixed step is scaled by the pace's time scale (as the garden's
catch-up does), so 30 days take the same number of steps as at the demo pace.

With ``--gardener`` the player's Settings -> Gardener is on (engine/life/world/guardian.Gardener): the
garden is tended while time flies and stops only for decisions (ripe fruit, a tree wilting anyway or dead,
a season's first day).

    python -m benchmarks.kind [--days 30] [--speed 100] [--baseline] [--gardener]
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
from pathlib import Path

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("SDL_AUDIODRIVER", "dummy")

import moderngl

from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.guardian import NEEDS
from arbor.game.screens.game import Game, GameConfig

FRAME = 0.25  # real seconds a frame (the loop's clamp)


class Watch:
    """Per step: thirst episodes, and whether the guardian had told that tree's thirst before each."""

    def __init__(self, game: Game) -> None:
        self.game, self.rules = game, game.rules
        self.stops: list[tuple[int, int, str]] = []  # (step, tree, need)
        self.warned: set[int] = set()  # trees whose water need was told and that have not drunk since
        self.thirsty: set[int] = set()
        self.episodes = self.unwarned = 0
        self.low_water = self.low_sun = 1.0
        self.wilt = 0.0
        self.steps = 0
        game.state.on_halt.append(self.halted)
        garden = game.state.garden
        inner = garden.step
        garden.step = lambda dt: (inner(dt), self.after_step())  # type: ignore[method-assign]

    def halted(self) -> None:
        need = self.game.state.halted
        self.stops.append((self.steps, need.index, need.what))
        if need.what == "water":
            self.warned.add(need.index)

    def after_step(self) -> None:
        self.steps += 1
        line = self.rules.growth.threshold
        for i, world in enumerate(self.game.state.garden.worlds):
            s = world.sim.state
            self.low_water, self.low_sun = min(self.low_water, s.water_meter), min(self.low_sun, s.sun_meter)
            self.wilt = max(self.wilt, s.wilt)
            if s.water_meter <= line and i not in self.thirsty:
                self.thirsty.add(i)
                self.episodes += 1
                self.unwarned += i not in self.warned
            elif s.water_meter >= line + self.rules.health.guard_margin:
                self.thirsty.discard(i)
                self.warned.discard(i)


def run(pace: str, days: float, speed: float, ctx: moderngl.Context, guard: bool = True,
        gardener: bool = False) -> None:
    """One scripted player at ``pace``; prints one line of figures."""
    with tempfile.TemporaryDirectory() as saves:
        clock = [0.0]
        game = Game(ctx, (1280, 720), GameConfig(saves=Path(saves), seed=11, pace=pace),
                    clock=lambda: clock[0], wall_clock=lambda: 1.7e9 + clock[0])
        game.loop.dt *= game.rules.time_scale
        game.rules.first_day_speed = 1.0  # (a faster first day would take 144 of these coarse steps at once)
        # the can is held per 0.1 s step of the real game: a coarse step pours what 0.1 s would
        game.rules.water.fill_rate *= 0.1 / game.loop.dt
        if not guard:
            game.state.guardian.watch = lambda garden: None  # the baseline: nobody watches
        game.loop.max_steps = 1000
        game.sound.prefs.gardener = gardener
        game.act(Action.PLANT, 1.0)  # a garden of two: every tree is watched
        watch = Watch(game)
        game.set_speed(speed)
        day = 2 * 3.141592653589793 / game.world.sim.state.sun_speed
        started = time.perf_counter()
        while game.world.sim.state.time < days * day:
            clock[0] += FRAME
            game.update(FRAME)
            if game.state.halted is not None:
                game.act(Action.GO_ON, 1.0)
        kinds = ("water", "sun", "drown", "wilt", "died", "dying", "fruit", "season")
        needs = {w: sum(1 for *_, n in watch.stops if n == w) for w in kinds if gardener or w in NEEDS}
        alive = [w.sim.state.alive for w in game.state.garden.worlds]
        who = "gardener" if gardener else "guarded" if guard else "no guardian"
        print(f"{pace:5s} {who} {days:g} days at {speed:g}x: {len(watch.stops)} guardian stops {needs}; "
              f"thirst episodes {watch.episodes}, without a stop before {watch.unwarned}; lowest water "
              f"{watch.low_water:.3f}, lowest sun {watch.low_sun:.3f}, most wilt {watch.wilt:.3f}; "
              f"alive {sum(alive)}/{len(alive)}; statuses {[w.status() for w in game.state.garden.worlds]}; "
              f"{watch.steps} steps in {time.perf_counter() - started:.0f} s")


def main() -> None:
    """Both paces, 30 days at 100x by default."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--days", type=float, default=30.0)
    parser.add_argument("--speed", type=float, default=100.0)
    parser.add_argument("--paces", default="demo,home")
    parser.add_argument("--baseline", action="store_true", help="also run without the guardian")
    parser.add_argument("--gardener", action="store_true", help="Settings -> Gardener on")
    args = parser.parse_args()
    ctx = moderngl.create_standalone_context(backend="egl")
    for pace in args.paces.split(","):
        run(pace, args.days, args.speed, ctx, gardener=args.gardener)
        if args.baseline:
            run(pace, args.days, args.speed, ctx, guard=False)


if __name__ == "__main__":
    main()
