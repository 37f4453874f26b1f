"""FXAA for a software GL (assets/shaders/fxaa.frag): the frame drawn into a picture of its own, then
copied to the screen with the trees' part of it smoothed along its edges.

Multisampling costs a software GL (Mesa llvmpipe) a whole frame, so without it thin twigs step and break
into dotted lines and leaf cards have jagged edges. The pass finds the local luminance edge of each pixel
and blends along it (FXAA's idea, made of exact texel reads: see the shader). Only the pixels around the
trees go through it (the sky and ground have no hard edges), the rest is copied.
"""

from __future__ import annotations

import moderngl
import numpy as np

from arbor.game.render.backdrop import program


class Fxaa:
    """An off-screen frame (colour texture and depth) and the FXAA pass that puts it on the screen."""

    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self.prog = program(ctx, "fxaa.vert", "fxaa.frag")
        tri = ctx.buffer(np.array([-1, -1, 3, -1, -1, 3], dtype="f4").tobytes())
        self.quad = ctx.vertex_array(self.prog, [(tri, "2f", "in_pos")])
        self.fbo: moderngl.Framebuffer | None = None
        self.color_fbo: moderngl.Framebuffer | None = None  # the same picture without its depth

    def target(self, size: tuple[int, int]) -> moderngl.Framebuffer:
        """The framebuffer to draw the frame into (``size`` pixels, with depth)."""
        if self.fbo is None or self.fbo.size != size:
            self.release()
            color = self.ctx.texture(size, 4)
            color.filter = (moderngl.LINEAR, moderngl.LINEAR)
            color.repeat_x = color.repeat_y = False
            depth = self.ctx.depth_renderbuffer(size)
            self.fbo = self.ctx.framebuffer(color_attachments=[color], depth_attachment=depth)
            self.color_fbo = self.ctx.framebuffer(color_attachments=[color])
        return self.fbo

    def resolve(self, into: moderngl.Framebuffer, size: tuple[int, int],
                rect: tuple[int, int, int, int] | None) -> None:
        """The frame drawn into :meth:`target` onto ``into``: copied, and smoothed within ``rect`` (x, y
        from the bottom, width, height; None: all of it)."""
        ctx = self.ctx
        if rect is not None:  # a window's own framebuffer takes no depth from ours (GL_INVALID_OPERATION: the
            # whole copy would fail and the screen keep old pixels outside ``rect``): colour alone there
            ctx.copy_framebuffer(into, self.fbo if into.depth_attachment is not None else self.color_fbo)
        into.use()  # (what is drawn next goes over the frame: the HUD)
        if rect is not None and (rect[2] <= 0 or rect[3] <= 0):
            return
        ctx.viewport = (0, 0, *size)
        ctx.scissor = rect
        ctx.disable(moderngl.BLEND)
        masked = rect is not None and into.depth_attachment is not None
        if masked:  # only where the trees are: the copy brought their depth along, the backdrop's is 1
            ctx.enable(moderngl.DEPTH_TEST)
            ctx.depth_func = ">"
            into.depth_mask = False
            into.use()
        else:
            ctx.disable(moderngl.DEPTH_TEST)
        self.fbo.color_attachments[0].use(location=0)
        self.prog["u_tex"].value = 0
        self.quad.render()
        ctx.scissor = None
        if masked:
            ctx.depth_func = "<"
            into.depth_mask = True
            into.use()

    def release(self) -> None:
        """Free the off-screen frame."""
        if self.fbo is not None:
            for attachment in (*self.fbo.color_attachments, self.fbo.depth_attachment):
                attachment.release()
            self.fbo.release()
            self.color_fbo.release()
            self.fbo = self.color_fbo = None
