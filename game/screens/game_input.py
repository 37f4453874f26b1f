"""The garden's screen, the bottom of the game's screen stack (game/screens/stack.py): what the events the
screens above pass down become here: camera gestures (drags, pinches, the wheel, a 3D mouse's turn, the
right button's tilt, the arrow keys), taps (the ripe fruit, another tree, else the menu opens there), the
3D cursor and the keys (the keys become :class:`~arbor.engine.life.world.actions.Action` values)."""

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
from arbor.game.screens.picking import Picker
from arbor.game.screens.stack import TAP, Screen, ScreenStack
from arbor.game.screens.state import GameState
from arbor.game.strings import text

KEY_YAW, KEY_TILT = 4.0, 3.0  # degrees per key press
TURN_KEYS = {pygame.K_LEFT: (KEY_YAW, 0), pygame.K_RIGHT: (-KEY_YAW, 0),
             pygame.K_UP: (0, KEY_TILT), pygame.K_DOWN: (0, -KEY_TILT)}
ZOOM_KEYS = {pygame.K_PLUS: 0.9, pygame.K_EQUALS: 0.9, pygame.K_KP_PLUS: 0.9,
             pygame.K_MINUS: 1 / 0.9, pygame.K_KP_MINUS: 1 / 0.9}
CAMERA_KEYS = frozenset(TURN_KEYS) | frozenset(ZOOM_KEYS)  # (the open menu holds them: the view stays)


def pointer_id(e: InputEvent) -> int:
    """One number for a pointer of a device (the mouse, a finger of a touch screen)."""
    return hash((e.device, e.pointer)) & 0x7FFFFFFF


class GameInput(Screen):
    """The garden screen's input (see module docstring); ``tap`` sends a tap down the whole stack."""

    def __init__(self, state: GameState, size: tuple[int, int], camera: Callable[[], OrbitCamera], *,
                 screens: ScreenStack, menu: Menu, gestures: Gestures, care: CareActions, picker: Picker) -> None:
        self.state, self.size, self.camera = state, size, camera
        self.stack, self.menu, self.gestures, self.care, self.picker = screens, menu, gestures, care, picker
        self.right_y: float | None = None
        self.keys_water = False
        self.ask_quit = False  # the next Esc asks before quitting (set when Esc left the modeler)

    def note_device(self, e: InputEvent) -> None:
        """Remember the input devices seen (Settings -> Devices lists them)."""
        state = self.state
        if e.device not in state.devices and e.device not in ("window", "hid") and e.amount >= 0:
            state.devices[e.device] = e.device.split(":")[0]

    def handle(self, e: InputEvent) -> InputEvent | None:
        """Take every event but a quit (the window's close, or Esc: left over, the game ends)."""
        state = self.state
        if e.kind == QUIT:
            return e
        if e.kind in (DOWN, MOVE, UP):
            if e.dims == 3:
                state.cursor3d = (e.x, e.y, e.z)  # (shown by the HUD; the modeler above draws with it)
            elif e.device == "mouse" and e.button == 3:
                self._right_drag(e)
            elif e.button == 1:
                self._pointer(e.kind, pointer_id(e), e.x, e.y, e.t)
        elif e.kind == TAP:
            self._tap(e.x, e.y)
        elif e.kind == WHEEL:
            state.control.zoom(0.9**e.amount)
        elif e.kind == ROTATE:
            state.control.turn(-e.ry)
            state.control.tilt_by(e.rx)
        elif e.kind in (KEY_DOWN, KEY_UP):
            return self._key(e)
        elif e.kind == FOCUS_LOST:
            self.gestures.cancel_all()
        elif e.kind == DEVICE:
            if e.amount < 0:
                state.devices.pop(e.device, None)
            state.say(e.text, 5)
        return None

    def _right_drag(self, e: InputEvent) -> None:
        """The mouse's tilt gesture: vertical right-button drag (the open menu passes its moves down as a
        release: the tilt ends)."""
        if e.kind == DOWN:
            self.right_y = e.y
        elif e.kind == MOVE and self.right_y is not None:
            self.state.control.tilt_by((e.y - self.right_y) * 0.25)
            self.right_y = e.y
        else:
            self.right_y = None

    def _pointer(self, kind: str, pid: int, x: float, y: float, now: float) -> None:
        """A finger or the mouse's left button on the garden: camera gestures, and taps."""
        if kind == DOWN:
            self.gestures.down(pid, x, y, now)
        elif kind == MOVE:
            self.gestures.move(pid, x, y, now)
        elif self.gestures.up(pid, x, y, now):
            self.tap(x, y)

    def tap(self, x: float, y: float) -> None:
        """A tap at (x, y), offered to the screens top first: the family tree takes it (and closes), or the
        open menu (it closes), or the modeler (its tools page opens there), else the garden's (below)."""
        self.stack.handle(InputEvent(TAP, self.state.clock(), "tap", x=x, y=y))

    def _tap(self, x: float, y: float) -> None:
        """The garden's tap: pick the ripe fruit or choose the tree that was tapped, or open the menu there."""
        if not self.picker.tap(x, y, self.camera()):
            self.care.sync_sliders()
            self.menu.show_at(x, y)

    def guard_quit(self) -> None:
        """Esc left the modeler: the garden's next Esc asks before quitting (a second Esc pressed in haste
        does not end the app)."""
        self.ask_quit = True

    def _key(self, e: InputEvent) -> InputEvent | None:
        key, down = e.key, e.kind == KEY_DOWN
        if key == pygame.K_w:
            if down != self.keys_water:
                self.keys_water = down
                self.care.act(Action.WATER, float(down))
            return None
        if not down:
            return None
        if key == pygame.K_ESCAPE:
            if self.ask_quit:  # (the Esc before left the modeler: this one asks, the next quits)
                self.ask_quit = False
                self.state.say(text("messages.quit_confirm"), 5.0)
                return None
            return InputEvent(QUIT, e.t, e.device)
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
        return None

    def _camera_key(self, key: int) -> None:
        """Arrows turn and tilt, +/- zoom."""
        control = self.state.control
        if key in TURN_KEYS:
            control.turn(TURN_KEYS[key][0])
            control.tilt_by(TURN_KEYS[key][1])
        elif key in ZOOM_KEYS:
            control.zoom(ZOOM_KEYS[key])
