"""The tap menu as a screen of the game's stack (game/screens/stack.py): up while the menu is shown
(:class:`~arbor.game.render.ui.Menu` tells it when it opens and closes). It takes the presses on its
widgets, the wheel, a 3D mouse's turn and the camera keys (the view holds still under it), and a tap or
Esc, which closes it; a press elsewhere is a gesture that moves nothing (only its tap counts), except on a
control of a screen below (the modeler's tool bar), which gets the press."""

from __future__ import annotations

from dataclasses import replace

import pygame

from arbor.game.input.events import DOWN, KEY_DOWN, MOVE, ROTATE, UP, WHEEL, InputEvent
from arbor.game.input.gestures import Gestures
from arbor.game.render.ui import Menu
from arbor.game.screens.care import CareActions
from arbor.game.screens.game_input import CAMERA_KEYS, pointer_id
from arbor.game.screens.stack import TAP, Canvas, Screen, ScreenStack


class MenuScreen(Screen):
    """The menu on the stack (see module docstring)."""

    def __init__(self, menu: Menu, screens: ScreenStack, *, gestures: Gestures, care: CareActions,
                 font: pygame.font.Font) -> None:
        self.menu, self.stack, self.gestures, self.care, self.font = menu, screens, gestures, care, font
        self.pointers: set[int] = set()  # pointers pressing the menu's widgets
        menu.on_toggle = self._toggled

    def _toggled(self, shown: bool) -> None:
        """The menu opened or closed: so does this screen (and the gestures under it move nothing)."""
        if shown:
            self.open()
        else:
            self.close()
            self.pointers.clear()
        self.gestures.menu_open = shown

    def _act(self, actions: list) -> None:
        for action in actions:
            self.care.act(*action)

    def handle(self, e: InputEvent) -> InputEvent | None:
        """See module docstring."""
        if e.kind in (WHEEL, ROTATE) or (e.kind == KEY_DOWN and e.key in CAMERA_KEYS):
            return None
        if e.kind == TAP or (e.kind == KEY_DOWN and e.key == pygame.K_ESCAPE):  # (Esc closes it, nothing more)
            self._act(self.menu.hide())
            return None
        if e.kind not in (DOWN, MOVE, UP) or e.dims != 2:
            return e
        if e.device == "mouse" and e.button == 3:  # a right-button tilt ends under the menu
            return replace(e, kind=UP) if e.kind == MOVE else e
        if e.button != 1:
            return e
        pid, x, y = pointer_id(e), e.x, e.y
        if e.kind == DOWN:
            self.pointers.discard(pid)
            if self.menu.hit(x, y):
                self.pointers.add(pid)
                self._act(self.menu.press(x, y))
                return None
            if any(screen.holds(x, y) for screen in self.stack.below(self)):
                return e
            self.gestures.down(pid, x, y, e.t)  # (it moves nothing while the menu is open: its tap closes it)
            return None
        if pid not in self.pointers:
            return e
        if e.kind == MOVE:
            self._act(self.menu.drag(x, y))
        else:
            self.pointers.discard(pid)
            self._act(self.menu.release())
        return None

    def draw(self, canvas: Canvas) -> None:
        """The menu's panel and the widgets of its page."""
        self.menu.draw(canvas.surface, self.font)

    def key(self) -> tuple:
        """The page and each widget's value, pressed state and label."""
        return self.menu.page, tuple((w.value, w.pressed, w.label) for w in self.menu.widgets)
