"""The title screen (issue 29): Arbor's name over the garden until any key or touch; the press that takes it
down does nothing else; the kiosk's attract loop is the title."""

import numpy as np
import pygame
import pytest

from arbor.game.input.events import DOWN, KEY_DOWN, KEY_UP, QUIT, UP, InputEvent
from arbor.game.screens.game import Game, GameConfig
from arbor.game.screens.kiosk import Kiosk, KioskConfig
from arbor.game.screens.stack import Canvas
from arbor.game.screens.title import place
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


def _word_rows(titled, plain):
    """Rows where the title's pale letters are (and the garden alone has none)."""
    pale = lambda picture: (picture.min(axis=2) > 235).mean(axis=1) > 0.01  # noqa: E731
    return np.flatnonzero(pale(titled) & ~pale(plain))


def test_the_title_shows_over_the_garden_and_a_tap_takes_it_down_and_nothing_else(gl_ctx, tmp_path, fbo):
    game = new_game(gl_ctx, tmp_path)
    titled = frame(game, fbo)
    scene = new_game(gl_ctx, tmp_path / "b", title=False)
    scene.hud.draw = lambda camera: None  # the garden alone, without the HUD
    plain = frame(scene, fbo)
    words = _word_rows(titled, plain)
    assert len(words) > 40, len(words)
    # clear of the tree (issue 47): the words stand beside the rows the sapling covers, not across them
    camera = game.camera()
    tree = game.title.clear_of(Canvas(None, camera, lambda points: game.hud.project_many(camera, points)))
    assert tree is not None and (words.max() < tree[0] or words.min() > tree[1]), (words.min(), words.max(), tree)
    # the garden behind it: away from the band the picture is the scene's own, and no meter or hint
    far = np.ones(SIZE[1], bool)
    far[max(words.min() - SIZE[1] // 5, 0): words.max() + SIZE[1] // 5] = False
    assert far.sum() > 100 and np.abs(titled[far] - plain[far]).max() <= 2
    assert game.handle_input(InputEvent(DOWN, 1.0, "touch:1", 1, 640, 360))
    assert game.handle_input(InputEvent(UP, 1.1, "touch:1", 1, 640, 360))
    assert not game.title.up and not game.menu.visible  # that tap was the title's only
    after = frame(game, fbo)
    block = (slice(words.min(), words.max() + 1), slice(SIZE[0] // 4, SIZE[0] * 3 // 4))  # where the words were
    pale = lambda picture: (picture[block].min(axis=2) > 235).mean()  # noqa: E731
    assert pale(titled) > 0.03 and pale(after) < pale(titled) / 3, (pale(titled), pale(after))  # (the HUD's lines)
    game.handle_input(InputEvent(DOWN, 2.0, "touch:1", 1, 640, 360))
    game.handle_input(InputEvent(UP, 2.1, "touch:1", 1, 640, 360))
    assert game.menu.visible  # the next tap is the game's


def test_the_title_stands_where_the_crown_is_not():
    """Over the sky while the tree stays below it, over the ground when the crown reaches up into the sky."""
    assert place(720, 200, None) < 360  # (nothing to keep clear of: the sky)
    assert place(720, 200, (420.0, 620.0)) < 200  # a sapling: the words over the sky
    assert place(720, 200, (40.0, 600.0)) > 360  # a tall crown: the words over the ground, below most of it


def test_any_key_takes_the_title_down_even_escape_and_closing_the_window_still_quits(gl_ctx, tmp_path, fbo):
    game = new_game(gl_ctx, tmp_path)
    frame(game, fbo)  # (the title is seen)
    assert game.handle_input(InputEvent(KEY_DOWN, 1.0, "keyboard", key=pygame.K_ESCAPE))
    assert game.handle_input(InputEvent(KEY_UP, 1.1, "keyboard", key=pygame.K_ESCAPE))
    assert not game.title.up
    other = new_game(gl_ctx, tmp_path / "b")
    assert not other.handle_input(InputEvent(QUIT, 1.0, "window"))


def test_a_key_pressed_while_the_garden_was_planted_is_kept(gl_ctx, tmp_path, fbo):
    """Issue 47: a key pressed while "planting the garden..." showed (it comes with the first frame, before
    the title was ever drawn) takes the title down and does what it does: 3 is 100x. Once the title was
    seen, the key that takes it down does nothing else."""
    game = new_game(gl_ctx, tmp_path)
    game.handle_input(InputEvent(KEY_DOWN, 1.0, "keyboard", key=pygame.K_3))
    game.handle_input(InputEvent(KEY_UP, 1.1, "keyboard", key=pygame.K_3))
    assert not game.title.up and game.loop.speed == 100.0
    seen = new_game(gl_ctx, tmp_path / "b")
    frame(seen, fbo)
    seen.handle_input(InputEvent(KEY_DOWN, 1.0, "keyboard", key=pygame.K_3))
    seen.handle_input(InputEvent(KEY_UP, 1.1, "keyboard", key=pygame.K_3))
    assert not seen.title.up and seen.loop.speed == 1.0


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
