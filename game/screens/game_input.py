"""The game's input routing: which gesture, stroke, menu press or key a device event becomes (the
menu's presses and the keys become :class:`~arbor.engine.life.world.actions.Action` values)."""

from __future__ import annotations

from collections.abc import Callable

import pygame

from arbor.engine.life.world.actions import Action
from arbor.game.input.events import (
    DEVICE,
    DOWN,
    FOCUS_LOST,
    KEY_DOWN,
    KEY_UP,
    MOVE,
    QUIT,
    ROTATE,
    UP,
    WHEEL,
    InputEvent,
)
from arbor.game.input.gestures import Gestures
from arbor.game.loop import SPEEDS
from arbor.game.render.camera import OrbitCamera
from arbor.game.render.ui import Menu
from arbor.game.screens.care import CareActions
from arbor.game.screens.coach import Coach
from arbor.game.screens.family import FamilyScreen
from arbor.game.screens.modeler import ModelingMode
from arbor.game.screens.picking import Picker
from arbor.game.screens.state import GameState
from arbor.game.strings import text

KEY_YAW, KEY_TILT = 4.0, 3.0  # degrees per key press
TAP_SECONDS, TAP_PIXELS = 0.3, 12
DRAWN_POINTS = 10  # pointer moves after which a stroke a second finger turns into a gesture is said to be let go


