"""Small vector icons for the menu (drawn with pygame shapes: no image files to ship or translate)."""

from __future__ import annotations

import math

import pygame

INK = (245, 245, 235)
SUN = (250, 204, 40)
WATER = (90, 160, 250)
LEAF = (120, 200, 90)


def draw_icon(surface: pygame.Surface, name: str, box: pygame.Rect) -> None:
    """Draw icon ``name`` (a key of ICONS: sun, clock, can, sapling, seed, speaker, ...) into ``box``."""
    cx, cy, r = box.centerx, box.centery, min(box.width, box.height) * 0.38
    draw = ICONS.get(name)
    if draw is not None:
        draw(surface, cx, cy, r)


def _sun(s, cx, cy, r):
    pygame.draw.circle(s, SUN, (cx, cy), int(r * 0.55))
    for k in range(8):
        a = k * math.pi / 4
        pygame.draw.line(s, SUN, (cx + math.cos(a) * r * 0.75, cy + math.sin(a) * r * 0.75),
                         (cx + math.cos(a) * r * 1.1, cy + math.sin(a) * r * 1.1), 3)


def _clock(s, cx, cy, r):
    pygame.draw.circle(s, INK, (cx, cy), int(r), 3)
    pygame.draw.line(s, INK, (cx, cy), (cx, cy - r * 0.7), 3)
    pygame.draw.line(s, INK, (cx, cy), (cx + r * 0.5, cy), 3)


def _can(s, cx, cy, r):
    body = pygame.Rect(0, 0, int(r * 1.2), int(r * 1.1))
    body.center = (int(cx - r * 0.2), int(cy + r * 0.2))
    pygame.draw.rect(s, WATER, body, border_radius=4)
    pygame.draw.line(s, WATER, body.topright, (cx + r * 1.0, cy - r * 0.6), 4)
    pygame.draw.arc(s, INK, body.inflate(-4, 8).move(0, -int(r * 0.6)), 0.3, 2.8, 3)
    for k in range(3):
        pygame.draw.circle(s, WATER, (int(cx + r * (0.9 + 0.12 * k)), int(cy - r * 0.2 + k * r * 0.35)), 2)


def _sapling(s, cx, cy, r):
    pygame.draw.line(s, (150, 110, 70), (cx, cy + r), (cx, cy - r * 0.3), 3)
    pygame.draw.ellipse(s, LEAF, pygame.Rect(cx - r, cy - r * 0.7, r, r * 0.55))
    pygame.draw.ellipse(s, LEAF, pygame.Rect(cx, cy - r * 1.0, r, r * 0.55))


def _seed(s, cx, cy, r):
    pygame.draw.ellipse(s, (180, 130, 70), pygame.Rect(cx - r * 0.5, cy - r * 0.8, r, r * 1.6))
    pygame.draw.line(s, (120, 80, 40), (cx, cy - r * 0.6), (cx, cy + r * 0.6), 2)


def _pencil(s, cx, cy, r):
    pygame.draw.line(s, SUN, (cx - r * 0.8, cy + r * 0.8), (cx + r * 0.7, cy - r * 0.7), 7)
    pygame.draw.polygon(s, INK, [(cx - r * 0.8, cy + r * 0.8), (cx - r * 1.0, cy + r * 1.0),
                                 (cx - r * 0.6, cy + r * 0.95)])


def _gear(s, cx, cy, r):
    for k in range(8):
        a = k * math.pi / 4
        pygame.draw.line(s, INK, (cx, cy), (cx + math.cos(a) * r, cy + math.sin(a) * r), 5)
    pygame.draw.circle(s, INK, (cx, cy), int(r * 0.7))
    pygame.draw.circle(s, (45, 70, 42), (cx, cy), int(r * 0.3))


def _book(s, cx, cy, r):
    left = pygame.Rect(cx - r, cy - r * 0.8, r, r * 1.6)
    pygame.draw.rect(s, INK, left, 2)
    pygame.draw.rect(s, INK, left.move(int(r), 0), 2)
    for k in range(3):
        y = cy - r * 0.4 + k * r * 0.4
        pygame.draw.line(s, INK, (cx - r * 0.8, y), (cx - r * 0.2, y), 1)


def _back(s, cx, cy, r):
    pygame.draw.polygon(s, INK, [(cx - r, cy), (cx, cy - r * 0.8), (cx, cy + r * 0.8)])
    pygame.draw.rect(s, INK, pygame.Rect(cx, cy - r * 0.3, r, r * 0.6))


def _cross(s, cx, cy, r):
    pygame.draw.line(s, (200, 70, 60), (cx - r * 0.7, cy - r * 0.7), (cx + r * 0.7, cy + r * 0.7), 5)
    pygame.draw.line(s, (200, 70, 60), (cx - r * 0.7, cy + r * 0.7), (cx + r * 0.7, cy - r * 0.7), 5)


def _stone(s, cx, cy, r):
    pygame.draw.ellipse(s, (150, 145, 135), pygame.Rect(cx - r, cy - r * 0.6, 2 * r, r * 1.3))
    pygame.draw.arc(s, INK, pygame.Rect(cx - r, cy - r * 0.6, 2 * r, r * 1.3), 0.4, 2.6, 2)


def _speaker(s, cx, cy, r):
    pygame.draw.polygon(s, INK, [(cx - r, cy - r * 0.35), (cx - r * 0.5, cy - r * 0.35), (cx, cy - r * 0.85),
                                 (cx, cy + r * 0.85), (cx - r * 0.5, cy + r * 0.35), (cx - r, cy + r * 0.35)])
    for k in (1, 2):
        box = pygame.Rect(0, 0, int(r * 0.6 * k), int(r * 0.9 * k))
        box.center = (int(cx), int(cy))
        pygame.draw.arc(s, INK, box, -0.9, 0.9, 3)


def _card(s, cx, cy, r):
    """A postcard with a little tree on it (Share, Import)."""
    card = pygame.Rect(0, 0, int(r * 2.0), int(r * 1.4))
    card.center = (int(cx), int(cy))
    pygame.draw.rect(s, INK, card, 2, border_radius=3)
    pygame.draw.line(s, (150, 110, 70), (cx - r * 0.4, cy + r * 0.5), (cx - r * 0.4, cy - r * 0.05), 3)
    pygame.draw.circle(s, LEAF, (int(cx - r * 0.4), int(cy - r * 0.25)), int(r * 0.35))
    for k in range(2):
        y = cy - r * 0.2 + k * r * 0.35
        pygame.draw.line(s, INK, (cx + r * 0.15, y), (cx + r * 0.75, y), 1)


ICONS = {"stone": _stone, "speaker": _speaker, "cross": _cross, "sun": _sun, "clock": _clock, "can": _can,
         "sapling": _sapling, "seed": _seed, "card": _card,
         "pencil": _pencil, "gear": _gear, "book": _book, "back": _back}
