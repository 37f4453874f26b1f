"""The trees drawn at a reduced resolution and laid over the full-size frame (software GL only), and
over a few frames while the camera holds still (:class:`Pictures`)."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import moderngl
import numpy as np

from arbor.game.render.backdrop import program
from arbor.game.render.camera import OrbitCamera, project_points

MIN_SCALE = 0.5  # never coarser than half the frame's resolution
REUSE_PIXELS = 1.5  # a picture is shown while the camera keeps every corner of the trees this close
MAX_AGE = 16  # frames (or four times a picture's steps): one begun longer ago is redrawn whole (when restarts
# keep a new one from finishing)
LOOK_JUMP = 0.1  # a number of how the trees are coloured that moves more than this redraws a picture at once
Step = tuple[Callable[[], None], bool]  # something to draw, and whether it draws into the picture


class TreeLayer:
    """An off-screen picture of the trees (colour with alpha, and depth) at a fraction of the frame's
    size, composited over the frame with bilinear filtering: on a software GL the leaves' pixels are
    most of a big tree's frame, and a picture at half the size has a quarter of them. Its alpha edges
    come out soft, like antialiasing."""

    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self.prog = program(ctx, "overlay.vert", "layer.frag")
        corners = np.array([[-1, -1], [1, -1], [1, 1], [-1, -1], [1, 1], [-1, 1]], "f4")
        self.quad = ctx.vertex_array(self.prog, [(ctx.buffer(corners.tobytes()), "2f", "in_pos")])
        self.fbo: moderngl.Framebuffer | None = None
        self.size = (0, 0)

    def begin(self, size: tuple[int, int], scale: float) -> tuple[int, int]:
        """Bind the layer for a frame of ``size`` at ``scale`` (cleared to transparent); returns its size."""
        small = (max(1, round(size[0] * scale)), max(1, round(size[1] * scale)))
        if self.fbo is None or self.size != small:
            self.release()
            color = self.ctx.texture(small, 4)
            color.filter = (moderngl.LINEAR, moderngl.LINEAR)
            color.repeat_x = color.repeat_y = False
            depth = self.ctx.depth_renderbuffer(small)
            self.fbo = self.ctx.framebuffer(color_attachments=[color], depth_attachment=depth)
            self.size = small
        self.use()
        self.fbo.clear(0.0, 0.0, 0.0, 0.0, depth=1.0)
        return small

    def use(self) -> None:
        """Draw into the layer (as it is: for the next share of a picture drawn over several frames)."""
        self.fbo.use()
        self.ctx.viewport = (0, 0, *self.size)

    def composite(self, target: moderngl.Framebuffer, size: tuple[int, int],
                  rect: tuple[int, int, int, int] | None = None) -> None:
        """Lay the layer over ``target``, only within ``rect`` (x, y from the bottom, width, height)
        when given (its colours are premultiplied: drawn pixels have alpha 1). Where it lays a tree's
        pixel it writes depth (0.5), so that a pass after it can keep to the trees (fxaa.py)."""
        target.use()
        self.ctx.viewport = (0, 0, *size)
        self.ctx.scissor = rect
        self.fbo.color_attachments[0].use(location=0)
        self.prog["u_tex"].value = 0
        self.ctx.enable(moderngl.DEPTH_TEST)
        self.ctx.depth_func = "1"  # (always: the depth is only written)
        self.ctx.enable(moderngl.BLEND)
        self.ctx.blend_func = moderngl.ONE, moderngl.ONE_MINUS_SRC_ALPHA
        self.quad.render()
        self.ctx.disable(moderngl.BLEND)
        self.ctx.depth_func = "<"
        self.ctx.disable(moderngl.DEPTH_TEST)
        self.ctx.scissor = None

    def release(self) -> None:
        """Free the off-screen picture."""
        if self.fbo is not None:
            for attachment in (*self.fbo.color_attachments, self.fbo.depth_attachment):
                attachment.release()
            self.fbo.release()
            self.fbo = None


@dataclass
class _Cycle:
    """A picture being drawn over several frames: the camera and scene it shows, and what is left."""

    key: tuple  # frame size, scale and the trees' views: a change starts the picture again
    vp: np.ndarray  # the camera's view-projection it is drawn with
    steps: list[Step]
    start: int  # the frame it was begun in
    scene: object = None  # the caller's state it shows (camera, sun...)
    look: tuple = ()  # how it colours the trees (the caller's numbers: a jump in one redraws it at once)
    done: int = 0


class Pictures:
    """Big crowns on a software GL drawn over a few frames: the front picture is shown while the back
    one is drawn a step per frame (each step a share of the leaves, the wood, or the shadow map), then
    they swap. Once the camera has moved more than REUSE_PIXELS from the front picture's, a whole
    picture is drawn in the frame (the trees never lag the ground); growth and wind show a frame or
    two late."""

    def __init__(self, ctx: moderngl.Context) -> None:
        self.front, self.back = TreeLayer(ctx), TreeLayer(ctx)
        self.cycle: _Cycle | None = None
        self.shown: _Cycle | None = None  # the cycle that drew the front picture
        self.frame = 0
        self.version = 0  # counts the pictures shown

    def draw(self, size: tuple[int, int], scale: float, vp: np.ndarray, points: np.ndarray, key: tuple,
             steps: Callable[[bool], list[Step]], scene: object = None, look: tuple = ()) -> None:
        """Advance the back picture by a step, or draw a whole picture now when the front one does not
        fit this frame. ``points``: the trees' box corners (to measure how far the camera moved);
        ``key``: what the picture shows (a change starts it again); ``steps(whole)``: the steps of a
        picture from this frame's state (``whole``: all of them in this frame), ``scene`` that state
        (kept with the picture: ``shown.scene``); ``look``: numbers of how the trees are coloured (autumn,
        leaves still on, tints): one that moved more than LOOK_JUMP since the front picture's has the picture
        drawn whole now (a season or a wilt changes slowly while played, but jumps after time away)."""
        self.frame += 1
        key = (size, scale, key)
        shown = self.shown
        # (a picture of many steps is older when the next is shown: its age is counted in pictures' lengths)
        if (shown is None or shown.key[0] != size or self.frame - shown.start > max(MAX_AGE, 4 * len(shown.steps))
                or moved(shown.vp, vp, points, size) > REUSE_PIXELS or _jumped(shown.look, look)):
            self._run(_Cycle(key, vp, steps(True), self.frame, scene, look), size, scale, whole=True)
            return
        cycle = self.cycle
        if cycle is None or cycle.key != key or moved(cycle.vp, vp, points, size) > REUSE_PIXELS:
            cycle = self.cycle = _Cycle(key, vp, steps(False), self.frame, scene, look)
        self._run(cycle, size, scale, whole=False)

    def _run(self, cycle: _Cycle, size: tuple[int, int], scale: float, whole: bool) -> None:
        """Run the cycle's next step (all that are left when ``whole``); swap pictures when it is done."""
        todo = cycle.steps[cycle.done:] if whole else cycle.steps[cycle.done:cycle.done + 1]
        if cycle.done == 0:
            self.back.begin(size, scale)
        for run, into_picture in todo:
            if into_picture:
                self.back.use()
            run()
            cycle.done += 1
        if cycle.done == len(cycle.steps):
            self.front, self.back = self.back, self.front
            self.shown, self.cycle = cycle, None
            self.version += 1

    def composite(self, target: moderngl.Framebuffer, size: tuple[int, int],
                  rect: tuple[int, int, int, int] | None) -> None:
        """Lay the front picture over ``target`` (see :meth:`TreeLayer.composite`)."""
        if self.shown is not None:
            self.front.composite(target, size, rect)

    def release(self) -> None:
        """Free both pictures."""
        self.front.release()
        self.back.release()
        self.cycle = self.shown = None


