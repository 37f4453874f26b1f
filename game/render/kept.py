"""The backdrop a software GL keeps as pictures (game/render/stage.py), brought up to date a part at a time.

The *ground* picture holds the sky, the ground and what covers it (the grass), unshaded; the *shown*
picture, which the frames copy, is a copy of it darkened by the trees' shadows. The ground and the grass
write their depth in the ground picture (with the test 'always', so they look as drawn without one);
the sky lies on the far plane. So each part can be drawn again alone:

- the sky (the sun moved, the clouds drifted): into the ground picture where the depth is the far
  plane's (the ground and the grass keep their pixels);
- the ground or the grass (the sun's light on them changed): into the ground picture, over themselves;
- the shadows (a new shadow map, or any part changed): the ground picture copied into the shown one and
  darkened by the shadow pass.

A frame whose camera did not move runs one such part at most (see :meth:`KeptBackdrop.step`), so a sun
moving at the demo's pace costs a frame a few milliseconds now and then, not 15-20 ms at once; what the
camera changes (or the frame's size, the cutaway) is drawn in full in the frame (the ground never lags
the trees).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple

import moderngl


class Looks(NamedTuple):
    """What the backdrop shows, part by part (each a version, see sky_look.LookKey)."""

    view: tuple  # frame size, camera, cutaway, the ground's size, what covers it: a change redraws all of it
    sky: tuple  # the sky's look and the clouds' drift
    ground: int
    cover: int
    shade: int  # how dark the trees' shadows are


class Parts(NamedTuple):
    """Drawing the parts of the backdrop into the framebuffer bound, each ``part(depth)``: with the depth
    test ``depth`` ('<=', '1' for always: writing the depth) or none (None)."""

    sky: Callable[[str | None], None]
    ground: Callable[[str | None], None]
    cover: Callable[[str | None], None] | None  # (None: nothing covers the ground)
    shadows: Callable[[moderngl.Framebuffer], None]  # the trees' shadows darkening the ground in it


class KeptBackdrop:
    """The ground picture and the shown picture, and what each shows (see module docstring)."""

    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self.size: tuple[int, int] | None = None
        self.ground: Looks | None = None  # what the ground picture shows
        self.shown: Looks | None = None  # ... and the shown picture
        self.shadows: tuple | None = None  # the shadow map's version (and filter, trees) the shown one has
        self.pending: list[Callable[[str | None], None]] = []  # the ground picture's parts still to draw
        self.after_sky = False  # (the last part drawn was the sky: the next one is another when one is due)
        self._fbos: tuple = ()

    @property
    def frame(self) -> moderngl.Framebuffer:
        """The shown picture (what a frame copies)."""
        return self._fbos[2]

    @property
    def busy(self) -> bool:
        """Whether a part is due in the next frame the camera holds still."""
        ground, shown = self.ground, self.shown
        return bool(self.pending) or (ground is not None and shown is not None
                                      and ground._replace(shade=0) != shown._replace(shade=0))

    def _make(self, size: tuple[int, int]) -> None:
        if self.size == size:
            return
        self.release()
        ctx = self.ctx
        colour, depth, shown = ctx.renderbuffer(size), ctx.depth_renderbuffer(size), ctx.renderbuffer(size)
        self._fbos = (ctx.framebuffer([colour], depth), ctx.framebuffer([colour]), ctx.framebuffer([shown]),
                      colour, depth, shown)
        self.size, self.ground, self.shown, self.shadows, self.pending = size, None, None, None, []

    def full(self, size: tuple[int, int], looks: Looks, shadows: tuple | None, parts: Parts) -> None:
        """Draw everything now: the ground picture in full (unless it shows ``looks``), copied into the
        shown one, shadowed."""
        self._make(size)
        if self.ground != looks or self.pending:
            ground = self._bind(self._fbos[0])
            ground.clear(depth=1.0)  # (only the depth matters: every pixel is drawn)
            parts.sky(None)
            parts.ground("1")
            if parts.cover is not None:
                parts.cover("1")
            self.ground, self.pending = looks, []
        self._shade(looks, shadows, parts)

    def step(self, looks: Looks, shadows: tuple, parts: Parts) -> None:
        """Bring the pictures a part closer to ``looks`` and ``shadows`` (the camera holds still): a part
        of the ground picture (the sky first), else the shown picture from it."""
        ground, after_sky, self.after_sky = self.ground, self.after_sky, False
        shading = self.shown != ground._replace(shade=looks.shade) or shadows != self.shadows
        if not self.pending and looks.sky != ground.sky and not (after_sky and shading):  # (never starving the rest)
            self._bind(self._fbos[0], depth_mask=False)
            parts.sky("<=")  # (nearer things keep their pixels)
            self._fbos[0].depth_mask = True
            self.ground, self.after_sky = ground._replace(sky=looks.sky), True
            return
        if not self.pending and (looks.ground != ground.ground or looks.cover != ground.cover):
            redraw = [parts.ground] if looks.ground != ground.ground else []
            self.pending = redraw + ([parts.cover] if parts.cover is not None else [])
            self.ground = ground._replace(ground=looks.ground, cover=looks.cover)  # (once they are drawn)
        if self.pending:
            self._bind(self._fbos[0])
            self.pending.pop(0)("1")
            return
        if self.shown != self.ground._replace(shade=looks.shade) or shadows != self.shadows:
            self._shade(self.ground._replace(shade=looks.shade), shadows, parts)

    def current(self, looks: Looks, shadows: tuple) -> bool:
        """Whether the shown picture shows ``looks`` with ``shadows``."""
        return self.shown == looks and self.shadows == shadows and not self.pending

    def _shade(self, looks: Looks, shadows: tuple | None, parts: Parts) -> None:
        """The shown picture: the ground picture, darkened by the trees' shadows."""
        self.ctx.copy_framebuffer(self._fbos[2], self._fbos[1])
        parts.shadows(self._fbos[2])
        self.shown, self.shadows = looks, shadows

    def _bind(self, fbo: moderngl.Framebuffer, depth_mask: bool = True) -> moderngl.Framebuffer:
        fbo.depth_mask = depth_mask
        fbo.use()
        self.ctx.viewport = (0, 0, *self.size)
        return fbo

    def release(self) -> None:
        """Free the pictures."""
        for obj in self._fbos:
            obj.release()
        self._fbos, self.size = (), None
