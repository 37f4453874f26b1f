"""What stands behind the garden's trees: sky, sun and ground with the trees' shadows on it, and the
framebuffer a frame is drawn into (multisampled where that is cheap). On a software GL the backdrop is
kept as a picture and copied while nothing it shows changed, and so is the whole scene while the trees
are shown as a layer's picture (game/render/layer.py); in a frame whose camera moved it is drawn straight
into the frame (a picture kept for one frame only cost two full-screen copies), the ground first and the
sky only where no ground is."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import moderngl
import numpy as np

from arbor.game.render.backdrop import Backdrop
from arbor.game.render.camera import OrbitCamera
from arbor.game.render.kept import KeptBackdrop, Looks, Parts
from arbor.game.render.layer import Pictures, screen_rect
from arbor.game.render.renderer import _gl
from arbor.game.render.shadows import ShadowMaps
from arbor.game.render.sky_look import LookKey, sky_look


@dataclass
class Scene:
    """What a frame (or a layered picture of the trees) is drawn for: the camera and its view-projection,
    the sun and the light's direction, the trees' bounding boxes and the radius of the scene."""

    camera: OrbitCamera
    vp: np.ndarray
    sun: np.ndarray
    light: np.ndarray
    boxes: list
    radius: float


class Stage:
    """Sky, ground and shadows behind the trees, and the frame's target (see module docstring)."""

    def __init__(self, ctx: moderngl.Context, backdrop: Backdrop, shadows: ShadowMaps, samples: int) -> None:
        self.ctx, self.backdrop, self.shadows, self.samples = ctx, backdrop, shadows, samples
        self._msaa: tuple | None = None
        self.kept = KeptBackdrop(ctx)  # (software GL) the backdrop's pictures, see kept.py
        self._scene: moderngl.Framebuffer | None = None  # backdrop and trees' picture (layered frames)
        self._scene_key: tuple | None = None
        self.cover = None  # () -> draws what covers the ground into the backdrop's picture (software GL: grass)
        self.cover_version = 0  # changes when what it draws changed
        self.cover_look = np.zeros(0)  # how what covers the ground is lit, in 8-bit levels (see sky_look.py)
        self.looks = {part: LookKey() for part in ("sky", "ground", "cover", "shade")}
        self._now: dict[str, np.ndarray] = {}  # the looks of the last state asked for (and the sky's pixels)
        self._rects = np.zeros((0, 4))
        self._inputs: tuple | None = None  # what the sky's look was last worked out for, and that look
        self._sky: tuple = ()
        self._view: tuple | None = None  # the last state's view (frame, camera, cutaway, ground, cover) ...
        self.moved = False  # ... and whether it differed from the one before

    def _state(self, size: tuple[int, int], vp: np.ndarray, camera: OrbitCamera, sun: np.ndarray,
               radius: float) -> Looks:
        """What the sky and ground pictures show, part by part: frame, camera, cutaway, the ground's size
        (in 2 % steps) and what covers it; how the sun lights the sky (and the clouds' drift), the ground,
        the grass and the shadows, each a new version once a colour changed by a level (sky_look.py)."""
        backdrop = self.backdrop
        inputs = (_gl(vp), tuple(camera.eye), tuple(sun), size, backdrop.ground_kind, camera.fov_y, backdrop.drift)
        if inputs != self._inputs:  # (1-2 ms of numpy: the sun moves at a fixed step, a frame in six at 1x)
            self._inputs, self._sky = inputs, sky_look(backdrop.dome_dirs, backdrop.dome_sectors, camera, vp, sun,
                                                        size, backdrop.ground_kind, backdrop.drift)
        sky, rects, ground = self._sky
        shade = np.array([0.45 / (0.45 + 0.55 * max(float(sun[1]), 0.0)) * 255.0 * 0.5])  # (shade.frag, ~0.5)
        self._now = {"sky": sky, "ground": ground, "cover": self.cover_look, "shade": shade}
        self._rects = rects
        view = (size, _gl(vp), backdrop.cutaway, round(math.log(max(radius, 1e-3)) / 0.02), self.cover_version)
        self.moved, self._view = view != self._view, view
        looks = self.looks
        return Looks(view, (looks["sky"].of(sky),), looks["ground"].of(ground), looks["cover"].of(self.cover_look),
                     looks["shade"].of(shade))

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

    def draw(self, target: moderngl.Framebuffer, size: tuple[int, int], scene: Scene, spread: bool = False,
             wait: bool = False) -> None:
        """Sky, ground and the trees' shadows on it into ``target``, its depth cleared for the trees.

        On a software GL they are kept as pictures (see kept.py): with ``spread``, what changed while the
        camera held still is brought up to date a part a frame (none in a frame that ``wait``s: it had
        work enough), else all of it now; a frame of ``spread`` whose view changed since the last draws them
        straight into ``target`` (see :meth:`_moving`). With multisampling the sky dome and the ground cover every
        pixel, behind everything: drawn first without any depth test (only the trees need depth), then a
        depth-only clear."""
        ctx = self.ctx
        if self.samples <= 1:
            looks = self._state(size, scene.vp, scene.camera, scene.sun, scene.radius)
            if spread and self.moved:
                self._moving(target, size, scene)
                return
            self._keep(size, scene, spread, wait, looks)
            ctx.copy_framebuffer(target, self.kept.frame)
            _clear_depth(target)
            return
        target.use()
        ctx.viewport = (0, 0, *size)
        ctx.disable(moderngl.DEPTH_TEST | moderngl.CULL_FACE)
        parts = self._parts(size, scene)
        parts.sky(None)
        parts.ground(None)
        _clear_depth(target)
        parts.shadows(target)

    def _moving(self, target: moderngl.Framebuffer, size: tuple[int, int], scene: Scene) -> None:
        """The backdrop of a frame whose camera moved (software GL), straight into ``target``: the ground
        and what covers it, writing their depth, then the sky where none was written (it lies on the far
        plane), then the shadows; the kept pictures are drawn anew once the camera holds still."""
        target.use()
        self.ctx.viewport = (0, 0, *size)
        target.clear(depth=1.0)  # (only the depth matters: every pixel is drawn)
        parts = self._parts(size, scene, fresh=True)
        parts.ground("1")
        if parts.cover is not None:
            parts.cover("1")
        target.depth_mask = False
        parts.sky("<=")
        target.depth_mask = True
        parts.shadows(target)
        _clear_depth(target)
        self.forget()

    def _keep(self, size: tuple[int, int], scene: Scene, spread: bool, wait: bool, looks: Looks | None = None
              ) -> None:
        """Bring the kept backdrop (software GL) up to date with ``looks`` (default: worked out now): a part
        of it (``spread``, the camera holding still; none when the frame must ``wait``), else all of it."""
        if looks is None:
            looks = self._state(size, scene.vp, scene.camera, scene.sun, scene.radius)
        shadows = (self.shadows.version, self.backdrop.soft, len(scene.boxes))
        kept = self.kept
        if kept.current(looks, shadows):
            return
        parts = self._parts(size, scene)
        if spread and kept.shown is not None and kept.shown.view == looks.view and kept.ground is not None:
            if not wait:
                kept.step(looks, shadows, parts)
        else:
            kept.full(size, looks, shadows, parts)

    @property
    def busy(self) -> bool:
        """Whether the kept backdrop has a part to draw in the next frame the camera holds still."""
        return self.kept.busy

    def forget(self) -> None:
        """Draw the backdrop in full next time (as a fresh game would)."""
        self.kept.ground = self.kept.shown = None

    def _parts(self, size: tuple[int, int], scene: Scene, fresh: bool = False) -> Parts:
        """Drawing the backdrop's parts for this camera and sun (see kept.Parts); each tells the look it
        drew (sky_look.LookKey), the sky again only where it changed when drawn over the ground (all of it
        when ``fresh``: into a frame, not a kept picture)."""
        ctx, backdrop, looks, now, rects = self.ctx, self.backdrop, self.looks, dict(self._now), self._rects
        vp, camera, sun, radius = scene.vp, scene.camera, scene.sun, scene.radius
        light, boxes = scene.light, scene.boxes

        def part(name: str, draw: Callable[[], None]) -> Callable[[str | None], None]:
            def run(depth: str | None) -> None:
                ctx.disable(moderngl.CULL_FACE)
                if depth is None:
                    ctx.disable(moderngl.DEPTH_TEST)
                else:
                    ctx.enable(moderngl.DEPTH_TEST)
                    ctx.depth_func = depth
                look = now.get(name)  # (None: not kept, multisampled)
                again = name == "sky" and depth and look is not None and not fresh
                rect = looks[name].dirty(look, rects, size) if again else None
                ctx.scissor = rect
                draw()
                ctx.scissor = None
                ctx.depth_func = "<"
                ctx.disable(moderngl.DEPTH_TEST)
                if look is not None:
                    looks[name].draw(look, rects if name == "sky" else None, rect, size)
            return run

        def ground() -> None:
            backdrop.set_ground(max(radius, 1.0) * 12)
            backdrop.draw_ground(_gl(vp), sun, (radius * 3, radius * 11), np.asarray(camera.eye, float))

        def shadows(into: moderngl.Framebuffer) -> None:
            into.use()
            ctx.viewport = (0, 0, *size)
            ctx.disable(moderngl.DEPTH_TEST | moderngl.CULL_FACE)
            self.shadows.texture.use(location=1)
            pad = np.array([1.5, 0.0, 1.5])  # leaves reach past the points the bounds were taken from
            backdrop.draw_shadows(_gl(vp), _gl(light), sun, [(lo - pad, hi + pad) for lo, hi in boxes])
            if "shade" in now:
                looks["shade"].draw(now["shade"])

        cover = self.cover if self.cover is not None and not backdrop.cutaway else None
        sky = part("sky", lambda: backdrop.draw_sky(vp, camera.eye, camera.distance * 20.0, sun))
        return Parts(sky, part("ground", ground), part("cover", cover) if cover is not None else None, shadows)

    def layered(self, target: moderngl.Framebuffer, size: tuple[int, int], scene: Scene, pictures: Pictures,
                smooth: Callable[[moderngl.Framebuffer, tuple | None], None] | None = None) -> None:
        """Backdrop and the front picture of the trees laid over it, into ``target``, as they were when
        that picture was begun (camera, sun, shadows): kept as a picture of its own and copied until the
        next picture is shown or the backdrop changed (the layer's composite is a full-screen pass). The
        backdrop follows a part a frame what the camera did not change (see :meth:`draw`). ``smooth``
        (target, rect): a pass over the trees once they are laid over the backdrop (their depth is set
        there: FXAA), run once per picture shown, its result kept with it."""
        rect = screen_rect(scene.camera, size, scene.boxes, margin=0.15)
        self._keep(size, scene, spread=True, wait=False)
        key = (self.kept.shown, self.kept.shadows, pictures.version, rect)
        self._scene = self._picture(self._scene, size)
        if key != self._scene_key:  # (keys hold the size: a new picture never matches an old key)
            self.ctx.copy_framebuffer(target, self.kept.frame)
            _clear_depth(target)
            pictures.composite(target, size, rect)
            if smooth is not None:
                smooth(target, rect)
                _clear_depth(target)
            self.ctx.copy_framebuffer(self._scene, target)
            self._scene_key = key
        else:
            self.ctx.copy_framebuffer(target, self._scene)
            _clear_depth(target)  # (as a frame drawn in full leaves it, for what is drawn over it)
        self.ctx.enable(moderngl.DEPTH_TEST)

    def _picture(self, picture: moderngl.Framebuffer | None, size: tuple[int, int]) -> moderngl.Framebuffer:
        """``picture``, or a new colour framebuffer when there is none of ``size``."""
        if picture is not None and picture.size == size:
            return picture
        if picture is not None:
            picture.release()
        return self.ctx.framebuffer(color_attachments=[self.ctx.renderbuffer(size)])


def _clear_depth(target: moderngl.Framebuffer) -> None:
    """Clear only the depth of ``target`` (its colours stay) and leave it bound."""
    target.color_mask = (False, False, False, False)
    target.clear(depth=1.0)
    target.color_mask = (True, True, True, True)
    target.use()  # (the mask takes effect when the framebuffer is bound)
