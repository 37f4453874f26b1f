"""How the backdrop looks, in 8-bit levels of its colours: a software GL keeps the sky and the ground as a
picture (game/render/stage.py) and redraws it once something it shows changed by a level (or its sun's
disc moved a few pixels), not at every small step of the sun. At the demo's pace the sun moves a step
(0.003 radians) every three or four frames, but away from its disc and glow the sky and the ground
take twenty frames or more to change by a level: redrawing them (13 ms of a 20 ms frame on llvmpipe) at
every step made the slow frames, and the picture did not change.

The colours are those the shaders compute (assets/shaders/dome.vert, ground_plain.*, cloud.frag,
sun.frag, stars.frag), here for the dome's vertices in view, the ground, clouds, stars and discs.
"""

from __future__ import annotations

import math

import numpy as np

from arbor.game.render.backdrop import FAR_HAZE, HORIZON_HAZE, MOON, far_ground, ground_color, sky_colors
from arbor.game.render.camera import OrbitCamera

LEVEL = 1.0  # a picture is stale once a colour it shows changed by this many 8-bit levels
DISC_PIXELS = 3.0  # ... or the sun's or the moon's disc moved this many pixels
GLOW = (1.0, 0.85, 0.55)  # the sun's glow in the dome (dome.vert's u_glow by day)


