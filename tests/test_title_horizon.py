"""No fog band on the title's horizon (issue 47, looks): the ground fades only part of the way into the
sky's pale horizon (aerial haze) and the dome below the horizon is that far ground, so between the sky
and the grass there is a sharp line, not a band of rows that are neither (grey-white fog)."""

from pathlib import Path

import numpy as np

SIZE = (1280, 720)


def kinds_of_rows(shot: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per row (averaged away from the middle, where the tree and the title are): sky (blue over green)
    and ground (green over red and blue)."""
    side = np.concatenate([shot[:, 20:400], shot[:, -340:-20]], axis=1).mean(axis=1)
    r, g, b = side.T
    return b > g + 12, (g > r + 20) & (g > b + 15)


def test_the_title_has_a_sharp_horizon_not_a_fog_band(gl_ctx, tmp_path):
    from arbor.game.screens.game import Game, GameConfig
    from benchmarks.shots import _grow, summer_day

    clock = [1000.0]
    game = Game(gl_ctx, SIZE, GameConfig(saves=Path(tmp_path), seed=3, resume=False, title=True),
                clock=lambda: clock[0])
    game.garden.worlds[0] = world = _grow(summer_day(), 3)
    world.sim.state.sun_angle = 1.1  # (by day)
    game.state.remember()
    fbo = gl_ctx.framebuffer(color_attachments=[gl_ctx.renderbuffer(SIZE)],
                             depth_attachment=gl_ctx.depth_renderbuffer(SIZE))
    game.draw(fbo)
    shot = np.frombuffer(fbo.read(components=3), np.uint8).reshape(SIZE[1], SIZE[0], 3)[::-1].astype(float)
    sky, ground = kinds_of_rows(shot)
    rows = slice(SIZE[1] // 4, SIZE[1] * 3 // 4)  # (below the clouds, above the title's lines)
    assert sky[rows].any() and ground[rows].any()  # (the horizon is in these rows)
    fog = ~sky[rows] & ~ground[rows]
    assert fog.sum() <= 4, np.flatnonzero(fog) + rows.start  # (measured 2; the fog band was 25 rows)