class GameInput:
    """Routes device-independent input events to the camera, the menu, the modeler and the actions."""

    def __init__(self, state: GameState, size: tuple[int, int], camera: Callable[[], OrbitCamera], *, menu: Menu,
                 gestures: Gestures, modeling: ModelingMode, care: CareActions, picker: Picker,
                 family: FamilyScreen, coach: Coach) -> None:
        self.state, self.size, self.camera = state, size, camera
        self.menu, self.gestures, self.modeling, self.care = menu, gestures, modeling, care
        self.picker, self.family, self.coach = picker, family, coach
        self.menu_pointers: set[int] = set()
        self.bar_pointers: set[int] = set()  # pointers pressing the modeler's tool bar
        self.right_y: float | None = None
        self.stroke_pointer: int | None = None
        self.stroke_start: tuple[float, float, float] = (0.0, 0.0, 0.0)
        self.keys_water = False

    def handle(self, e: InputEvent) -> bool:
        """Handle one event; returns False when the game should quit."""
        state = self.state
        if e.device not in state.devices and e.device not in ("window", "hid") and e.amount >= 0:
            state.devices[e.device] = e.device.split(":")[0]
        if e.kind == QUIT:
            return False
        if e.kind in (DOWN, MOVE, UP):
            if e.dims == 3:
                self._pointer3d(e)
            elif e.device == "mouse" and e.button == 3:
                self._right_drag(e)
            elif e.button == 1:
                self._pointer(e.kind, hash((e.device, e.pointer)) & 0x7FFFFFFF, e.x, e.y, e.t)
        elif e.kind == WHEEL and not self.menu.visible:
            state.control.zoom(0.9**e.amount)
        elif e.kind == ROTATE and not self.menu.visible:
            state.control.turn(-e.ry)
            state.control.tilt_by(e.rx)
        elif e.kind in (KEY_DOWN, KEY_UP):
            return self._key(e.key, e.kind == KEY_DOWN)
        elif e.kind == FOCUS_LOST:
            self.gestures.cancel_all()
        elif e.kind == DEVICE:
            if e.amount < 0:
                state.devices.pop(e.device, None)
            state.say(e.text, 5)
        return True

    def _right_drag(self, e: InputEvent) -> None:
        """The mouse's tilt gesture: vertical right-button drag."""
        if e.kind == DOWN:
            self.right_y = e.y
        elif e.kind == MOVE and not self.menu.visible and self.right_y is not None:
            self.state.control.tilt_by((e.y - self.right_y) * 0.25)
            self.right_y = e.y
        else:
            self.right_y = None

    def _pointer3d(self, e: InputEvent) -> None:
        """A 3D tracker's cursor (shown by the HUD); in the modeler, its button draws strokes in 3D."""
        modeling = self.modeling
        self.state.cursor3d = (e.x, e.y, e.z)
        if not modeling.active:
            return
        if e.kind == DOWN:
            modeling.cancel_points()
            self.stroke_pointer = -3
        if self.stroke_pointer == -3:
            modeling.add3d(self.state.cursor3d, e.t)
            if e.kind == UP:
                modeling.finish()
                self.stroke_pointer = None

    def _stroke(self, kind: str, pid: int, x: float, y: float, now: float) -> bool:
        """Modeler: one pointer draws; a second pointer turns the stroke into a camera gesture."""
        if not self.modeling.active or self.menu.visible:
            return False
        if kind == DOWN and self.stroke_pointer is None and not self.gestures.pointers:
            if self.menu.hit(x, y) or self.modeling.bar.over(x, y):
                return False
            self.stroke_pointer, self.stroke_start = pid, (x, y, now)
            self.modeling.begin2d(x, y, now, self.camera())
            return True
        if kind == DOWN and self.stroke_pointer is not None:  # second finger: it was a camera gesture
            sx, sy, st = self.stroke_start
            if len(self.modeling.points) >= DRAWN_POINTS:  # a stroke well under way is not lost in silence
                self.state.say(text("messages.stroke_dropped"))
            self.modeling.cancel_points()
            self.gestures.down(self.stroke_pointer, sx, sy, st)
            self.stroke_pointer = None
            return False
        if pid != self.stroke_pointer:
            return False
        if kind == MOVE:
            self.modeling.add2d(x, y, now, self.camera())
        elif kind == UP:
            self._stroke_up(x, y, now)
        return True

    def _stroke_up(self, x: float, y: float, now: float) -> None:
        sx, sy, st = self.stroke_start
        self.stroke_pointer = None
        if now - st < TAP_SECONDS and abs(x - sx) + abs(y - sy) < TAP_PIXELS:  # a tap: a cut, or the menu
            self.modeling.cancel_points()
            camera = self.camera()
            if not (self.modeling.prune_at(x, y, camera) or self.modeling.edit_at(x, y, camera)):
                self.tap(x, y)
        else:
            self.modeling.finish()

    def _pointer(self, kind: str, pid: int, x: float, y: float, now: float) -> None:
        if self._stroke(kind, pid, x, y, now):
            return
        if kind == DOWN:
            if self.menu.hit(x, y):
                self.menu_pointers.add(pid)
                for action in self.menu.press(x, y):
                    self.care.act(*action)
            elif self.modeling.bar.over(x, y):  # the modeler's tool bar (a press there closes the menu)
                self.bar_pointers.add(pid)
                for action in [*self.menu.hide(), *self.modeling.bar.press(x, y)]:
                    self.care.act(*action)
                self.gestures.menu_open = False
            else:
                self.gestures.menu_open = self.menu.visible
                self.gestures.down(pid, x, y, now)
        elif pid in self.bar_pointers:
            if kind == UP:
                self.bar_pointers.discard(pid)
                self.modeling.bar.release()
        elif kind == MOVE:
            if pid in self.menu_pointers:
                for action in self.menu.drag(x, y):
                    self.care.act(*action)
            else:
                self.gestures.move(pid, x, y, now)
        elif pid in self.menu_pointers:
            self.menu_pointers.discard(pid)
            for action in self.menu.release():
                self.care.act(*action)
        elif self.gestures.up(pid, x, y, now):
            self.tap(x, y)

    def tap(self, x: float, y: float) -> None:
        """A tap outside the menu: close the menu if it is open; else pick the ripe fruit or choose the
        tree that was tapped, or open the menu there (the modeler's tools page in the modeler)."""
        if self.family.visible:
            index = self.family.tap(x, y)
            if index is not None:
                self.care.care_for(index)
        elif self.menu.visible:
            for action in self.menu.hide():
                self.care.act(*action)
        elif self.modeling.active or not self.picker.tap(x, y, self.camera()):
            self.care.sync_sliders()
            self.menu.show_at(x, y, "tools" if self.modeling.active else None)
        self.gestures.menu_open = self.menu.visible

    def _key(self, key: int, down: bool) -> bool:
        if key == pygame.K_w:
            if down != self.keys_water:
                self.keys_water = down
                self.care.act(Action.WATER, float(down))
            return True
        if not down:
            return True
        if key == pygame.K_ESCAPE:
            return False
        if not self.menu.visible:
            self._camera_key(key)
        if key == pygame.K_m:
            self.tap(self.size[0] * 0.6, self.size[1] * 0.2)
        elif key == pygame.K_r:
            self.care.act(Action.REPLANT, 1.0)
        elif key == pygame.K_g:
            self.care.act(Action.GO_ON, 1.0)
        elif key == pygame.K_p:
            self.care.set_speed(0.0 if self.state.loop.speed else 1.0)
        elif key in (pygame.K_1, pygame.K_2, pygame.K_3):
            self.care.set_speed(SPEEDS[key - pygame.K_1 + 1])
        elif key == pygame.K_F5:
            self.care.act(Action.SAVE, 1.0)
        elif key == pygame.K_F9:
            self.care.act(Action.LOAD, 1.0)
        return True

    def _camera_key(self, key: int) -> None:
        """Arrows turn and tilt, +/- zoom."""
        control = self.state.control
        turns = {pygame.K_LEFT: (KEY_YAW, 0), pygame.K_RIGHT: (-KEY_YAW, 0),
                 pygame.K_UP: (0, KEY_TILT), pygame.K_DOWN: (0, -KEY_TILT)}
        if key in turns:
            control.turn(turns[key][0])
            control.tilt_by(turns[key][1])
        elif key in (pygame.K_PLUS, pygame.K_EQUALS, pygame.K_KP_PLUS):
            control.zoom(0.9)
        elif key in (pygame.K_MINUS, pygame.K_KP_MINUS):
            control.zoom(1 / 0.9)
