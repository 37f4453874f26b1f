"""The trees drawn at a reduced resolution and laid over the full-size frame (software GL only)."""

from __future__ import annotations

import moderngl
import numpy as np

from game.render.backdrop import program
from game.render.camera import OrbitCamera, project_points

MIN_SCALE = 0.5  # never coarser than half the frame's resolution


class TreeLayer:
    """An off-screen picture of the trees (colour with alpha, and depth) at a fraction of the frame's
    size, composited over the frame with bilinear filtering: on a software GL the leaves' pixels are
    most of a big tree's frame, and a picture at half the size has a quarter of them. Its alpha edges
    come out soft, like antialiasing."""

    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self.prog = program(ctx, "overlay.vert", "overlay.frag")
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
        self.fbo.use()
        self.ctx.viewport = (0, 0, *small)
        self.fbo.clear(0.0, 0.0, 0.0, 0.0, depth=1.0)
        return small

    def composite(self, target: moderngl.Framebuffer, size: tuple[int, int],
                  rect: tuple[int, int, int, int] | None = None) -> None:
        """Lay the layer over ``target``, only within ``rect`` (x, y from the bottom, width, height)
        when given (its colours are premultiplied: drawn pixels have alpha 1)."""
        target.use()
        self.ctx.viewport = (0, 0, *size)
        self.ctx.scissor = rect
        self.fbo.color_attachments[0].use(location=0)
        self.prog["u_tex"].value = 0
        self.ctx.disable(moderngl.DEPTH_TEST)
        self.ctx.enable(moderngl.BLEND)
        self.ctx.blend_func = moderngl.ONE, moderngl.ONE_MINUS_SRC_ALPHA
        self.quad.render()
        self.ctx.disable(moderngl.BLEND)
        self.ctx.scissor = None

    def release(self) -> None:
        """Free the off-screen picture."""
        if self.fbo is not None:
            for attachment in (*self.fbo.color_attachments, self.fbo.depth_attachment):
                attachment.release()
            self.fbo.release()
            self.fbo = None


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
