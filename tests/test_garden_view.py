"""Issue 28: a garden's markers never overlap, and the zoom goes out far enough to frame the whole garden."""

import itertools

import numpy as np
import pytest

from arbor.engine.life.world.actions import Action
from arbor.game.render.camera import project_points
from arbor.game.screens.game import Game, GameConfig
from tests.conftest import FakeClock

SIZE = (1280, 720)


@pytest.fixture(scope="module")
def garden_game(gl_ctx, tmp_path_factory):
    """A game with a garden of six trees, each grown a little."""
    game = Game(gl_ctx, SIZE, GameConfig(saves=tmp_path_factory.mktemp("garden"), seed=6, resume=False, pace="demo"),
                clock=FakeClock())
    game.coach.hints = []
    for _ in range(5):
        game.act(Action.PLANT, 1.0)
    game.state.autopilot = True  # (tended while it grows)
    game.set_speed(10.0)
    for _ in range(40):
        game.update(0.25)
    game.fbo = gl_ctx.framebuffer(color_attachments=[gl_ctx.renderbuffer(SIZE)],
                                  depth_attachment=gl_ctx.depth_renderbuffer(SIZE))
    return game


def corners(lo, hi):
    return np.array(list(itertools.product(*zip(lo, hi, strict=True))), float)


def test_at_the_farthest_zoom_the_whole_garden_is_in_view(garden_game):
    game = garden_game
    game.draw(game.fbo)  # (every tree's view built)
    assert len(game.garden.worlds) == 6
    here = np.array(game.world.position)
    control = game.control
    for yaw in (0.0, 50.0, 135.0, 230.0, 300.0):
        control.yaw, control.distance = yaw, control.max_distance
        camera = game.camera()
        for world in game.garden.worlds:
            view = game.view.views[id(world)][1]
            dx, dz = np.array(world.position) - here
            pixels = project_points(camera, SIZE, corners(view.lo, view.hi) + np.array([dx, 0.0, dz]))
            assert np.isfinite(pixels).all()
            assert (pixels >= 0).all() and (pixels[:, 0] <= SIZE[0]).all() and (pixels[:, 1] <= SIZE[1]).all(), yaw
    control.distance = 1.0
    near = game.camera().distance
    control.distance = 3.0
    assert game.camera().distance > near  # (zooming out between goes on growing the distance)


def test_garden_markers_never_overlap(garden_game):
    game = garden_game
    control = game.control
    overlaps, shown = [], 0
    for yaw, zoom in itertools.product((0.0, 40.0, 90.0, 160.0, 250.0, 320.0), (1.0, 2.5, control.max_distance)):
        control.yaw, control.distance = yaw, zoom
        game.hud.paint(game.camera())
        boxes = game.hud.marker_boxes
        shown += len(boxes)
        overlaps += [(yaw, zoom) for a, b in itertools.combinations(boxes, 2) if a.colliderect(b)]
        if zoom == control.max_distance:
            assert len(boxes) == 6  # (every tree is in view, and marked)
    assert shown >= 6 * 6 and not overlaps
