"""Frame brightness across days of the sun at fast game speeds: does the screen strobe?

Run: python -m benchmarks.daylight
The real game (demo pace, a grown sapling) is played at 10x and 100x for two days of the sun at 30
frames a second (640 x 360, headless EGL). For each speed: the darkest and brightest frame (mean of
all pixels, 0..255) and the largest change from one frame to the next, with the smoothed scene sun
(what the game does) and with the raw sun (what it did before).
"""

from __future__ import annotations

import math
import os
import tempfile
from pathlib import Path

import numpy as np

FPS = 30.0
SIZE = (640, 360)


def brightness(ctx, speed: float, smooth: bool) -> np.ndarray:
    """Mean frame brightness, frame by frame, over two days of the sun at ``speed``."""
    from arbor.game.screens.game import Game, GameConfig

    fbo = ctx.framebuffer(color_attachments=[ctx.renderbuffer(SIZE)], depth_attachment=ctx.depth_renderbuffer(SIZE))
    clock = [0.0]
    with tempfile.TemporaryDirectory() as saves:
        game = Game(ctx, SIZE, GameConfig(saves=Path(saves), seed=5, resume=False, pace="demo"),
                    clock=lambda: clock[0])
        game.coach.hints = []
        if not smooth:
            game.view.scene_sun = game.world.sim.sun_direction
        game.set_speed(speed)
        day = 2 * math.pi / game.world.sim.state.sun_speed / speed  # real seconds
        out = []
        for _ in range(int(2 * day * FPS)):
            clock[0] += 1 / FPS
            game.update(1 / FPS)
            game.world.sim.state.water_meter = 0.8  # (a cared-for tree: it must not wilt meanwhile)
            game.draw(fbo)
            out.append(np.frombuffer(fbo.read(components=3), np.uint8).mean())
    return np.array(out)


def main() -> None:
    """Print the table."""
    os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
    import pygame

    from arbor.game.render.renderer import headless_context

    pygame.init()
    ctx = headless_context()  # (one context for every run)
    print(f"{'speed':>6} {'sun':>9} {'frames':>7} {'darkest':>8} {'brightest':>10} {'max change/frame':>17}")
    for speed in (10.0, 100.0):
        for smooth in (True, False):
            b = brightness(ctx, speed, smooth)
            print(f"{speed:5g}x {'smoothed' if smooth else 'raw':>9} {len(b):7d} {b.min():8.1f} {b.max():10.1f} "
                  f"{np.abs(np.diff(b)).max():17.2f}", flush=True)


if __name__ == "__main__":
    main()
