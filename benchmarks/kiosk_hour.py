"""The kiosk left alone for an hour at its own pace (issue 28): a visitor must always find a living tree.

Run it in a real window under Xvfb (it refuses SDL's invisible fallback, as the game does):

    xvfb-run -a -s "-screen 0 1280x720x24" python -m benchmarks.kiosk_hour [--minutes 60] [--shot FILE]

The kiosk is built as ``arbor --kiosk`` builds it (assets/kiosk.toml's settings and pace, a fresh saves
folder of its own), and nobody touches it: after ``care_after`` seconds the autopilot cares for the
garden, after ``attract_after`` the attract loop plays, after ``reset_after`` the visitor's tree is saved
and a new sapling planted. Printed: a line a minute (trees alive, status, meters, frames), the sun
height, sun speed and time speed after every attract run next to the kiosk's settings, and at the end
the trees alive, frames (and frames a second), attract runs, runs that left a slider moved, and crashes
(frames the kiosk had to recover from, and any exception that escaped it).
"""

from __future__ import annotations

import argparse
import tempfile
import time
import traceback
from pathlib import Path

from arbor.game.app import WINDOW, open_window
from arbor.game.paths import ASSETS
from arbor.game.signals import StopSignals


def build(saves: Path):
    """A kiosk over a fresh garden in ``saves``, as run_kiosk builds one."""
    import pygame

    from arbor.game.screens.game import Game, GameConfig
    from arbor.game.screens.kiosk import Kiosk, load_kiosk_config

    settings = load_kiosk_config(ASSETS / "kiosk.toml")
    config = GameConfig(saves=saves, resume=True, pace=settings.pace)
    ctx = open_window(WINDOW, "Arbor kiosk hour")
    size = pygame.display.get_surface().get_size()
    kiosk = Kiosk(lambda: Game(ctx, size, config, clock=time.perf_counter), settings, saves,
                  clock=time.perf_counter)
    return ctx, size, kiosk


def expected(kiosk) -> tuple[float, float, float]:
    """The settings every attract run must leave: the sun's slider defaults and the kiosk's speed."""
    sun = kiosk.game.rules.sun
    return sun.orbit_height, sun.speed, kiosk.config.speed


def run(minutes: float, shot: str | None) -> None:
    """Run the kiosk untouched for ``minutes`` of wall time and print what happened (module docstring)."""
    import pygame

    from arbor.game.input.events import InputHub

    saves = Path(tempfile.mkdtemp(prefix="arbor-kiosk-hour-"))
    ctx, size, kiosk = build(saves)
    hub, clock = InputHub(size), pygame.time.Clock()
    want = expected(kiosk)
    print(f"kiosk settings: care after {kiosk.config.care_after:g} s, attract after {kiosk.config.attract_after:g} s,"
          f" reset after {kiosk.config.reset_after:g} s, speed {want[2]:g}x, pace {kiosk.config.pace};"
          f" sun height {want[0]:g}, sun speed {want[1]:g}", flush=True)
    start = last = time.perf_counter()
    frames, escaped, runs_seen, moved, minute = 0, 0, 0, 0, 0
    with StopSignals() as signals:
        while not signals.stop and last - start < minutes * 60:
            now = time.perf_counter()
            try:
                kiosk.frame(kiosk.guarded(hub.poll)(pygame.event.get(), now), now - last, ctx.screen)
            except Exception:
                escaped += 1
                print("ESCAPED:", traceback.format_exc(), flush=True)
            last = now
            frames += 1
            pygame.display.flip()
            clock.tick(60)
            if kiosk.attract_runs != runs_seen and kiosk.attract is not None and kiosk.attract.after_run:
                runs_seen = kiosk.attract_runs
                s = kiosk.attract.after_run
                ok = (s.orbit_height, s.sun_speed, s.speed) == want
                moved += not ok
                print(f"  attract run {runs_seen} at {now - start:6.0f} s: sun height {s.orbit_height:g}, "
                      f"sun speed {s.sun_speed:g}, speed {s.speed:g}x {'(as set)' if ok else '(MOVED)'}", flush=True)
            if now - start >= (minute + 1) * 60:
                minute += 1
                print(f"minute {minute}: {line(kiosk)}, frames {frames}", flush=True)
    elapsed = time.perf_counter() - start
    if shot:  # one more frame, read before it is flipped (after a flip the back buffer holds no frame)
        from arbor.game.app import _save_screen

        kiosk.frame([], 0.0, ctx.screen)
        ctx.finish()
        _save_screen(ctx, size, shot)
    worlds = kiosk.game.garden.worlds
    print(f"after {elapsed / 60:.1f} min: trees alive {sum(w.sim.state.alive for w in worlds)}/{len(worlds)}; "
          f"frames {frames} ({frames / elapsed:.1f} a second); attract runs {kiosk.attract_runs}, "
          f"{moved} left a slider moved; crashes: {kiosk.recoveries} recovered frames, {escaped} escaped; "
          f"visitor trees saved {len(list(saves.glob('visitor-*.arbor')))}", flush=True)
    kiosk.game.quit()
    pygame.quit()


def line(kiosk) -> str:
    """One line about the garden now."""
    parts = []
    for number, world in enumerate(kiosk.game.garden.worlds, 1):
        s = world.sim.state
        parts.append(f"tree {number} {'alive' if s.alive else 'DEAD'} {world.status()} water {s.water_meter:.2f} "
                     f"sun {s.sun_meter:.2f} wilt {s.wilt:.2f} day {int(s.sun_turns) + 1}")
    return "; ".join(parts) + f"; autopilot {'on' if kiosk.game.state.autopilot else 'off'}"


def main() -> None:
    """Parse the arguments and run."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--minutes", type=float, default=60.0, help="wall-clock minutes to run (60)")
    parser.add_argument("--shot", help="PNG of the last frame")
    args = parser.parse_args()
    run(args.minutes, args.shot)


if __name__ == "__main__":
    main()
