"""The L-string overlay (Onishi et al. 2003 Fig. 7): the symbols of the modules inside a region, written where
the turtle is when it reaches them. Shape symbols are yellow, transformations (turns, widths,
brackets) red; the text has a fixed pixel size, so it stays readable at any zoom. Modules at one
spot (turns before a piece) read as one row; rows nearest the centre come first and a row that
would overlap a nearer one is left out; at most ``MAX_ROWS`` rows (bounded for huge crowns).
"""

from __future__ import annotations

import numpy as np
import pygame

from arbor.engine.lsystem.lstring import LString
from arbor.engine.modeling.regions import Sphere
from arbor.game.render.camera import OrbitCamera, project_ball, project_points

MAX_ROWS = 160
ROW_SYMBOLS = 10  # symbols shown at one spot before an ellipsis
TRANSFORMATIONS = set("+-&^/\\|!$[]T%")


def draw_symbols(surface: pygame.Surface, font: pygame.font.Font, camera: OrbitCamera, size: tuple[int, int],
                 ls: LString, positions: np.ndarray, region) -> list[tuple[str, float, float, bool]]:
    """Draw the modules' symbols inside ``region`` (anything with ``contains`` and ``center``; a
    sphere's circle is drawn too); returns what was written: (symbol, x, y, is a transformation)."""
    roi = np.asarray(region.center, float)
    distance = np.linalg.norm(positions - roi, axis=1)
    inside = np.flatnonzero(region.contains(positions))
    inside = inside[np.argsort(distance[inside], kind="stable")]
    pixels = project_points(camera, size, positions[inside])
    if isinstance(region, Sphere):
        centre, radius = project_ball(camera, size, roi, region.radius)
        if np.isfinite(centre).all() and np.isfinite(radius):
            pygame.draw.circle(surface, (255, 255, 255, 160), centre, radius, 2)
    ok = np.isfinite(pixels).all(axis=1)
    inside, pixels = inside[ok], pixels[ok]
    _, first, group = np.unique((pixels // 8).astype(np.int64), axis=0, return_index=True, return_inverse=True)
    taken: list[pygame.Rect] = []
    labels: list[tuple[str, float, float, bool]] = []
    for g in np.argsort(first)[:MAX_ROWS]:
        labels += _draw_row(surface, font, ls, inside[group.ravel() == g], pixels[first[g]], taken)
    return labels


def _draw_row(surface, font, ls: LString, modules: np.ndarray, at: np.ndarray, taken: list) -> list:
    symbols = [chr(c) for c in ls.sym[modules[:ROW_SYMBOLS]]] + (["…"] if len(modules) > ROW_SYMBOLS else [])
    images = [font.render(c, True, (255, 80, 70) if c in TRANSFORMATIONS else (255, 235, 120)) for c in symbols]
    width = sum(image.get_width() for image in images)
    rect = pygame.Rect(int(at[0]), int(at[1] - images[0].get_height() / 2), width, images[0].get_height())
    if rect.collidelist(taken) >= 0:
        return []
    taken.append(rect)
    pygame.draw.rect(surface, (0, 0, 0, 110), rect.inflate(4, 2))
    labels, x = [], rect.x
    for symbol, image in zip(symbols, images, strict=True):
        surface.blit(image, (x, rect.y))
        labels.append((symbol, x, float(at[1]), symbol in TRANSFORMATIONS))
        x += image.get_width()
    return labels
