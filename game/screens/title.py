"""The title screen: Arbor's name over the garden itself (the scene keeps drawing behind it: the trees
sway, the clouds drift), shown when the game window opens after the first start's preparing screen
(game/first_start.py), until any key or touch; the kiosk shows it over its attract loop.

The words stand over the sky, or over the ground when the tree reaches up into the sky's band, so the crown
(and a new game's seedling rising) stays in view. It owns no window and no scene: it is the top of the game's
screen stack (game/screens/stack.py) while it is up, so :meth:`TitleScreen.handle` takes the game's input
events first (the press that dismisses it does nothing else), and it covers the HUD: :meth:`TitleScreen.paint`
draws it into the overlay in its place.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pygame

from arbor.game.input.events import DOWN, KEY_DOWN, KEY_UP, MOVE, UP, InputEvent
from arbor.game.screens.stack import Canvas, Screen
from arbor.game.strings import text

INK = (250, 248, 238)
SHADOW = (10, 20, 10)
BAND = (12, 26, 14)  # the shade behind the words (darkest at the band's middle)
NAME_SIZE, LINE_SIZE = 0.2, 0.045  # the name's and the lines' font size, as shares of the window's height
CROWN = 0.6  # the share of a tree's height on the screen, from its top, the words keep clear of
PLACES = (0.2, 0.8)  # where the words may stand (their middle, a share of the window's height): sky, ground


class TitleScreen(Screen):
    """What takes the title down, and its picture (see module docstring)."""

    covers = True  # (in place of the HUD)

    def __init__(self, size: tuple[int, int], prompt: str | None = None) -> None:
        self.size = size
        self.on_close: list[Callable[[], None]] = []  # told when a press takes the title down
        self.seen = False  # drawn at least once (a key before that was pressed while the garden was planted)
        self.subject: Callable[[], np.ndarray] | None = None  # 3D points of what the words keep clear of (the tree)
        self.prompt = prompt or text("title.prompt")
        height = size[1]
        self.fonts = (pygame.font.Font(None, max(int(height * NAME_SIZE), 24)),
                      pygame.font.Font(None, max(int(height * LINE_SIZE), 14)))

    def handle(self, e: InputEvent) -> InputEvent | None:
        """Every press, key and move is the title's, and a press or a key takes it down (its release alone
        is no tap: the game's gestures see nothing of that press); the rest (a quit) goes down. A key pressed
        before the title was first drawn (while "planting the garden..." showed) takes it down and acts too:
        the player pressed it to play, not to dismiss a title they had not seen."""
        if e.kind in (DOWN, KEY_DOWN):
            self.close()
            for listener in self.on_close:
                listener()
            if e.kind == KEY_DOWN and not self.seen:  # pressed while the garden was planted: it acts (kept)
                return e
        return None if e.kind in (DOWN, MOVE, UP, KEY_DOWN, KEY_UP) else e

    def draw(self, canvas: Canvas) -> None:
        """The title over the garden (see :meth:`paint`), clear of its :attr:`subject` as the camera sees it."""
        self.paint(canvas.surface, self.clear_of(canvas))

    def clear_of(self, canvas: Canvas) -> tuple[float, float] | None:
        """The rows (top, bottom, window pixels) of the subject's crown on the screen now: the upper CROWN
        share of the rows it covers (the trunk below may be covered); None when unknown."""
        if self.subject is None or canvas.project is None:
            return None
        seen = canvas.project(self.subject())
        if not seen:
            return None
        top, bottom = min(y for _, y in seen), max(y for _, y in seen)
        return top, top + CROWN * (bottom - top)

    def paint(self, surface: pygame.Surface, clear: tuple[float, float] | None = None) -> None:
        """The name, the tagline and the prompt on a soft band of shade across ``surface``: over the sky, or
        over the ground when that covers less of the rows ``clear`` (the tree: its crown stays in view)."""
        self.seen = True
        w, h = surface.get_size()
        big, small = self.fonts
        words = [(big, text("title.name"), INK), (small, text("title.tagline"), INK),
                 (small, self.prompt, (255, 228, 120))]
        gap = small.get_linesize() // 2
        block = sum(font.get_linesize() for font, _, _ in words) + 3 * gap
        top = place(h, block, clear)
        _band(surface, top - h * 0.08, block + h * 0.16)
        y = top
        for k, (font, line, colour) in enumerate(words):
            label = font.render(line, True, colour)
            if label.get_width() > w - 40:  # (a long translation still fits)
                label = pygame.transform.smoothscale_by(label, (w - 40) / label.get_width())
            at = label.get_rect(midtop=(w // 2, y + (gap if k == 2 else 0)))
            offset = max(h // 240, 1) * (2 if k == 0 else 1)
            shade = font.render(line, True, SHADOW)
            surface.blit(pygame.transform.smoothscale(shade, label.get_size()), at.move(offset, offset))
            surface.blit(label, at)
            y = at.bottom + gap


def place(height: int, block: int, clear: tuple[float, float] | None) -> int:
    """The top row of the title's words (``block`` rows high) in a window ``height`` rows high: the first of
    PLACES whose band of shade covers the fewest of the rows ``clear`` (top, bottom; None: the first)."""
    best = None
    for at in PLACES:
        top = int(height * at - block / 2)
        band = (top - height * 0.08, top + block + height * 0.08)
        covered = 0.0 if clear is None else max(0.0, min(band[1], clear[1]) - max(band[0], clear[0]))
        if best is None or covered < best[0]:
            best = (covered, top)
    return best[1]


def box_corners(lo, hi) -> np.ndarray:
    """The 8 corners of the box ``lo`` .. ``hi`` (3D points), for :attr:`TitleScreen.subject`."""
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    return np.array([[(lo, hi)[i][0], (lo, hi)[j][1], (lo, hi)[k][2]] for i in (0, 1) for j in (0, 1) for k in (0, 1)])


def _band(surface: pygame.Surface, top: float, height: float) -> None:
    """A horizontal band of shade, clear at its edges and most opaque in its middle."""
    w = surface.get_width()
    rows = max(int(height), 1)
    band = pygame.Surface((1, rows), pygame.SRCALPHA)
    for r in range(rows):
        middle = 1.0 - abs(2.0 * r / max(rows - 1, 1) - 1.0)
        band.set_at((0, r), (*BAND, int(85 * min(middle * 1.6, 1.0))))
    surface.blit(pygame.transform.scale(band, (w, rows)), (0, int(top)))
