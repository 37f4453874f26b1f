"""FXAA for a software GL (assets/shaders/fxaa.frag): the trees' part of a drawn frame smoothed along its
edges, in place.

Multisampling costs a software GL (Mesa llvmpipe) a whole frame, so without it thin twigs step and break
into dotted lines and leaf cards have jagged edges. The pass finds the local luminance edge of each pixel
and blends along it (FXAA's idea, made of exact texel reads: see the shader). Only the pixels around the
trees go through it (the sky and ground have no hard edges): that part is copied into a texture and
drawn back through the pass.
"""

from __future__ import annotations

import moderngl
import numpy as np

from arbor.game.render.backdrop import program

RIM = 4  # pixels around the smoothed part copied too (the pass reads neighbours)


class Fxaa:
    """The FXAA pass and the texture it reads (a copy of the part of the frame it smooths)."""

    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self.prog = program(ctx, "fxaa.vert", "fxaa.frag")
        tri = ctx.buffer(np.array([-1, -1, 3, -1, -1, 3], dtype="f4").tobytes())
        self.quad = ctx.vertex_array(self.prog, [(tri, "2f", "in_pos")])
        self.color_fbo: moderngl.Framebuffer | None = None  # a copy of the part of the frame the pass reads

    def _picture(self, size: tuple[int, int]) -> moderngl.Framebuffer:
        """The colour texture the pass reads (``size`` pixels)."""
        if self.color_fbo is None or self.color_fbo.size != size:
            self.release()
            color = self.ctx.texture(size, 4)
            color.filter = (moderngl.LINEAR, moderngl.LINEAR)
            color.repeat_x = color.repeat_y = False
            self.color_fbo = self.ctx.framebuffer(color_attachments=[color])
        return self.color_fbo

    def smooth(self, frame: moderngl.Framebuffer, size: tuple[int, int],
               rect: tuple[int, int, int, int] | None) -> None:
        """Smooth the trees' edges in ``frame``, a whole frame already drawn (with the trees' depth), within
        ``rect`` (x, y from the bottom, width, height; None: all of it): that part (and a rim the pass
        reads) is copied into the pass's texture and drawn back through it where the trees are. No
        full-frame copy: a sapling's frame was a tenth copies."""
        ctx = self.ctx
        if rect is not None and (rect[2] <= 0 or rect[3] <= 0):
            return
        picture = self._picture(size)
        if rect is not None:  # (a blit keeps to the scissor box of the framebuffer it writes)
            x, y = max(rect[0] - RIM, 0), max(rect[1] - RIM, 0)
            right, top = min(rect[0] + rect[2] + RIM, size[0]), min(rect[1] + rect[3] + RIM, size[1])
            picture.scissor = (x, y, right - x, top - y)
            picture.use()
        ctx.copy_framebuffer(picture, frame)
        picture.scissor = None
        frame.use()
        ctx.viewport = (0, 0, *size)
        ctx.scissor = rect
        ctx.disable(moderngl.BLEND)
        masked = frame.depth_attachment is not None
        if masked:  # only where the trees are: the backdrop's depth is 1
            ctx.enable(moderngl.DEPTH_TEST)
            ctx.depth_func = ">"
            frame.depth_mask = False
            frame.use()
        else:
            ctx.disable(moderngl.DEPTH_TEST)
        picture.color_attachments[0].use(location=0)
        self.prog["u_tex"].value = 0
        self.quad.render()
        ctx.scissor = None
        if masked:
            ctx.depth_func = "<"
            frame.depth_mask = True
            frame.use()

    def release(self) -> None:
        """Free the pass's texture."""
        if self.color_fbo is not None:
            self.color_fbo.color_attachments[0].release()
            self.color_fbo.release()
            self.color_fbo = None
