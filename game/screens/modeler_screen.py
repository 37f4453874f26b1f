"""The modeler as a screen of the game's stack (game/screens/stack.py): up while the modeler is open
(:class:`~arbor.game.screens.modeler.ModelingMode` opens and closes it). It takes the strokes (one pointer
draws; a second pointer turns the stroke into a camera gesture, passed down to the garden), a 3D tracker's
strokes, the presses on its tool bar and the taps (a cut or a region edit with their tools, else the menu's
tools page opens there); it draws the tools' outlines, the symbols' overlay and the tool bar.

Keys in the modeler: Esc leaves it (the menu's screen above takes an Esc that closes it; back in the
garden, the next Esc asks before quitting), Ctrl+Z undoes, Ctrl+Y or Ctrl+Shift+Z redoes, F frames the tree and its
lobes (the view never re-frames by itself while a tool is in use). Other Ctrl combinations are the
modeler's too (none reaches the garden's one-letter keys); the rest go down to the garden (arrows turn
the view, +/- zoom)."""

from __future__ import annotations

from collections.abc import Callable

import pygame

from arbor.game.input.events import DOWN, KEY_DOWN, KEY_UP, MOVE, UP, InputEvent
from arbor.game.input.gestures import Gestures
from arbor.game.render.ui import Menu
from arbor.game.screens.care import CareActions
from arbor.game.screens.game_input import pointer_id
from arbor.game.screens.modeler import ModelingMode
from arbor.game.screens.stack import TAP, Canvas, Screen, ScreenStack
from arbor.game.strings import text

TAP_SECONDS, TAP_PIXELS = 0.3, 12
DRAWN_POINTS = 10  # pointer moves after which a stroke a second finger turns into a gesture is said to be let go
TRACKER = -3  # the stroke pointer of a 3D tracker's button
CTRL_KEYS = (pygame.K_LCTRL, pygame.K_RCTRL, pygame.K_LMETA, pygame.K_RMETA)  # (Cmd on a Mac)
SHIFT_KEYS = (pygame.K_LSHIFT, pygame.K_RSHIFT)


