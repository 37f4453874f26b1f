"""What stands behind the garden's trees: sky, sun and ground with the trees' shadows on it, and the
framebuffer a frame is drawn into (multisampled where that is cheap). On a software GL the backdrop is
kept as a picture and copied while nothing it shows changed, and so is the whole scene while the trees
are shown as a layer's picture (game/render/layer.py)."""

from __future__ import annotations

import math

import moderngl
import numpy as np

from arbor.game.render.backdrop import Backdrop
from arbor.game.render.camera import OrbitCamera
from arbor.game.render.layer import Pictures, screen_rect
from arbor.game.render.renderer import _gl
from arbor.game.render.shadows import ShadowMaps

SUN_STEP = 0.003  # the sky picture is redrawn when the sun moved this far (the disc moves ~3 px at 720 px)


class Stage:
    """Sky, ground and shadows behind the trees, and the frame's target (see module docstring)."""

    def __init__(self, ctx: moderngl.Context, backdrop: Backdrop, shadows: ShadowMaps, samples: int) -> None:
        self.ctx, self.backdrop, self.shadows, self.samples = ctx, backdrop, shadows, samples
        self._msaa: tuple | None = None
        self._backdrop_picture: moderngl.Framebuffer | None = None
        self._backdrop_key: tuple | None = None
        self._shaded_picture: moderngl.Framebuffer | None = None  # the backdrop with the trees' shadows
        self._shaded_key: tuple | None = None
        self._scene: moderngl.Framebuffer | None = None  # backdrop and trees' picture (layered frames)
        self._scene_key: tuple | None = None
        self.cover = None  # () -> draws what covers the ground into the backdrop's picture (software GL: grass)
        self.cover_version = 0  # changes when what it draws changed

    def _state(self, size: tuple[int, int], vp: np.ndarray, sun: np.ndarray, radius: float) -> tuple:
        """What the sky and ground picture shows: frame, camera, the sun (to SUN_STEP), the cutaway, the
        clouds' drift, what covers the ground and the ground's size (in 2 % steps)."""
        return (size, _gl(vp), tuple(np.round(sun / SUN_STEP)), self.backdrop.cutaway, self.backdrop.drift,
                self.cover_version, round(math.log(max(radius, 1e-3)) / 0.02))

    def target(self, fbo: moderngl.Framebuffer, size: tuple[int, int]) -> moderngl.Framebuffer:
        """The multisampled framebuffer the scene is drawn into (resolved into ``fbo``)."""
        if self.samples <= 1:
            return fbo
        if self._msaa is None or self._msaa[0] != size:
            if self._msaa is not None:
                self._msaa[1].release()
            color = self.ctx.renderbuffer(size, samples=self.samples)
            depth = self.ctx.depth_renderbuffer(size, samples=self.samples)
            self._msaa = (size, self.ctx.framebuffer(color_attachments=[color], depth_attachment=depth))
        return self._msaa[1]

    def draw(self, target: moderngl.Framebuffer, size: tuple[int, int], vp: np.ndarray, camera: OrbitCamera,
             sun: np.ndarray, light: np.ndarray, boxes: list, radius: float) -> None:
        """Sky, ground and the trees' shadows on it into ``target``, its depth cleared for the trees.

        The sky dome and the ground cover every pixel, behind everything: drawn first without any depth
        test (only the trees need depth), then a depth-only clear. On a software GL the depth test and
        write of a full-screen background cost as much as shading it."""
        ctx = self.ctx
        if self.samples <= 1:  # the picture with the shadows on it, redrawn only when they or it changed
            self._shade(size, vp, camera, sun, light, boxes, radius)
            ctx.copy_framebuffer(target, self._shaded_picture)
            _clear_depth(target)
            return
        target.use()
        ctx.viewport = (0, 0, *size)
        ctx.disable(moderngl.DEPTH_TEST | moderngl.CULL_FACE)
        self._draw_backdrop(target, size, vp, camera, sun, radius)
        _clear_depth(target)
        self._draw_shadows(target, size, vp, sun, light, boxes)

    def _draw_shadows(self, into: moderngl.Framebuffer, size: tuple[int, int], vp: np.ndarray, sun: np.ndarray,
                      light: np.ndarray, boxes: list) -> None:
        """The trees' shadows darkening the ground already in ``into``."""
        into.use()
        self.ctx.viewport = (0, 0, *size)
        self.ctx.disable(moderngl.DEPTH_TEST | moderngl.CULL_FACE)
        self.shadows.texture.use(location=1)
        pad = np.array([1.5, 0.0, 1.5])  # leaves reach past the points the bounds were taken from
        self.backdrop.draw_shadows(_gl(vp), _gl(light), sun, [(lo - pad, hi + pad) for lo, hi in boxes])

    def _shade(self, size: tuple[int, int], vp: np.ndarray, camera: OrbitCamera, sun: np.ndarray,
               light: np.ndarray, boxes: list, radius: float) -> None:
        """Keep the backdrop's picture with the trees' shadows on it (software GL: the shadow test over
        the ground is a third of a sapling's frame). The shadows change only with the shadow map (a new
        version when the sun turned or a tree changed) and with the backdrop: the boxes bound where the
        test runs, not what it shows, so they are not part of the key."""
        self.refresh(size, vp, camera, sun, radius)
        key = (self._backdrop_key, self.shadows.version, self.backdrop.soft, len(boxes))
        self._shaded_picture = self._picture(self._shaded_picture, size)
        if key != self._shaded_key:
            self._shaded_key = key
            self.ctx.copy_framebuffer(self._shaded_picture, self._backdrop_picture)
            self._draw_shadows(self._shaded_picture, size, vp, sun, light, boxes)

    def layered(self, target: moderngl.Framebuffer, size: tuple[int, int], vp: np.ndarray, camera: OrbitCamera,
                sun: np.ndarray, light: np.ndarray, boxes: list, radius: float, pictures: Pictures) -> None:
        """Backdrop and the front picture of the trees laid over it, into ``target``, as they were when
        that picture was begun (camera, sun, shadows): kept as a picture of its own and copied until the
        next picture is shown (the layer's composite is a full-screen pass)."""
        rect = screen_rect(camera, size, boxes, margin=0.15)
        key = (self._state(size, vp, sun, radius), pictures.version, rect)
        self._scene = self._picture(self._scene, size)
        if key != self._scene_key:  # (keys hold the size: a new picture never matches an old key)
            self.draw(target, size, vp, camera, sun, light, boxes, radius)
            pictures.composite(target, size, rect)
            self.ctx.copy_framebuffer(self._scene, target)
            self._scene_key = key
        else:
            self.ctx.copy_framebuffer(target, self._scene)
            _clear_depth(target)  # (as a frame drawn in full leaves it, for what is drawn over it)
        self.ctx.enable(moderngl.DEPTH_TEST)

    def stale(self, size: tuple[int, int], vp: np.ndarray, sun: np.ndarray, radius: float) -> bool:
        """Whether the backdrop's picture does not show this camera, sun and ground."""
        return self._state(size, vp, sun, radius) != self._backdrop_key

    def refresh(self, size: tuple[int, int], vp: np.ndarray, camera: OrbitCamera, sun: np.ndarray,
                radius: float) -> None:
        """Redraw the backdrop's picture (software GL) if it does not show this camera, sun and ground."""
        key = self._state(size, vp, sun, radius)
        self._backdrop_picture = self._picture(self._backdrop_picture, size)
        if key != self._backdrop_key:
            self._backdrop_key = key
            self._draw_backdrop(self._backdrop_picture, size, vp, camera, sun, radius)

    def _picture(self, picture: moderngl.Framebuffer | None, size: tuple[int, int]) -> moderngl.Framebuffer:
        """``picture``, or a new colour framebuffer when there is none of ``size``."""
        if picture is not None and picture.size == size:
            return picture
        if picture is not None:
            picture.release()
        return self.ctx.framebuffer(color_attachments=[self.ctx.renderbuffer(size)])

    def _draw_backdrop(self, into: moderngl.Framebuffer, size: tuple[int, int], vp: np.ndarray,
                       camera: OrbitCamera, sun: np.ndarray, radius: float) -> None:
        into.use()
        self.ctx.viewport = (0, 0, *size)
        self.ctx.disable(moderngl.DEPTH_TEST | moderngl.CULL_FACE)
        self.backdrop.draw_sky(vp, camera.eye, camera.distance * 20.0, sun)
        self.backdrop.set_ground(max(radius, 1.0) * 12)
        self.backdrop.draw_ground(_gl(vp), sun, (radius * 3, radius * 11))
        if self.cover is not None and not self.backdrop.cutaway:
            self.cover()


def _clear_depth(target: moderngl.Framebuffer) -> None:
    """Clear only the depth of ``target`` (its colours stay) and leave it bound."""
    target.color_mask = (False, False, False, False)
    target.clear(depth=1.0)
    target.color_mask = (True, True, True, True)
    target.use()  # (the mask takes effect when the framebuffer is bound)
