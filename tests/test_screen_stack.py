"""The screen stack (game/screens/stack.py, issue 42): push and pop, input taken top first and the rest passed
down, drawing bottom first from the topmost screen that covers; and the real game driven through it (the
menu over the garden takes its keys and passes the others down; the modeler, the family tree, the title
and the kiosk's PIN pad are screens of it)."""

import ast
from pathlib import Path

import pygame
import pytest

from arbor.game.input.events import DOWN, KEY_DOWN, QUIT, UP, WHEEL, InputEvent
from arbor.game.screens.stack import Screen, ScreenStack
from tests.conftest import FakeClock

ROOT = Path(__file__).resolve().parent.parent
SIZE = (1280, 720)


class Layer(Screen):
    """Takes the event kinds in ``takes``, writes down what it saw and drew."""

    def __init__(self, name: str, log: list, takes=(), covers=False) -> None:
        self.name, self.log, self.takes, self.covers = name, log, set(takes), covers

    def handle(self, e):
        self.log.append((self.name, e.kind))
        return None if e.kind in self.takes else e

    def draw(self, target):
        target.append(self.name)

    def key(self):
        return (self.name,)


def event(kind: str) -> InputEvent:
    return InputEvent(kind, 0.0)


def test_push_pop_and_top():
    log = []
    a, b, c = Layer("a", log), Layer("b", log), Layer("c", log)
    stack = ScreenStack(a)
    assert stack.top is a and len(stack) == 1 and a.up and not b.up
    stack.push(b)
    c.stack = stack
    c.open()
    assert [s.name for s in stack] == ["a", "b", "c"] and stack.top is c
    stack.push(a)  # already up: moves to the top, once
    assert [s.name for s in stack] == ["b", "c", "a"]
    assert stack.pop(c) is c and not c.up and stack.pop(c) is None  # from the middle; twice is nothing
    b.close()
    assert stack.pop() is a and stack.top is None and stack.pop() is None
    with pytest.raises(RuntimeError):
        Layer("lost", log).open()  # (a screen opens on the stack it belongs to)


def test_input_goes_top_first_and_what_is_not_taken_passes_down():
    log = []
    garden, menu = Layer("garden", log, takes=(DOWN, KEY_DOWN)), Layer("menu", log, takes=(WHEEL,))
    stack = ScreenStack(garden, menu)
    assert stack.handle(event(WHEEL)) is None and log == [("menu", WHEEL)]  # taken on top: the garden never sees it
    log.clear()
    assert stack.handle(event(DOWN)) is None and log == [("menu", DOWN), ("garden", DOWN)]  # passed down
    log.clear()
    left = stack.handle(event(QUIT))
    assert left is not None and left.kind == QUIT and not stack.handle_input(event(QUIT))  # nobody's: quit
    assert stack.handle_input(event(DOWN))


def test_a_screen_passes_down_what_the_event_became_and_pushes_during_handling_see_nothing():
    log, stack = [], ScreenStack()

    class Opener(Layer):
        def handle(self, e):
            super().handle(e)
            stack.push(Layer("popup", log, takes=(DOWN,)))
            return InputEvent(UP, e.t)  # (what it became for the screens below)

    stack.push(Layer("garden", log))
    stack.push(Opener("opener", log))
    stack.handle(event(DOWN))
    assert log == [("opener", DOWN), ("garden", UP)]  # the new popup did not see the press
    assert stack.top.name == "popup"


def test_a_screen_popped_on_the_way_down_is_skipped():
    log, stack = [], ScreenStack()
    under = Layer("under", log)

    class Closer(Layer):
        def handle(self, e):
            super().handle(e)
            stack.pop(under)
            return e

    stack.push(Layer("garden", log))
    stack.push(under)
    stack.push(Closer("closer", log))
    stack.handle(event(DOWN))
    assert log == [("closer", DOWN), ("garden", DOWN)]


def test_drawing_is_bottom_first_from_the_topmost_screen_that_covers():
    log = []
    stack = ScreenStack(Layer("garden", log), Layer("menu", log))
    drawn = []
    stack.draw(drawn)
    assert drawn == ["garden", "menu"] and not stack.covered()
    stack.push(Layer("title", log, covers=True))
    stack.push(Layer("pad", log))
    drawn = []
    stack.draw(drawn)
    assert drawn == ["title", "pad"] and stack.covered()
    assert [k for _, k in stack.key()] == [("garden",), ("menu",), ("title",), ("pad",)]


def test_holds_lets_a_press_through_a_popup_to_a_control_below():
    class Bar(Layer):
        def holds(self, x, y):
            return x > 100

    assert Bar("bar", []).holds(200, 0) and not Layer("x", []).holds(200, 0)


# ---- the real game, headless ---------------------------------------------------------------------------
@pytest.fixture
def game(gl_ctx, tmp_path):
    from arbor.game.screens.game import Game, GameConfig

    clock = FakeClock()
    g = Game(gl_ctx, SIZE, GameConfig(saves=tmp_path, seed=4, resume=False), clock=clock)
    g.fake_clock = clock
    return g


def press(game, x, y, t=1.0, pointer=1):
    game.handle_input(InputEvent(DOWN, t, "touch:1", pointer, x, y))
    game.handle_input(InputEvent(UP, t + 0.05, "touch:1", pointer, x, y))


