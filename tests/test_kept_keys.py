"""Issue 47: a key pressed while the first start's screen shows ("waking the garden...") is not lost: the
game's first frame gets it (and a key before the game's title was drawn acts: tests/test_look_title.py)."""

import pygame

from arbor.game import first_start


class _Screen:
    def __init__(self, ctx, size):
        self.lines = []

    def draw(self, progress, line):
        self.lines.append(line)


class _Warmup:
    """Done once the loop has looked at the window's events twice."""

    def __init__(self, extra=None):
        self.cold, self.progress, self.looks = False, 0.5, 0

    @property
    def done(self):
        self.looks += 1
        return self.looks > 2

    def result(self):
        return None


def test_a_key_pressed_while_the_garden_is_prepared_is_given_to_the_game(gl_ctx, monkeypatch):
    monkeypatch.setattr(first_start, "TitleScreen", _Screen)
    monkeypatch.setattr(first_start, "Warmup", _Warmup)
    pygame.event.clear()
    pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_3, mod=0, unicode="3", scancode=32))
    pygame.event.post(pygame.event.Event(pygame.KEYUP, key=pygame.K_3, mod=0, unicode="3", scancode=32))
    assert first_start.show_until_ready(None, (64, 64))
    keys = [(e.type, e.key) for e in pygame.event.get() if e.type in (pygame.KEYDOWN, pygame.KEYUP)]
    assert keys == [(pygame.KEYDOWN, pygame.K_3), (pygame.KEYUP, pygame.K_3)], keys
