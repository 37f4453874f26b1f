"""Trees rendered at one shared scale with a metre bar, so pictures of different trees can be compared.

Every tree is framed in the same box (``frame`` metres high round the trunk: the renderer's
:func:`~arbor.game.render.renderer.shared_camera`), so a tree twice as tall stands twice as high in the
picture; the bar stands upright at the left edge, as long as a whole number of metres (1 m unless the
frame is tall) measured at the trunk by projecting the scene's metre (engine/base/units.py METRE).
"""

from __future__ import annotations

import math

import numpy as np

from arbor.engine.base.units import METRE
from arbor.game.render.camera import project_points
from arbor.game.render.renderer import render_image, shared_camera

BAR_RGB = (255, 255, 255)  # the bar's fill (outlined in black): pure white, which the sky never is
NICE = (1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1000.0)


def bar_metres(frame: float) -> float:
    """The bar's length (m) for a frame ``frame`` m high: the longest of 1, 2, 5, 10, ... m up to 40 % of it
    (1 m for any frame under 5 m)."""
    return max([n for n in NICE if n <= 0.4 * frame] or [1.0])


def frame_for(height_m: float) -> float:
    """The frame (m) a lone tree of ``height_m`` metres is rendered in: its height rounded up to a whole
    metre (at least 1), so trees of similar size share a scale."""
    return float(max(math.ceil(height_m - 1e-9), 1))


def bar_pixels(frame: float, size: tuple[int, int], yaw: float, pitch: float) -> tuple[float, float, float]:
    """(x of the trunk, y of the ground at the trunk, pixels per metre there) in a picture of ``size``
    rendered at the shared scale of ``frame`` metres."""
    camera = shared_camera(frame * METRE, size, yaw, pitch)
    base, top = project_points(camera, size, np.array([[0.0, 0.0, 0.0], [0.0, METRE, 0.0]]))
    return float(base[0]), float(base[1]), float(base[1] - top[1])


def draw_bar(pixels: np.ndarray, frame: float, yaw: float, pitch: float) -> np.ndarray:
    """``pixels`` (H, W, 3, a picture rendered at the shared scale of ``frame`` m) with the metre bar
    drawn upright near the left edge from the ground line, labelled with its length."""
    import pygame

    height, width = pixels.shape[:2]
    _, ground, per_metre = bar_pixels(frame, (width, height), yaw, pitch)
    metres = bar_metres(frame)
    length = round(metres * per_metre)
    thick = max(3, width // 120)
    x, bottom = max(8, width // 25), round(min(ground, height - 4))
    surf = pygame.surfarray.make_surface(np.ascontiguousarray(pixels.swapaxes(0, 1)))
    pygame.draw.rect(surf, (0, 0, 0), (x - 2, bottom - length - 2, thick + 4, length + 4))
    pygame.draw.rect(surf, BAR_RGB, (x, bottom - length, thick, length))
    if not pygame.font.get_init():
        pygame.font.init()
    font = pygame.font.Font(None, max(16, height // 15))
    label = font.render(f"{metres:g} m", True, (20, 20, 20), (235, 235, 235))
    surf.blit(label, (x + thick + 6, bottom - length))
    return pygame.surfarray.array3d(surf).swapaxes(0, 1).copy()


def render_to_scale(mesh, size: tuple[int, int], frame: float, yaw: float = 30.0, pitch: float = 12.0,
                    ctx=None, samples: int = 4) -> np.ndarray:
    """A tree rendered at the shared scale of ``frame`` metres, with the metre bar."""
    pixels = render_image(mesh, size, yaw=yaw, pitch=pitch, ctx=ctx, frame_height=frame * METRE, samples=samples)
    return draw_bar(pixels, frame, yaw, pitch)
