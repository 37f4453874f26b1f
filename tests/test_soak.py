"""Soak: one simulated hour of random touches on the kiosk at 100x; memory stays flat, nothing breaks."""

import os

import numpy as np
import pytest

from arbor.game.input.events import DOWN, MOVE, UP, InputEvent
from arbor.game.screens.game import Game, GameConfig
from arbor.game.screens.kiosk import Kiosk, KioskConfig

SIZE = (960, 540)
FRAME = 1 / 20  # real seconds per frame: 100x turns one simulated hour into 720 frames


def rss_bytes() -> int:
    with open("/proc/self/statm") as fh:
        return int(fh.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def random_gesture(rng, t):
    """A tap, a drag or a two-finger pinch somewhere on the screen."""
    kind = rng.integers(3)
    x, y = rng.uniform(0, SIZE[0]), rng.uniform(0, SIZE[1])
    if kind == 0:
        return [InputEvent(DOWN, t, "touch:1", 0, x, y), InputEvent(UP, t + 0.05, "touch:1", 0, x, y)]
    if kind == 1:
        dx, dy = rng.uniform(-200, 200, 2)
        return ([InputEvent(DOWN, t, "touch:1", 0, x, y)]
                + [InputEvent(MOVE, t + 0.02 * i, "touch:1", 0, x + dx * i / 8, y + dy * i / 8) for i in range(1, 9)]
                + [InputEvent(UP, t + 0.2, "touch:1", 0, x + dx, y + dy)])
    s = rng.uniform(-60, 60)
    return [InputEvent(DOWN, t, "touch:1", 0, x, y), InputEvent(DOWN, t, "touch:1", 1, x + 80, y),
            InputEvent(MOVE, t + 0.05, "touch:1", 0, x - s, y), InputEvent(MOVE, t + 0.05, "touch:1", 1, x + 80 + s, y),
            InputEvent(UP, t + 0.1, "touch:1", 0, x - s, y), InputEvent(UP, t + 0.1, "touch:1", 1, x + 80 + s, y)]


@pytest.mark.skipif(not os.path.exists("/proc/self/statm"), reason="reads RSS from /proc")
def test_one_simulated_hour_of_random_touches(gl_ctx, tmp_path):
    clock = [0.0]
    config = KioskConfig(attract_after=120.0, reset_after=600.0, speed=100.0)
    kiosk = Kiosk(lambda: Game(gl_ctx, SIZE, GameConfig(saves=tmp_path, seed=9, resume=False, autosave_seconds=5.0),
                               clock=lambda: clock[0]), config, tmp_path, clock=lambda: clock[0])
    fbo = gl_ctx.framebuffer(color_attachments=[gl_ctx.renderbuffer(SIZE)],
                             depth_attachment=gl_ctx.depth_renderbuffer(SIZE))
    rng = np.random.default_rng(4)
    frames = int(3600 / 100 / FRAME)
    rss = []
    for f in range(frames):
        clock[0] += FRAME
        events = random_gesture(rng, clock[0]) if rng.random() < 0.3 and f % 150 < 120 else []  # idle spells too
        kiosk.game.loop.speed = 100.0
        assert kiosk.frame(events, FRAME, fbo)
        if f % 60 == 0:
            rss.append(rss_bytes())
    assert kiosk.recoveries == 0  # no frame raised
    simulated = kiosk.game.loop.steps * kiosk.game.loop.dt  # (replants restart the tree, not the clock)
    assert simulated == pytest.approx(3600.0, rel=0.01)
    warm = np.median(rss[len(rss) // 2 - 1 : len(rss) // 2 + 2])  # half-way: the tree, caches and GL buffers exist
    print(f"RSS MiB: warm {warm / 2**20:.1f}, end {rss[-1] / 2**20:.1f}, peak {max(rss) / 2**20:.1f}")
    assert rss[-1] < warm * 1.05, [round(r / 2**20) for r in rss]
