"""The screen stack: which screen is up, which takes an input event, and what is drawn over what.

In the manner of Tuxemon's ``StateManager``: screens are pushed and popped; an input event goes to the top
screen first, and each screen takes the events it wants (returning None) and passes the rest down
(returning the event, or another event it became) to the screen below it; what comes out of the bottom
was nobody's (the game quits on a QUIT left over). Screens are drawn bottom first, each over those below,
from the topmost one that ``covers`` what is beneath it (the title stands in for the HUD). The game's
stack, bottom first: the garden (game_input.py), the modeler (modeler_screen.py), the menu
(menu_screen.py), the family tree (family.py), the title (title.py), the kiosk's own layers (kiosk.py);
the lab's window is a stack with the lab screen alone (game/app.py).

Nothing here knows the game: a screen is anything with ``handle``, ``update`` and ``draw``; a screen's
``layer`` keeps the kiosk's layers over what opens after them (a menu, the modeler).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Any

import pygame

from arbor.game.input.events import KEY_DOWN, QUIT, InputEvent

TAP = "tap"  # an event kind the screens make themselves: a quick press and release at (x, y)


def quit_asked(e: InputEvent) -> InputEvent | None:
    """The quit a window's event asks for (the window's close, or Esc in a window of its own), else None."""
    if e.kind == QUIT:
        return e
    if e.kind == KEY_DOWN and e.key == pygame.K_ESCAPE:
        return InputEvent(QUIT, e.t, e.device)
    return None


@dataclass(frozen=True)
class Canvas:
    """What the game's screens draw into: the overlay ``surface`` (pygame, RGBA), the ``camera`` the scene
    was seen through this frame and ``project`` (3D points -> the window pixels of those in view)."""

    surface: Any
    camera: Any = None
    project: Callable[[Any], list[tuple[float, float]]] | None = None


class Screen:
    """One layer of a :class:`ScreenStack`. The defaults pass every event down, draw nothing and cover
    nothing; a screen overrides what it does."""

    covers = False  # drawn in place of every screen below it (those are not drawn)
    layer = 0  # a screen opens on top of those of its layer and lower, under any of a higher layer
    stack: ScreenStack | None = None  # the stack it is pushed on (set by push; a screen opens itself on it)

    def handle(self, e: InputEvent) -> InputEvent | None:
        """Take ``e`` (return None) or pass it down (return it, or what it became for the screens below)."""
        return e

    def update(self, seconds: float) -> None:
        """One frame's worth of time (real seconds)."""

    def draw(self, target: Any) -> None:
        """Draw this screen over those below it into ``target`` (the game's :class:`Canvas`)."""

    def holds(self, x: float, y: float) -> bool:
        """Whether (x, y) is on a control of this screen (a tool bar) that a screen above it lets a press
        through to."""
        return False

    def key(self) -> tuple:
        """What this screen shows (a screen drawn into a cached layer is redrawn when this changes)."""
        return ()

    @property
    def up(self) -> bool:
        """Whether this screen is on its stack now."""
        return self.stack is not None and self in self.stack

    def open(self) -> None:
        """Push this screen on its stack (on top; already up: moved to the top)."""
        if self.stack is None:
            raise RuntimeError(f"{type(self).__name__} has no stack to open on")
        self.stack.push(self)

    def close(self) -> None:
        """Take this screen off its stack (nothing when it is not up)."""
        if self.stack is not None:
            self.stack.pop(self)


class ScreenStack:
    """Screens, bottom first (see module docstring)."""

    def __init__(self, *screens: Screen) -> None:
        self._screens: list[Screen] = []
        for screen in screens:
            self.push(screen)

    def push(self, screen: Screen) -> Screen:
        """Put ``screen`` on top of the screens of its ``layer`` and lower, under any of a higher layer (the
        kiosk's own layers stay over a menu opened after them); a screen already on the stack
        moves there. Returns it."""
        if screen in self._screens:
            self._screens.remove(screen)
        screen.stack = self
        at = next((i for i, s in enumerate(self._screens) if s.layer > screen.layer), len(self._screens))
        self._screens.insert(at, screen)
        return screen

    def pop(self, screen: Screen | None = None) -> Screen | None:
        """Take ``screen`` off the stack, wherever it is (None: the top one); returns what was taken, or None
        when it was not on the stack."""
        if screen is None:
            return self._screens.pop() if self._screens else None
        if screen not in self._screens:
            return None
        self._screens.remove(screen)
        return screen

    @property
    def top(self) -> Screen | None:
        """The screen on top, None when the stack is empty."""
        return self._screens[-1] if self._screens else None

    def __contains__(self, screen: object) -> bool:
        return any(s is screen for s in self._screens)

    def __iter__(self) -> Iterator[Screen]:
        """The screens, bottom first."""
        return iter(list(self._screens))

    def __len__(self) -> int:
        return len(self._screens)

    def below(self, screen: Screen) -> list[Screen]:
        """The screens under ``screen``, nearest first."""
        index = next(i for i, s in enumerate(self._screens) if s is screen)
        return self._screens[:index][::-1]

    def handle(self, e: InputEvent) -> InputEvent | None:
        """Offer ``e`` to the screens top first until one takes it; returns what is left (None: taken).
        A screen pushed while the event goes down does not see it; one popped on the way is skipped."""
        for screen in self._screens[::-1]:
            if screen not in self:
                continue
            e = screen.handle(e)
            if e is None:
                return None
        return e

    def handle_input(self, e: InputEvent) -> bool:
        """:meth:`handle` ``e``; False when what is left over is a quit (the window ends)."""
        left = self.handle(e)
        return left is None or left.kind != QUIT

    def update(self, seconds: float) -> None:
        """Every screen's frame, bottom first."""
        for screen in list(self._screens):
            screen.update(seconds)

    def drawn(self) -> list[Screen]:
        """The screens drawn, bottom first: from the topmost one that covers those below it."""
        start = max((i for i, s in enumerate(self._screens) if s.covers), default=0)
        return self._screens[start:]

    def covered(self) -> bool:
        """Whether a screen that covers those below it is up."""
        return any(s.covers for s in self._screens)

    def draw(self, target: Any) -> None:
        """Draw the screens :meth:`drawn` shows, bottom first, into ``target``."""
        for screen in self.drawn():
            screen.draw(target)

    def key(self) -> tuple:
        """What the screens show: each screen's :meth:`Screen.key`, bottom first."""
        return tuple((id(s), s.key()) for s in self._screens)
