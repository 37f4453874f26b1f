"""Soak: the real game, headless, under random input in every mode (garden, modeler and all its tools)
for a while of real time; memory must stay flat.

Run: python -m benchmarks.soak [MINUTES]   (default 60)
Random taps, drags (corner to corner too), pinches, menu actions (water, sun, speed, plant, next tree,
modeler, crown, shape, prune, symbols, edits, undo/redo, save, load) and leaving and re-entering the
modeler, at up to 100x, at the kiosk's pace (as `arbor --kiosk` plays it). Prints RSS from the first
sample after warm-up to the end, frame counts and recoveries; RSS growth over the second half must
stay under 5 %.
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path
from tempfile import TemporaryDirectory

import numpy as np

SIZE = (960, 540)
ACTIONS = ["water", "orbit_height", "sun_speed", "speed", "plant", "next", "modeler", "crown", "shape", "prune",
           "symbols", "edit", "undo", "redo", "save", "load", "replant"]


def rss_bytes() -> int:
    """Resident memory of this process."""
    with open("/proc/self/statm") as fh:
        return int(fh.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def gesture(rng, t: float) -> list:
    """A tap, a drag (sometimes corner to corner) or a two-finger pinch."""
    from arbor.game.input.events import DOWN, MOVE, UP, InputEvent

    x, y = rng.uniform(0, SIZE[0]), rng.uniform(0, SIZE[1])
    kind = rng.integers(4)
    if kind == 0:
        return [InputEvent(DOWN, t, "touch:1", 0, x, y), InputEvent(UP, t + 0.05, "touch:1", 0, x, y)]
    if kind in (1, 2):
        x2, y2 = (SIZE[0] - x, SIZE[1] - y) if kind == 2 else (x + rng.uniform(-200, 200), y + rng.uniform(-200, 200))
        steps = 40 if kind == 2 else 8
        return ([InputEvent(DOWN, t, "touch:1", 0, x, y)]
                + [InputEvent(MOVE, t + 0.02 * i, "touch:1", 0, x + (x2 - x) * i / steps, y + (y2 - y) * i / steps)
                   for i in range(1, steps + 1)]
                + [InputEvent(UP, t + 0.02 * steps + 0.01, "touch:1", 0, x2, y2)])
    s = rng.uniform(-60, 60)
    return [InputEvent(DOWN, t, "touch:1", 0, x, y), InputEvent(DOWN, t, "touch:1", 1, x + 80, y),
            InputEvent(MOVE, t + 0.05, "touch:1", 0, x - s, y), InputEvent(MOVE, t + 0.05, "touch:1", 1, x + 80 + s, y),
            InputEvent(UP, t + 0.1, "touch:1", 0, x - s, y), InputEvent(UP, t + 0.1, "touch:1", 1, x + 80 + s, y)]


def soak(minutes: float, seed: int = 3) -> float:
    """Run the soak; returns the RSS growth over the second half (a fraction)."""
    import pygame

    from arbor.engine.base.memory import keep_freed_memory
    from arbor.engine.life.world.actions import Action
    from arbor.game.render.renderer import headless_context
    from arbor.game.screens.game import Game, GameConfig
    from arbor.game.screens.kiosk import Kiosk, KioskConfig

    keep_freed_memory()  # as `arbor` does
    pygame.init()
    pygame.display.set_mode((64, 64))
    ctx = headless_context()
    fbo = ctx.framebuffer(color_attachments=[ctx.renderbuffer(SIZE)], depth_attachment=ctx.depth_renderbuffer(SIZE))
    rng = np.random.default_rng(seed)
    with TemporaryDirectory() as saves:
        config = KioskConfig(attract_after=60.0, reset_after=240.0, speed=100.0)
        kiosk = Kiosk(lambda: Game(ctx, SIZE, GameConfig(saves=Path(saves), seed=seed, resume=True,
                                                         autosave_seconds=20.0, pace=config.pace),
                                   clock=time.perf_counter),
                      config, Path(saves), clock=time.perf_counter)
        start, last, frames, samples = time.perf_counter(), time.perf_counter(), 0, []
        printed = start
        while time.perf_counter() - start < minutes * 60:
            now = time.perf_counter()
            events = gesture(rng, now) if rng.random() < 0.3 else []
            if rng.random() < 0.05:
                action = ACTIONS[rng.integers(len(ACTIONS))]
                kiosk.game.act(Action.named(action), float(rng.uniform(0.05, 1.0)))
            kiosk.frame(events, now - last, fbo)
            last, frames = now, frames + 1
            if frames % 200 == 0:
                modules = sum(len(w.tree.lstring) for w in kiosk.game.garden.worlds)
                samples.append((now - start, rss_bytes(), modules))
                if now - printed > 300:  # a line every five minutes
                    printed = now
                    print(f"  {samples[-1][0] / 60:5.1f} min  RSS {samples[-1][1] / 2**20:6.1f} MiB  "
                          f"{len(kiosk.game.garden.worlds)} trees  {modules:,} modules", flush=True)
    half = [(r, m) for t, r, m in samples if t >= minutes * 30]
    growth = (half[-1][0] - half[0][0]) / half[0][0] if len(half) > 1 else 0.0
    print(f"{minutes:g} min, {frames:,} frames, {kiosk.recoveries} recoveries; RSS MiB at half-way "
          f"{half[0][0] / 2**20:.1f}, end {half[-1][0] / 2**20:.1f}, peak {max(s[1] for s in samples) / 2**20:.1f}: "
          f"growth over the second half {100 * growth:+.1f} %; modules in the garden then "
          f"{half[0][1]:,} and {half[-1][1]:,} (trees growing toward their budgets need memory too)")
    return growth


if __name__ == "__main__":
    os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
    os.environ.setdefault("SDL_AUDIODRIVER", "dummy")
    sys.exit(0 if soak(float(sys.argv[1]) if len(sys.argv) > 1 else 60.0) < 0.05 else 1)
