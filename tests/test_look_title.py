"""The title screen (issue 29): Arbor's name over the garden until any key or touch; the press that takes it
down does nothing else; the kiosk's attract loop is the title."""

import numpy as np
import pygame
import pytest

from arbor.game.input.events import DOWN, KEY_DOWN, KEY_UP, QUIT, UP, InputEvent
from arbor.game.screens.game import Game, GameConfig
from arbor.game.screens.kiosk import Kiosk, KioskConfig
from tests.conftest import FakeClock

SIZE = (1280, 720)


def new_game(ctx, folder, clock=None, title=True):
    clock = clock or FakeClock()
    return Game(ctx, SIZE, GameConfig(saves=folder, seed=4, title=title), clock=clock)


def frame(game, fbo) -> np.ndarray:
    game.draw(fbo)
    return np.frombuffer(fbo.read(components=3), np.uint8).reshape(SIZE[1], SIZE[0], 3)[::-1].astype(int)


@pytest.fixture(scope="module")
def fbo(gl_ctx):
    return gl_ctx.framebuffer(color_attachments=[gl_ctx.renderbuffer(SIZE)],
                              depth_attachment=gl_ctx.depth_renderbuffer(SIZE))


def test_the_title_shows_over_the_garden_and_a_tap_takes_it_down_and_nothing_else(gl_ctx, tmp_path, fbo):
    game = new_game(gl_ctx, tmp_path)
    titled = frame(game, fbo)
    scene = new_game(gl_ctx, tmp_path / "b", title=False)
    scene.hud.draw = lambda camera: None  # the garden alone, without the HUD
    plain = frame(scene, fbo)
    band = (slice(SIZE[1] // 4, SIZE[1] * 3 // 5), slice(SIZE[0] // 4, SIZE[0] * 3 // 4))
    bright = (titled[band].min(axis=2) > 235).mean()  # the name's and the lines' pale letters
    assert bright > 0.03 and (plain[band].min(axis=2) > 235).mean() < 0.01
    # the garden behind it: above and below the band the picture is the scene's own, and no meter or hint
    assert np.abs(titled[:100] - plain[:100]).max() <= 2 and np.abs(titled[-100:] - plain[-100:]).max() <= 2
    assert game.handle_input(InputEvent(DOWN, 1.0, "touch:1", 1, 640, 360))
    assert game.handle_input(InputEvent(UP, 1.1, "touch:1", 1, 640, 360))
    assert not game.title.up and not game.menu.visible  # that tap was the title's only
    after = frame(game, fbo)
    assert (after[band].min(axis=2) > 235).mean() < 0.01
    game.handle_input(InputEvent(DOWN, 2.0, "touch:1", 1, 640, 360))
    game.handle_input(InputEvent(UP, 2.1, "touch:1", 1, 640, 360))
    assert game.menu.visible  # the next tap is the game's


def test_any_key_takes_the_title_down_even_escape_and_closing_the_window_still_quits(gl_ctx, tmp_path):
    game = new_game(gl_ctx, tmp_path)
    assert game.handle_input(InputEvent(KEY_DOWN, 1.0, "keyboard", key=pygame.K_ESCAPE))
    assert game.handle_input(InputEvent(KEY_UP, 1.1, "keyboard", key=pygame.K_ESCAPE))
    assert not game.title.up
    other = new_game(gl_ctx, tmp_path / "b")
    assert not other.handle_input(InputEvent(QUIT, 1.0, "window"))


def test_the_kiosks_attract_loop_is_the_title(gl_ctx, tmp_path, fbo):
    clock = FakeClock(50.0)
    folder = tmp_path / "kiosk"
    kiosk = Kiosk(lambda: new_game(gl_ctx, folder, clock, title=False), KioskConfig(attract_after=10.0), folder,
                  clock)
    surface = pygame.Surface(SIZE, pygame.SRCALPHA)
    kiosk.draw_attract(surface)
    assert pygame.mask.from_surface(surface).count() == 0  # a visitor's game: no title
    clock.t += 11.0
    kiosk.update(1 / 60)
    assert kiosk.attract is not None
    kiosk.draw_attract(surface)
    assert pygame.mask.from_surface(surface, 100).count() > 0.1 * SIZE[0] * SIZE[1] / 4  # the band and words
    assert kiosk.title.prompt == "Touch the screen to grow your own tree!"
    kiosk.handle_input(InputEvent(DOWN, clock.t, "touch:1", 1, 640, 360))
    assert kiosk.attract is None
