"""The title screen: Arbor's name over the garden itself (the scene keeps drawing behind it: the trees
sway, the clouds drift), shown when the game window opens after the first start's preparing screen
(game/first_start.py), until any key or touch; the kiosk shows it over its attract loop.

It owns no window and no scene: it is the top of the game's screen stack (game/screens/stack.py) while it
is up, so :meth:`TitleScreen.handle` takes the game's input events first (the press that dismisses it does
nothing else), and it covers the HUD: :meth:`TitleScreen.paint` draws it into the overlay in its place.
"""

from __future__ import annotations

from collections.abc import Callable

import pygame

from arbor.game.input.events import DOWN, KEY_DOWN, KEY_UP, MOVE, UP, InputEvent
from arbor.game.screens.stack import Canvas, Screen
from arbor.game.strings import text

INK = (250, 248, 238)
SHADOW = (10, 20, 10)
BAND = (12, 26, 14)  # the shade behind the words (darkest at the band's middle)
NAME_SIZE, LINE_SIZE = 0.2, 0.045  # the name's and the lines' font size, as shares of the window's height


class TitleScreen(Screen):
    """What takes the title down, and its picture (see module docstring)."""

    covers = True  # (in place of the HUD)

    def __init__(self, size: tuple[int, int], prompt: str | None = None) -> None:
        self.size = size
        self.on_close: list[Callable[[], None]] = []  # told when a press takes the title down
        self.prompt = prompt or text("title.prompt")
        height = size[1]
        self.fonts = (pygame.font.Font(None, max(int(height * NAME_SIZE), 24)),
                      pygame.font.Font(None, max(int(height * LINE_SIZE), 14)))

    def handle(self, e: InputEvent) -> InputEvent | None:
        """Every press, key and move is the title's, and a press or a key takes it down (its release alone
        is no tap: the game's gestures see nothing of that press); the rest (a quit) goes down."""
        if e.kind in (DOWN, KEY_DOWN):
            self.close()
            for listener in self.on_close:
                listener()
        return None if e.kind in (DOWN, MOVE, UP, KEY_DOWN, KEY_UP) else e

    def draw(self, canvas: Canvas) -> None:
        """The title over the garden (see :meth:`paint`)."""
        self.paint(canvas.surface)

    def paint(self, surface: pygame.Surface) -> None:
        """The name, the tagline and the prompt on a soft band of shade across the middle of ``surface``."""
        w, h = surface.get_size()
        big, small = self.fonts
        words = [(big, text("title.name"), INK), (small, text("title.tagline"), INK),
                 (small, self.prompt, (255, 228, 120))]
        gap = small.get_linesize() // 2
        block = sum(font.get_linesize() for font, _, _ in words) + 3 * gap
        top = int(h * 0.42 - block / 2)
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


def _band(surface: pygame.Surface, top: float, height: float) -> None:
    """A horizontal band of shade, clear at its edges and most opaque in its middle."""
    w = surface.get_width()
    rows = max(int(height), 1)
    band = pygame.Surface((1, rows), pygame.SRCALPHA)
    for r in range(rows):
        middle = 1.0 - abs(2.0 * r / max(rows - 1, 1) - 1.0)
        band.set_at((0, r), (*BAND, int(150 * min(middle * 1.6, 1.0))))
    surface.blit(pygame.transform.scale(band, (w, rows)), (0, int(top)))
