"""A reminder while the player is elsewhere (issue 47): when the cared-for tree comes to want water while the
game's window is not focused (minimised, or behind other windows), the window asks for attention once
(its taskbar entry flashes until it is focused) and its title says what the tree wants; the title comes
back once the window is focused again. Off with ``remind = false`` in the saves folder's settings.toml.
"""

from __future__ import annotations

import warnings

import pygame

from arbor.game.strings import text

TITLE = "Arbor"


class NeedBell:
    """Rings once per thirst of the cared-for tree while the window is not focused (see module docstring)."""

    def __init__(self) -> None:
        self.rung = False  # rung for the thirst now (until the tree has water again)
        self.titled = False  # the window's title says the tree wants water

    def check(self, thirsty: bool, focused: bool) -> bool:
        """Whether to ring now: the tree wants water, the window is not focused, and this thirst has not
        rung yet."""
        if not thirsty:
            self.rung = False
            return False
        if focused or self.rung:
            return False
        self.rung = True
        return True

    def update(self, thirsty: bool) -> None:
        """Look at the window and ring (flash it, say it in its title) or take the title back."""
        window = _window()
        if window is None:
            return
        if self.check(thirsty, window.focused):
            pygame.display.set_caption(f"{TITLE} - {text('messages.bell')}")
            window.flash(pygame.FLASH_UNTIL_FOCUSED)
            self.titled = True
        elif self.titled and (window.focused or not thirsty):
            pygame.display.set_caption(TITLE)
            self.titled = False


def _window() -> pygame.Window | None:
    """The game's window, or None (no window: the display is not up)."""
    if not pygame.display.get_init() or pygame.display.get_surface() is None:
        return None
    with warnings.catch_warnings():  # (pygame-ce warns that surface rendering moves to Window: not used here)
        warnings.simplefilter("ignore", DeprecationWarning)
        try:
            return pygame.Window.from_display_module()
        except (pygame.error, AttributeError):
            return None
