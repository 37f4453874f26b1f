"""The game's input routing: which gesture, stroke, menu press or key a device event becomes."""

from __future__ import annotations

from typing import TYPE_CHECKING

import pygame

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
from arbor.game.loop import SPEEDS

if TYPE_CHECKING:
    from arbor.game.screens.game import Game

KEY_YAW, KEY_TILT = 4.0, 3.0  # degrees per key press
TAP_SECONDS, TAP_PIXELS = 0.3, 12


class GameInput:
    """Routes device-independent input events to the camera, the menu, the modeler and the actions."""

    def __init__(self, game: Game) -> None:
        self.game = game
        self.menu_pointers: set[int] = set()
        self.right_y: float | None = None
        self.stroke_pointer: int | None = None
        self.stroke_start: tuple[float, float, float] = (0.0, 0.0, 0.0)
        self.keys_water = False

    def handle(self, e: InputEvent) -> bool:
        """Handle one event; returns False when the game should quit."""
        game = self.game
        if e.device not in game.devices and e.device not in ("window", "hid") and e.amount >= 0:
            game.devices[e.device] = e.device.split(":")[0]
        if e.kind == QUIT:
            return False
        if e.kind in (DOWN, MOVE, UP):
            if e.dims == 3:
                self._pointer3d(e)
            elif e.device == "mouse" and e.button == 3:
                self._right_drag(e)
            elif e.button == 1:
                self._pointer(e.kind, hash((e.device, e.pointer)) & 0x7FFFFFFF, e.x, e.y, e.t)
        elif e.kind == WHEEL and not game.menu.visible:
            game.control.zoom(0.9**e.amount)
        elif e.kind == ROTATE and not game.menu.visible:
            game.control.turn(-e.ry)
            game.control.tilt_by(e.rx)
        elif e.kind in (KEY_DOWN, KEY_UP):
            return self._key(e.key, e.kind == KEY_DOWN)
        elif e.kind == FOCUS_LOST:
            game.gestures.cancel_all()
        elif e.kind == DEVICE:
            if e.amount < 0:
                game.devices.pop(e.device, None)
            game.say(e.text, 5)
        return True

    def _right_drag(self, e: InputEvent) -> None:
        """The mouse's tilt gesture: vertical right-button drag."""
        if e.kind == DOWN:
            self.right_y = e.y
        elif e.kind == MOVE and not self.game.menu.visible and self.right_y is not None:
            self.game.control.tilt_by((e.y - self.right_y) * 0.25)
            self.right_y = e.y
        else:
            self.right_y = None

    def _pointer3d(self, e: InputEvent) -> None:
        """A 3D tracker's cursor (shown by the HUD); in the modeler, its button draws strokes in 3D."""
        game = self.game
        game.cursor3d = (e.x, e.y, e.z)
        if not game.modeling.active:
            return
        if e.kind == DOWN:
            game.modeling.cancel_points()
            self.stroke_pointer = -3
        if self.stroke_pointer == -3:
            game.modeling.add3d(game.cursor3d, e.t)
            if e.kind == UP:
                game.modeling.finish()
                self.stroke_pointer = None

    def _stroke(self, kind: str, pid: int, x: float, y: float, now: float) -> bool:
        """Modeler: one pointer draws; a second pointer turns the stroke into a camera gesture."""
        game = self.game
        if not game.modeling.active or game.menu.visible:
            return False
        if kind == DOWN and self.stroke_pointer is None and not game.gestures.pointers:
            if game.menu.hit(x, y):
                return False
            self.stroke_pointer, self.stroke_start = pid, (x, y, now)
            game.modeling.begin2d(x, y, now, game.camera())
            return True
        if kind == DOWN and self.stroke_pointer is not None:  # second finger: it was a camera gesture
            sx, sy, st = self.stroke_start
            game.modeling.cancel_points()
            game.gestures.down(self.stroke_pointer, sx, sy, st)
            self.stroke_pointer = None
            return False
        if pid != self.stroke_pointer:
            return False
        if kind == MOVE:
            game.modeling.add2d(x, y, now, game.camera())
        elif kind == UP:
            self._stroke_up(x, y, now)
        return True

    def _stroke_up(self, x: float, y: float, now: float) -> None:
        game = self.game
        sx, sy, st = self.stroke_start
        self.stroke_pointer = None
        if now - st < TAP_SECONDS and abs(x - sx) + abs(y - sy) < TAP_PIXELS:  # a tap: a cut, or the menu
            game.modeling.cancel_points()
            camera = game.camera()
            if not (game.modeling.prune_at(x, y, camera) or game.modeling.edit_at(x, y, camera)):
                self.tap(x, y)
        else:
            game.modeling.finish()

    def _pointer(self, kind: str, pid: int, x: float, y: float, now: float) -> None:
        game = self.game
        if self._stroke(kind, pid, x, y, now):
            return
        if kind == DOWN:
            if game.menu.hit(x, y):
                self.menu_pointers.add(pid)
                for action in game.menu.press(x, y):
                    game.act(*action)
            else:
                game.gestures.menu_open = game.menu.visible
                game.gestures.down(pid, x, y, now)
        elif kind == MOVE:
            if pid in self.menu_pointers:
                for action in game.menu.drag(x, y):
                    game.act(*action)
            else:
                game.gestures.move(pid, x, y, now)
        elif pid in self.menu_pointers:
            self.menu_pointers.discard(pid)
            for action in game.menu.release():
                game.act(*action)
        elif game.gestures.up(pid, x, y, now):
            self.tap(x, y)

    def tap(self, x: float, y: float) -> None:
        """A tap outside the menu: close the menu if it is open; else pick the ripe fruit or choose the
        tree that was tapped, or open the menu there (the modeler's tools page in the modeler)."""
        game = self.game
        if game.family.visible:
            game.family.tap(x, y)
        elif game.menu.visible:
            for action in game.menu.hide():
                game.act(*action)
        elif game.modeling.active or not game.picker.tap(x, y, game.camera()):
            game.care.sync_sliders()
            game.menu.show_at(x, y, "tools" if game.modeling.active else None)
            game.coach.done("open_menu")
        game.gestures.menu_open = game.menu.visible

    def _key(self, key: int, down: bool) -> bool:
        game = self.game
        if key == pygame.K_w:
            if down != self.keys_water:
                self.keys_water = down
                game.act("water", float(down))
            return True
        if not down:
            return True
        if key == pygame.K_ESCAPE:
            return False
        if not game.menu.visible:
            self._camera_key(key)
        if key == pygame.K_m:
            self.tap(game.size[0] * 0.6, game.size[1] * 0.2)
        elif key == pygame.K_r:
            game.act("replant", 1.0)
        elif key == pygame.K_p:
            game.set_speed(0.0 if game.loop.speed else 1.0)
        elif key in (pygame.K_1, pygame.K_2, pygame.K_3):
            game.set_speed(SPEEDS[key - pygame.K_1 + 1])
        elif key == pygame.K_F5:
            game.act("save", 1.0)
        elif key == pygame.K_F9:
            game.act("load", 1.0)
        return True

    def _camera_key(self, key: int) -> None:
        """Arrows turn and tilt, +/- zoom."""
        control = self.game.control
        turns = {pygame.K_LEFT: (KEY_YAW, 0), pygame.K_RIGHT: (-KEY_YAW, 0),
                 pygame.K_UP: (0, KEY_TILT), pygame.K_DOWN: (0, -KEY_TILT)}
        if key in turns:
            control.turn(turns[key][0])
            control.tilt_by(turns[key][1])
        elif key in (pygame.K_PLUS, pygame.K_EQUALS, pygame.K_KP_PLUS):
            control.zoom(0.9)
        elif key in (pygame.K_MINUS, pygame.K_KP_MINUS):
            control.zoom(1 / 0.9)