def _jumped(old: tuple, new: tuple) -> bool:
    """Whether a number of a picture's look moved more than LOOK_JUMP (see Pictures.draw)."""
    return len(old) != len(new) or any(abs(a - b) > LOOK_JUMP for a, b in zip(old, new, strict=True))


def moved(old: np.ndarray, new: np.ndarray, points: np.ndarray, size: tuple[int, int]) -> float:
    """How far (pixels) any of ``points`` lies from where the view-projection ``old`` put it."""
    if old is new or np.array_equal(old, new):
        return 0.0
    ends = []
    for vp in (old, new):
        clip = np.c_[points, np.ones(len(points))] @ vp.T
        if np.any(clip[:, 3] <= 1e-9):
            return math.inf
        ends.append(clip[:, :2] / clip[:, 3:] * (0.5 * np.array(size)))
    return float(np.abs(ends[0] - ends[1]).max())


def screen_rect(camera: OrbitCamera, size: tuple[int, int], boxes: list[tuple[np.ndarray, np.ndarray]],
                margin: float = 0.0) -> tuple[int, int, int, int] | None:
    """The pixels (x, y from the bottom, width, height) the boxes (lo, hi) cover on screen, each
    widened by ``margin`` of its size (leaves reach past the points the bounds come from); None
    (the whole frame) when a box reaches behind the camera."""
    corners = []
    for lo, hi in boxes:
        pad = (np.asarray(hi) - np.asarray(lo)) * margin
        lo, hi = np.asarray(lo) - pad, np.asarray(hi) + pad
        corners += [[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
    if not corners:
        return None
    px = project_points(camera, size, np.array(corners, float))
    if not np.isfinite(px).all():
        return None
    x0, x1 = int(max(np.floor(px[:, 0].min()), 0)), int(min(np.ceil(px[:, 0].max()), size[0]))
    y0, y1 = int(max(np.floor(px[:, 1].min()), 0)), int(min(np.ceil(px[:, 1].max()), size[1]))
    if x1 <= x0 or y1 <= y0:
        return (0, 0, 0, 0)
    return (x0, size[1] - y1, x1 - x0, y1 - y0)