class ModelerScreen(Screen):
    """The modeler on the stack (see module docstring); ``tap`` sends a tap down the whole stack."""

    def __init__(self, modeling: ModelingMode, screens: ScreenStack, *, menu: Menu, gestures: Gestures,
                 care: CareActions, tap: Callable[[float, float], None],
                 fonts: tuple[pygame.font.Font, pygame.font.Font],
                 left: Callable[[], None] = lambda: None) -> None:
        self.modeling, self.stack, self.menu, self.gestures, self.care = modeling, screens, menu, gestures, care
        self.state, self.camera = modeling.state, modeling.camera  # (the game's, as the modeler has them)
        self.tap, self.fonts = tap, fonts
        self.left = left  # called when Esc left the modeler (the garden's next Esc then asks before quitting)
        self.held: set[int] = set()  # Ctrl and Shift keys held down
        self.bar_pointers: set[int] = set()  # pointers pressing the tool bar
        self.stroke_pointer: int | None = None
        self.stroke_start: tuple[float, float, float] = (0.0, 0.0, 0.0)

    def handle(self, e: InputEvent) -> InputEvent | None:
        """See module docstring; what is not the modeler's goes down to the garden."""
        if e.kind == TAP:
            self.care.sync_sliders()
            self.menu.show_at(e.x, e.y, "tools")
            return None
        if e.kind in (KEY_DOWN, KEY_UP):
            return self._key(e)
        if e.kind not in (DOWN, MOVE, UP):
            return e
        if e.dims == 3:
            self._tracker(e)
            return e  # (the garden moves the 3D cursor)
        if e.button != 1:
            return e
        pid, x, y = pointer_id(e), e.x, e.y
        if self._stroke(e.kind, pid, x, y, e.t):
            return None
        if e.kind == DOWN and self.modeling.crown_panel.over(x, y):  # the crown panel's buttons act on the press
            self.bar_pointers.add(pid)
            self.menu.hide()
            self.modeling.crown_panel.press(x, y)
            return None
        if e.kind == DOWN and self.modeling.bar.over(x, y):  # (a press there closes the menu)
            self.bar_pointers.add(pid)
            for action in [*self.menu.hide(), *self.modeling.bar.press(x, y)]:
                self.care.act(*action)
            return None
        if pid in self.bar_pointers:
            if e.kind == UP:
                self.bar_pointers.discard(pid)
                self.modeling.bar.release()
            return None
        return e

    def _key(self, e: InputEvent) -> InputEvent | None:
        """The modeler's keys (see module docstring); the others go down to the garden."""
        if e.key in (*CTRL_KEYS, *SHIFT_KEYS):
            (self.held.add if e.kind == KEY_DOWN else self.held.discard)(e.key)
            return e
        mods = pygame.key.get_mods()
        ctrl = bool(self.held.intersection(CTRL_KEYS)) or bool(mods & (pygame.KMOD_CTRL | pygame.KMOD_META))
        shift = bool(self.held.intersection(SHIFT_KEYS)) or bool(mods & pygame.KMOD_SHIFT)
        if e.kind != KEY_DOWN:
            return e  # (a release always reaches the garden: W let go with Ctrl held stops the can)
        if e.key == pygame.K_ESCAPE:
            self.modeling.toggle(leave_key=True)
            self.left()
            return None
        if ctrl:
            if e.key == pygame.K_z:
                (self.modeling.redo if shift else self.modeling.undo)()
            elif e.key == pygame.K_y:
                self.modeling.redo()
            return None
        if e.key == pygame.K_f:
            self.modeling.frame()
            return None
        return e

    def close(self) -> None:
        """Leave the stack with the tool bar let go (the press on Done closes it before its release) and no
        stroke half drawn (its pointer would stay a finger down for good)."""
        super().close()
        self.bar_pointers.clear()
        self.held.clear()
        self.modeling.bar.release()
        self.stroke_pointer = None
        self.modeling.cancel_points()

    def holds(self, x: float, y: float) -> bool:
        """The tool bar: a press on it reaches it through the open menu."""
        return self.modeling.bar.over(x, y)

    def _tracker(self, e: InputEvent) -> None:
        """A 3D tracker's button draws strokes in 3D."""
        modeling = self.modeling
        if e.kind == DOWN:
            modeling.cancel_points()
            self.stroke_pointer = TRACKER
        if self.stroke_pointer == TRACKER:
            modeling.add3d((e.x, e.y, e.z), e.t)
            if e.kind == UP:
                modeling.finish()
                self.stroke_pointer = None

    def _stroke(self, kind: str, pid: int, x: float, y: float, now: float) -> bool:
        """One pointer draws; a second pointer turns the stroke into a camera gesture. True: taken."""
        modeling = self.modeling
        if kind == DOWN and self.stroke_pointer is None and not self.gestures.pointers:
            if modeling.bar.over(x, y) or modeling.crown_panel.over(x, y):
                return False
            self.stroke_pointer, self.stroke_start = pid, (x, y, now)
            modeling.begin2d(x, y, now, self.camera())
            return True
        if kind == DOWN and self.stroke_pointer is not None:  # second finger: it was a camera gesture
            sx, sy, st = self.stroke_start
            if len(modeling.points) >= DRAWN_POINTS:  # a stroke well under way is not lost in silence
                self.state.say(text("messages.stroke_dropped"))
            modeling.cancel_points()
            self.gestures.down(self.stroke_pointer, sx, sy, st)
            self.stroke_pointer = None
            return False
        if pid != self.stroke_pointer:
            return False
        if kind == MOVE:
            modeling.add2d(x, y, now, self.camera())
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

    def draw(self, canvas: Canvas) -> None:
        """The tools' outlines and the joint marker, the symbols' overlay, then the tool bar."""
        font, small = self.fonts
        self.modeling.draw_outline(canvas.surface, canvas.project)
        self.modeling.draw_symbols(canvas.surface, canvas.camera, small, canvas.project)
        self.modeling.bar.draw(canvas.surface, font)
        self.modeling.crown_panel.draw(canvas.surface, font, small)

    def key(self) -> tuple:
        """What the tool bar shows."""
        return self.modeling.bar.key(), self.modeling.crown_panel.key()