def key(game, k):
    return game.handle_input(InputEvent(KEY_DOWN, 1.0, "keyboard", key=k))


def names(game):
    return [type(s).__name__ for s in game.screens]


def test_the_menu_over_the_garden_takes_its_keys_and_passes_the_others_down(game):
    assert names(game) == ["GameInput"]  # the garden alone
    press(game, 600, 200)
    assert names(game) == ["GameInput", "MenuScreen"] and game.menu.visible
    yaw, distance = game.control.yaw, game.control.distance
    key(game, pygame.K_LEFT)  # the camera's keys are the menu's: the view holds still under it
    game.handle_input(InputEvent(WHEEL, 1.0, "mouse", amount=2))
    assert (game.control.yaw, game.control.distance) == (yaw, distance)
    key(game, pygame.K_3)  # the rest go down to the garden
    assert game.loop.speed == 100.0
    speed = game.menu.widget("speed")
    press(game, *speed.rect.center)  # a press on a widget is the menu's
    assert game.loop.speed == 0.0 and game.menu.visible
    press(game, 20, 700)  # a tap outside it closes it, and only that
    assert names(game) == ["GameInput"] and not game.menu.visible
    key(game, pygame.K_LEFT)
    assert game.control.yaw != yaw  # with the menu gone the garden's keys turn the view
    assert not key(game, pygame.K_ESCAPE)  # Esc: a quit left over at the bottom


def test_the_modeler_family_and_title_are_screens_of_the_stack(game):
    from arbor.engine.life.world.actions import Action

    game.act(Action.MODELER, 1.0)
    assert names(game) == ["GameInput", "ModelerScreen"] and game.modeling.active
    press(game, 300, 300)  # in the modeler a tap opens the tools page over it
    assert names(game)[-1] == "MenuScreen" and game.menu.page == "tools"
    done = game.modeling.bar.widgets["modeler"]
    press(game, *done.rect.center)  # the tool bar below takes its press through the open menu: Done
    assert names(game) == ["GameInput"] and not game.modeling.active and not game.menu.visible
    assert not done.pressed  # (let go with the screen, though the finger's release came after)
    game.act(Action.FAMILY, 1.0)
    assert names(game) == ["GameInput", "FamilyScreen"]
    press(game, 5, 5)  # any tap closes it
    assert names(game) == ["GameInput"]
    game.screens.push(game.title)
    press(game, 600, 200)  # the title's press does nothing else
    assert names(game) == ["GameInput"] and not game.menu.visible


def test_a_screen_opens_under_those_of_a_higher_layer():
    log = []
    garden, kiosk, menu, pin = (Layer(n, log) for n in ("garden", "kiosk", "menu", "pin"))
    kiosk.layer, pin.layer = 2, 3
    stack = ScreenStack(garden, kiosk)
    stack.push(menu)  # a visitor's menu opens under the kiosk's own layer
    assert [s.name for s in stack] == ["garden", "menu", "kiosk"]
    stack.push(pin)
    stack.push(menu)  # opened again: still under the kiosk and the pad
    assert [s.name for s in stack] == ["garden", "menu", "kiosk", "pin"]


def test_the_kiosk_pin_pad_is_a_screen_over_the_game(gl_ctx, tmp_path):
    from arbor.game.screens.game import Game, GameConfig
    from arbor.game.screens.kiosk import Kiosk, KioskConfig

    clock = FakeClock(100.0)
    kiosk = Kiosk(lambda: Game(gl_ctx, SIZE, GameConfig(saves=tmp_path, seed=4), clock=clock), KioskConfig(),
                  tmp_path, clock)
    assert names(kiosk.game) == ["GameInput", "KioskScreen"]
    kiosk.handle_input(InputEvent(DOWN, clock.t, "touch:1", 1, 20, 20))
    clock.t += kiosk.config.admin_hold + 0.1
    kiosk.update(0.0)
    assert names(kiosk.game)[-1] == "PinPad" and kiosk.pin_pad is not None
    press(kiosk.game, 600, 200, clock.t, pointer=2)  # the pad takes every press: no menu under it
    assert not kiosk.game.menu.visible
    press(kiosk.game, *kiosk.pin_pad.keys["cancel"].center, clock.t, pointer=2)
    assert kiosk.pin_pad is None and names(kiosk.game) == ["GameInput", "KioskScreen"]
    kiosk.game.tap(600, 200)  # a visitor opens the menu: the kiosk's layer stays over it
    assert kiosk.game.menu.visible and names(kiosk.game)[-1] == "KioskScreen"


def test_input_routing_reads_no_visibility_flags():
    """The screens' input routing asks the stack, not the overlays' flags (`.visible`, `.active`, `.shown`)."""
    routing = ["game_input.py", "menu_screen.py", "modeler_screen.py", "stack.py", "family.py", "title.py"]
    for name in routing:
        tree = ast.parse((ROOT / "game" / "screens" / name).read_text())
        flags = [n.lineno for n in ast.walk(tree)
                 if isinstance(n, ast.Attribute) and n.attr in ("visible", "active", "shown")]
        assert not flags, f"game/screens/{name}:{flags[0]} reads a visibility flag"