def sky_look(dirs: np.ndarray, sectors: int, camera: OrbitCamera, vp: np.ndarray, sun: np.ndarray,
             size: tuple[int, int], ground: tuple[float, float, float],
             drift: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """What the backdrop shows under ``sun`` through ``camera``'s view-projection ``vp``,
    in 8-bit levels: the sky (its colour at each of the dome's unit directions ``dirs``, rings of
    ``sectors``, NaN where out of view; the clouds' and the stars' light and the clouds' ``drift``;
    where the sun's and the moon's discs are, in steps of DISC_PIXELS, and the sun's colour, NaN when
    out of view), the pixels each of the sky's values colours (x0, y0, x1, y1 from the bottom left; NaN:
    all of the sky) and the ground (its colour and the horizon's it fades into)."""
    eye, fov_y = np.asarray(camera.eye, float), camera.fov_y
    zenith, horizon, day = sky_colors(sun)
    zenith, horizon, sun = np.array(zenith), np.array(horizon), np.asarray(sun, float)
    t = np.clip(dirs[:, 1], 0.0, 1.0) ** 0.6
    s = np.maximum(dirs @ sun, 0.0)
    dome = horizon + (zenith - horizon) * t[:, None] + np.outer(s**40 * 0.5 + s**5 * 0.1, np.array(GLOW) * day)
    dome[dirs[:, 1] < -0.001] = far_ground(sun, ground, FAR_HAZE * HORIZON_HAZE)  # (below the horizon)
    seen, cells = _geometry(dirs, sectors, vp, eye, size)
    dome[~seen] = np.nan
    night = 1.0 - day if day < 0.999 else 0.0
    light = horizon * (1.0 - day) + day * np.array((1.0, 0.99, 0.96))
    shade, alpha = 0.6 * horizon + 0.15 * day, 0.35 + 0.57 * day
    low = float(np.clip(sun[1] * 3.0, 0.0, 1.0))
    reach = 0.06 * size[1] / math.radians(fov_y) + 2.0  # (pixels: a disc's glow square, half its side)
    sun_px, moon_px = (_pixel(toward, vp, eye, size, reach) for toward in (sun, -sun))
    disc = np.array((1.0, 0.75 + 0.2 * low, 0.45 + 0.4 * low)) * (sun[1] > -0.05) + sun_px[0] * 0.0  # (NaN: unseen)
    everywhere = np.concatenate([light * alpha, shade * alpha, [alpha, night], np.array(MOON) * night]) * 255.0
    sky = np.concatenate([dome.ravel() * 255.0, everywhere, [drift * LEVEL], disc * 255.0,
                          sun_px / DISC_PIXELS * LEVEL, moon_px / DISC_PIXELS * LEVEL])
    discs = [np.tile(np.r_[at - reach, at + reach], (n, 1)) for at, n in ((sun_px, 5), (moon_px, 2))]
    rects = np.concatenate([np.repeat(cells, 3, axis=0), np.full((len(everywhere) + 1, 4), np.nan), discs[0][:3],
                            discs[0][3:], discs[1]])
    return sky, rects, np.concatenate([ground_color(sun, ground), horizon]) * 255.0


_GEOMETRY: list = [None, None]  # (the camera it was worked out for, and what: the sky's pixels move with it)


def _geometry(dirs: np.ndarray, sectors: int, vp: np.ndarray, eye: np.ndarray,
              size: tuple[int, int]) -> tuple[np.ndarray, np.ndarray]:
    """Which of the dome's vertices are in view (with a margin), and the pixels each one's triangles
    colour (see :func:`_cells`), for the camera ``vp`` at ``eye``."""
    key = (vp.tobytes(), tuple(eye), size, len(dirs), sectors)
    if _GEOMETRY[0] != key:
        clip = np.c_[eye + dirs * 100.0, np.ones(len(dirs))] @ vp.T
        w = clip[:, 3]
        seen = (w > 1e-6) & (np.abs(clip[:, 0]) <= 2.0 * w) & (np.abs(clip[:, 1]) <= 2.0 * w)
        px = np.where(w[:, None] > 1e-6, clip[:, :2] / np.maximum(w, 1e-6)[:, None] * 0.5 + 0.5, np.nan)
        _GEOMETRY[:] = [key, (seen, _cells((px * np.array(size)).reshape(-1, sectors, 2)))]
    return _GEOMETRY[1]


def _cells(px: np.ndarray) -> np.ndarray:
    """For each vertex of a grid of screen points (rings x sectors x 2, sectors wrapping round), the box
    (x0, y0, x1, y1) round it and its neighbours: the pixels its triangles colour (NaN when one lies
    behind the camera)."""
    rings = px.shape[0]
    near = [px[np.clip(np.arange(rings) + dr, 0, rings - 1)][:, np.roll(np.arange(px.shape[1]), -ds)]
            for dr in (-1, 0, 1) for ds in (-1, 0, 1)]
    stack = np.stack(near)  # (9, rings, sectors, 2)
    lo, hi = stack.min(axis=0), stack.max(axis=0)  # (NaN anywhere: NaN)
    return np.concatenate([lo, hi], axis=-1).reshape(-1, 4)


def _pixel(toward: np.ndarray, vp: np.ndarray, eye: np.ndarray, size: tuple[int, int], reach: float) -> np.ndarray:
    """Where on screen (pixels) the sky in direction ``toward`` is, NaN when no part of a disc there
    ``reach`` pixels wide would be seen."""
    clip = np.append(eye + toward * 100.0, 1.0) @ vp.T
    if clip[3] <= 1e-6:
        return np.full(2, np.nan)
    px = (clip[:2] / clip[3] * 0.5 + 0.5) * np.array(size)
    if np.any(px < -reach) or np.any(px > np.array(size) + reach):
        return np.full(2, np.nan)
    return px


class LookKey:
    """A version of a part of the backdrop's look that changes only once the look changed by LEVEL or
    more from the one drawn (part of the key its picture is kept by); with the pixels each value colours,
    the part of the screen to draw again (:meth:`dirty`)."""

    def __init__(self) -> None:
        self.drawn: np.ndarray | None = None
        self.rects: np.ndarray | None = None
        self.version = 0
        self.due = False  # (a new version was given out and not drawn yet)

    def of(self, look: np.ndarray) -> int:
        """The version for ``look`` (a new one when it differs from the drawn look by LEVEL)."""
        if not self.due and self.differs(look):
            self.version += 1
            self.due = True
        return self.version

    def differs(self, look: np.ndarray) -> bool:
        """Whether ``look`` differs from the drawn look by LEVEL or more where it is seen now (something
        seen now that was not seen then differs)."""
        old = self.drawn
        if old is None or old.shape != look.shape:
            return True
        seen = ~np.isnan(look)
        gap = np.abs(look[seen] - old[seen])
        return bool(np.isnan(gap).any() or (gap.size and gap.max() >= LEVEL))

    def dirty(self, look: np.ndarray, rects: np.ndarray, size: tuple[int, int]) -> tuple[int, int, int, int] | None:
        """The pixels (x, y from the bottom, width, height) where what ``look`` shows differs from the
        drawn look by a LEVEL or more (where it was and where it is now); None: all of them."""
        old = self.drawn
        if old is None or old.shape != look.shape or self.rects is None:
            return None
        changed = (np.abs(look - old) >= LEVEL) | (np.isnan(old) != np.isnan(look))
        boxes = np.concatenate([rects[changed], self.rects[changed]])
        if not len(boxes) or np.isnan(boxes).any():
            return None
        x0, y0 = np.floor(np.maximum(boxes[:, :2].min(axis=0) - 2, 0)).astype(int)
        x1, y1 = np.ceil(np.minimum(boxes[:, 2:].max(axis=0) + 2, size)).astype(int)
        return (int(x0), int(y0), max(int(x1 - x0), 0), max(int(y1 - y0), 0))

    def draw(self, look: np.ndarray, rects: np.ndarray | None = None, rect: tuple[int, int, int, int] | None = None,
             size: tuple[int, int] = (0, 0)) -> None:
        """``look`` was drawn (its values colouring ``rects``), all of it or only within ``rect`` of a frame
        of ``size``."""
        self.due = False
        if rect is None or self.drawn is None or self.drawn.shape != look.shape or rects is None:
            self.drawn, self.rects = look.copy(), rects
            return
        x, y, w, h = rect
        on = np.clip(rects, 0, np.tile(size, 2))  # (what lies off the screen colours nothing)
        empty = (on[:, 2] <= on[:, 0]) | (on[:, 3] <= on[:, 1])
        inside = empty | ((on[:, 0] >= x) & (on[:, 1] >= y) & (on[:, 2] <= x + w) & (on[:, 3] <= y + h))
        self.drawn[inside], self.rects[inside] = look[inside], rects[inside]
