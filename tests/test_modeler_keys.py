"""The modeler's keys and toasts through the real game, headless (issue 48): Esc leaves the modeler and the
next Esc asks before quitting; Ctrl+Z / Ctrl+Y undo and redo; toasts say what changed, in the singular
when it is one, and stay 3 s; the view does not re-frame while a tool is in use (F frames it)."""

import numpy as np
import pygame
import pytest

from arbor.game.tools.told import counted
from tests.test_modeler_tools import base_pixel, draw, press_bar, press_menu


@pytest.fixture
def game(modeler_game):
    return modeler_game(seed=3)


def key(game, k, up=False):
    """A real key event through the game's translator and its screen stack; False: the window would end."""
    kind = pygame.KEYUP if up else pygame.KEYDOWN
    return game.handle_event(pygame.event.Event(kind, key=k, mod=0, scancode=0, unicode=""))


def ctrl(game, k, shift=False):
    key(game, pygame.K_LCTRL)
    if shift:
        key(game, pygame.K_LSHIFT)
    key(game, k)
    key(game, k, up=True)
    if shift:
        key(game, pygame.K_LSHIFT, up=True)
    key(game, pygame.K_LCTRL, up=True)


def trunk(game):
    x0, y0 = base_pixel(game)
    draw(game, [(x0 + 2 * np.sin(i / 5), y0 - 9 * i) for i in range(30)])


def test_esc_leaves_the_modeler_and_the_next_esc_asks_before_quitting(game):
    press_menu(game, "modeler")
    assert game.modeling.active
    game.tap(500, 300)  # the menu's tools page, over the modeler
    assert game.menu.visible
    assert key(game, pygame.K_ESCAPE) is not False and not game.menu.visible and game.modeling.active  # closes it
    assert key(game, pygame.K_ESCAPE) is not False and not game.modeling.active  # back in the garden
    assert "Esc again" in game.hud_info().message
    assert key(game, pygame.K_ESCAPE) is not False  # asks ...
    assert "Quit Arbor?" in game.hud_info().message
    assert key(game, pygame.K_ESCAPE) is False  # ... and the next one quits


def test_ctrl_z_and_ctrl_y_undo_and_redo_and_say_what_changed(game):
    press_menu(game, "modeler")
    empty = game.world.tree.lstring
    trunk(game)
    drawn = game.world.tree.lstring
    assert drawn is not empty
    game.clock_box[0] += 10.0
    ctrl(game, pygame.K_z)
    message = game.hud_info().message
    assert game.world.tree.lstring.to_text() == empty.to_text()
    assert message.startswith("Undone: ") and "branch pieces" in message and "taken away" in message, message
    game.clock_box[0] += 2.9
    assert game.hud_info().message == message  # still shown after 2.9 s ...
    game.clock_box[0] += 0.2
    assert game.hud_info().message != message  # ... gone after 3 s
    ctrl(game, pygame.K_y)
    assert game.world.tree.lstring.to_text() == drawn.to_text()
    assert game.hud_info().message.startswith("Redone: ") and "put back" in game.hud_info().message
    ctrl(game, pygame.K_z)
    ctrl(game, pygame.K_z, shift=True)  # Ctrl+Shift+Z redoes too
    assert game.world.tree.lstring.to_text() == drawn.to_text()
    replanted = game.world.tree.lstring
    key(game, pygame.K_LCTRL)
    key(game, pygame.K_r)  # a Ctrl combination never reaches the garden's one-letter keys (R: new sapling)
    key(game, pygame.K_LCTRL, up=True)
    assert game.world.tree.lstring is replanted and game.modeling.active


def test_counts_are_said_in_the_singular_when_one():
    assert counted(1, "growth point") == "1 growth point" and counted(2, "growth point") == "2 growth points"
    assert counted(1, "leaf") == "1 leaf" and counted(3, "leaf") == "3 leaves" and counted(0, "lobe") == "0 lobes"


def test_the_view_stays_while_a_tool_is_in_use_and_f_frames_it(game):
    press_menu(game, "modeler")
    trunk(game)
    press_bar(game, "crown")
    view = (game.camera().eye.copy(), game.camera().target.copy())
    x0, y0 = base_pixel(game)
    a = np.linspace(0, 2 * np.pi, 48)
    draw(game, [(x0 + 250 + 200 * np.cos(t), y0 - 330 + 150 * np.sin(t)) for t in a])  # a lobe past the view
    assert len(game.modeling.crown_tool.state().lobes) == 1
    game.clock_box[0] += 5.0
    after = game.camera()
    assert np.allclose(after.eye, view[0]) and np.allclose(after.target, view[1])  # no re-framing
    key(game, pygame.K_f)
    framed = game.camera()
    assert not np.allclose(framed.eye, view[0]) and "frames" in game.hud_info().message
    lobe = game.modeling.crown_tool.state().lobes[0].vertices
    pixels = np.array(game.hud.project_many(framed, lobe))
    assert len(pixels) == len(lobe) and (pixels[:, 0] < game.modeling.bar.rect.left).all()  # the lobe in view


def test_the_can_let_go_with_ctrl_held_stops_pouring(game):
    """W down, Ctrl down, W up, Ctrl up in the modeler: the garden hears W go up and the can stops."""
    press_menu(game, "modeler")
    key(game, pygame.K_w)
    assert game.world.sim.state.watering
    key(game, pygame.K_LCTRL)
    key(game, pygame.K_w, up=True)
    key(game, pygame.K_LCTRL, up=True)
    assert not game.world.sim.state.watering


def test_a_stroke_cut_off_by_leaving_the_modeler_leaves_no_finger_down(game):
    """Leaving the modeler in the middle of a stroke (the attract loop, a lost focus): the next time a
    finger draws, it draws."""
    from arbor.game.input.events import DOWN, MOVE
    from tests.test_modeler_tools import touch

    press_menu(game, "modeler")
    x0, y0 = base_pixel(game)
    touch(game, DOWN, 0, x0, y0)
    touch(game, MOVE, 0, x0, y0 - 40)
    game.modeling.toggle()  # left with the finger still down
    press_menu(game, "modeler")
    before = game.world.tree.lstring
    trunk(game)
    assert game.world.tree.lstring is not before
