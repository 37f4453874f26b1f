"""The game's scene: the garden's trees (instanced, each at its own level of detail), the ground with
their shadows, the sky with the sun, antialiased.

Costs are kept where they must be: the shadow map (1024 texels) is redrawn only when the sun moved or a
tree changed enough; trees far away or small on screen use fewer sides per ring, leave out sub-pixel
twigs and draw fewer, larger leaves; the sky is a dome of vertices. Multisampling (4x) is resolved into
the target framebuffer. On a software GL (no multisampling) each tree keeps to a vertex budget, sky and
ground are drawn once and copied while nothing they show changes, and a crown whose leaves would
cover the screen many times over is drawn at a lower resolution (game/render/layer.py).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import moderngl
import numpy as np

from game.render.backdrop import Backdrop, sky_colors
from game.render.camera import OrbitCamera, look_at, orthographic
from game.render.instanced import LEAF_KEPT, SIDES, TEMPLATE_VERTICES, Detail, InstancedTrees, TreeBuffers, cover_grow
from game.render.layer import MIN_SCALE, TreeLayer, screen_rect
from game.render.renderer import _gl, _load_texture

SHADOW_SIZE = 1024
SHADOW_TURN = math.cos(math.radians(0.75))  # redraw shadows when the sun turned more than this
SHADOW_FRAMES = 30  # ... or at least every this many frames while trees grow
LOD_PIXELS = (520, 260, 120)  # on-screen height (px) above which a tree gets level 0, 1, 2 (else 3)
TWIG_PIXELS = (0.0, 0.1, 0.2, 0.35)  # per level: grown segments of a smaller radius (px) are left out
SUN_STEP = 0.003  # the sky picture is redrawn when the sun moved this far (the disc moves ~3 px at 720 px)
LEAF_PIXELS = 1_000_000  # leaf area (pixels, all layers) above which a software GL draws trees smaller
BARK = (1.45, 1.35, 1.25)
BLOSSOM = (1.2, 0.9, 1.0)


def software_gl(ctx: moderngl.Context) -> bool:
    """True on a CPU renderer (Mesa llvmpipe/softpipe, SwiftShader), where multisampling costs a frame."""
    name = str(ctx.info.get("GL_RENDERER", "")).lower()
    return any(word in name for word in ("llvmpipe", "softpipe", "swiftshader", "software"))


@dataclass
class Placed:
    """A tree in the scene: its buffers and where it stands (x, 0, z)."""

    buffers: TreeBuffers
    offset: np.ndarray
    version: int = 0  # changes when the tree changed enough to need new shadows


class GardenRenderer:
    """Draws placed trees with backdrop and shadows (see module docstring)."""

    def __init__(self, ctx: moderngl.Context, samples: int | None = None) -> None:
        self.ctx = ctx
        self.backdrop = Backdrop(ctx)
        self.trees = InstancedTrees(ctx)
        self.textures = {name: _load_texture(ctx, name, name == "bark") for name in ("bark", "leaf", "blossom")}
        self.shadow_map = ctx.depth_texture((SHADOW_SIZE, SHADOW_SIZE))
        self.shadow_map.compare_func = "<="
        self.shadow_map.filter = (moderngl.LINEAR, moderngl.LINEAR)
        self.shadow_fbo = ctx.framebuffer(depth_attachment=self.shadow_map)
        self.samples = samples if samples is not None else (1 if software_gl(ctx) else 4)
        self.vertex_budget = 60_000 if software_gl(ctx) else 10_000_000  # shaded per tree and frame
        self._msaa: tuple | None = None
        self._shadow_key: tuple | None = None
        self._shadow_age = 0
        self._backdrop_picture: moderngl.Framebuffer | None = None
        self._backdrop_key: tuple | None = None
        self.placed: list[Placed] = []
        self.lo, self.hi = -np.ones(3), np.ones(3)
        self.leaf_tint, self.bark_tint, self.blossom_tint = (1.0, 1.0, 1.0), BARK, BLOSSOM
        self.autumn, self.leaf_keep = 0.0, 1.0  # autumn colour (0..1) and share of leaves still on
        self.wind = np.zeros(3)  # direction x strength (scene units at the outermost twigs)
        self.time = 0.0
        self.last_details: list[Detail] = []
        self.layer = TreeLayer(ctx)
        self.last_scale = 1.0

    def place(self, placed: list[Placed], lo: np.ndarray, hi: np.ndarray) -> None:
        """The trees to draw this frame and the bounds of the one in the middle (for framing)."""
        self.placed = placed
        self.lo, self.hi = np.asarray(lo, float), np.asarray(hi, float)

    def _scene_bounds(self) -> tuple[np.ndarray, float]:
        centres, radius = [], 1.0
        for p in self.placed:
            view = p.buffers.view
            if view is None:
                continue
            lo, hi = np.asarray(view.lo) + p.offset, np.asarray(view.hi) + p.offset
            centres.append((lo + hi) / 2)
            radius = max(radius, float(np.linalg.norm(hi - lo)) / 2)
        if not centres:
            return np.zeros(3), radius
        centre = np.mean(centres, axis=0)
        spread = max(float(np.linalg.norm(c - centre)) for c in centres)
        return centre, radius + spread

    def light_matrix(self, sun: np.ndarray) -> np.ndarray:
        """Orthographic sun view covering every tree and the shadows it casts."""
        centre, radius = self._scene_bounds()
        reach = radius * (1.2 + 1.0 / max(float(sun[1]), 0.35))
        focus = np.array([centre[0], centre[1] * 0.5, centre[2]])
        return orthographic(reach, 0.01, reach * 4) @ look_at(focus + sun * reach * 2, focus)

    def _detail(self, buffers: TreeBuffers, offset: np.ndarray, camera: OrbitCamera, height_px: int) -> Detail:
        """The level of detail by the tree's size on screen (sides per ring, and grown twigs under a
        fraction of a pixel left out), coarser while the vertices it would shade exceed the budget;
        at the coarsest level the thinnest segments and a share of the leaves go until it fits."""
        view = buffers.view
        size = float(np.linalg.norm(np.asarray(view.hi) - np.asarray(view.lo)))
        per_pixel = self._per_pixel(buffers, offset, camera, height_px)
        lod = next((k for k, limit in enumerate(LOD_PIXELS) if size / per_pixel >= limit), len(SIDES) - 1)
        detail = Detail.of(buffers, lod, TWIG_PIXELS[lod] * per_pixel, LEAF_KEPT[lod])
        while detail.vertices(buffers) > self.vertex_budget and detail.lod < len(SIDES) - 1:
            lod = detail.lod + 1
            detail = Detail.of(buffers, lod, TWIG_PIXELS[lod] * per_pixel, LEAF_KEPT[lod])
        if detail.vertices(buffers) > self.vertex_budget:
            detail = self._squeezed(buffers, detail)
        if self.samples > 1:
            return detail
        natural = buffers.leaf_area * detail.leaf_share / per_pixel**2  # pixels of the drawn leaves, life size
        cap = math.sqrt(LEAF_PIXELS / MIN_SCALE**2 / max(natural, 1.0))  # (all their layers together)
        return replace(detail, leaf_grow=min(detail.leaf_grow, max(cap, 1.0)))

    def _squeezed(self, buffers: TreeBuffers, detail: Detail) -> Detail:
        """``detail`` at the coarsest level and still over the budget: the thinnest grown segments and
        a share of the grown leaves left out until it fits."""
        lod = detail.lod
        fixed = Detail(lod).vertices(buffers)  # young parts, blossoms, fruit: always drawn
        leaves = min(detail.leaves, max(self.vertex_budget - fixed, 0) // 8)  # half the rest for leaves
        share = float(buffers.hashes[leaves]) if leaves < len(buffers.hashes) else detail.leaf_share
        room = (self.vertex_budget - fixed - 4 * leaves) // TEMPLATE_VERTICES[lod]  # the rest for wood
        share, tubes = min(share, detail.leaf_share), min(detail.tubes, max(room, 0))
        thinnest = float(buffers.radii[tubes - 1]) if 0 < tubes < len(buffers.radii) else detail.thinnest
        return Detail(lod, tubes, leaves, share, cover_grow(share), max(thinnest, detail.thinnest))

    def render(self, fbo: moderngl.Framebuffer, camera: OrbitCamera, sun_dir: np.ndarray,
               size: tuple[int, int]) -> None:
        """Draw the scene into ``fbo`` (``size`` pixels)."""
        ctx = self.ctx
        sun = np.asarray(sun_dir, float) / np.linalg.norm(sun_dir)
        light = self.light_matrix(sun)
        vp = camera.projection(size[0] / size[1]) @ camera.view()
        details = [self._detail(p.buffers, p.offset, camera, size[1]) if p.buffers.view else Detail(3)
                   for p in self.placed]
        self.last_details = details
        self._shadows(light, sun, details)
        target = self._target(fbo, size)
        target.use()
        ctx.viewport = (0, 0, *size)
        day = sky_colors(sun)[2]
        # The sky dome and the ground cover every pixel, behind everything: drawn first without any
        # depth test (only the trees need depth), after a depth-only clear. On a software GL the depth
        # test and write of a full-screen background cost as much as shading it.
        ctx.disable(moderngl.DEPTH_TEST | moderngl.CULL_FACE)
        mvp, light_bytes = _gl(vp), _gl(light)
        pixel = 2.0 * math.tan(math.radians(camera.fov_y) / 2) / size[1]
        radius = self._scene_bounds()[1]
        self._background(target, size, vp, camera, sun, radius)
        target.color_mask = (False, False, False, False)
        target.clear(depth=1.0)
        target.color_mask = (True, True, True, True)
        target.use()  # (the mask takes effect when the framebuffer is bound)
        self.shadow_map.use(location=1)
        boxes = [(np.asarray(p.buffers.view.lo) + p.offset, np.asarray(p.buffers.view.hi) + p.offset)
                 for p in self.placed if p.buffers.view is not None]
        pad = np.array([1.5, 0.0, 1.5])  # leaves reach past the points the bounds were taken from
        self.backdrop.draw_shadows(mvp, light_bytes, sun, [(lo - pad, hi + pad) for lo, hi in boxes])
        uniforms = self._lit_uniforms(mvp, light_bytes, sun, day)
        self.last_scale = scale = self._scale(details, camera, size[1])
        if scale < 1.0:
            self.layer.begin(size, scale)
        ctx.enable(moderngl.DEPTH_TEST)
        uniforms.update(u_eye=tuple(camera.eye), u_pixel=pixel / scale)
        for placed, detail in zip(self.placed, details, strict=True):
            uniforms["u_offset"] = tuple(placed.offset)
            self.trees.draw(placed.buffers, "lit", detail, uniforms, self.textures)
        if scale < 1.0:
            self.layer.composite(target, size, screen_rect(camera, size, boxes, margin=0.15))
        if target is not fbo:
            ctx.copy_framebuffer(fbo, target)

    def _scale(self, details: list[Detail], camera: OrbitCamera, height_px: int) -> float:
        """The resolution the trees are drawn at: the whole frame's, or on a software GL less when
        their leaves would cover the screen many times over (their pixels are the frame's cost)."""
        if self.samples > 1:
            return 1.0
        pixels = sum(p.buffers.leaf_area * d.leaf_share * d.leaf_grow**2
                     / self._per_pixel(p.buffers, p.offset, camera, height_px) ** 2
                     for p, d in zip(self.placed, details, strict=True) if p.buffers.view is not None)
        return min(max(math.sqrt(LEAF_PIXELS / max(pixels, 1.0)), MIN_SCALE), 1.0)

    @staticmethod
    def _per_pixel(buffers: TreeBuffers, offset: np.ndarray, camera: OrbitCamera, height_px: int) -> float:
        """The size of a pixel (scene units) at the distance of the tree standing at ``offset``."""
        view = buffers.view
        centre = (np.asarray(view.lo) + np.asarray(view.hi)) / 2 + offset
        distance = max(float(np.linalg.norm(centre - camera.eye)), 1e-3)
        return 2 * distance * math.tan(math.radians(camera.fov_y) / 2) / height_px

    def _background(self, target: moderngl.Framebuffer, size: tuple[int, int], vp: np.ndarray,
                    camera: OrbitCamera, sun: np.ndarray, radius: float) -> None:
        """Sky, sun disc and ground into ``target``. Without multisampling (a software GL, where they
        cost more than half a sapling's frame) they are drawn into a picture of their own and copied
        from it while the camera, the sun (to SUN_STEP) and the ground's size stay the same."""
        key = (size, _gl(vp), tuple(np.round(sun / SUN_STEP)), self.backdrop.cutaway,
               round(math.log(max(radius, 1e-3)) / 0.02))  # (the ground's size in 2 % steps)
        if self.samples <= 1:
            if self._backdrop_picture is None or self._backdrop_picture.size != size:
                if self._backdrop_picture is not None:
                    self._backdrop_picture.release()
                self._backdrop_picture = self.ctx.framebuffer(color_attachments=[self.ctx.renderbuffer(size)])
                self._backdrop_key = None
            if key == self._backdrop_key:
                self.ctx.copy_framebuffer(target, self._backdrop_picture)
                return
            self._backdrop_key = key
            draw_into = self._backdrop_picture
        else:
            draw_into = target
        draw_into.use()
        self.ctx.viewport = (0, 0, *size)
        self.backdrop.draw_sky(vp, camera.eye, camera.distance * 20.0, sun)
        self.backdrop.set_ground(max(radius, 1.0) * 12)
        self.backdrop.draw_ground(_gl(vp), sun, (radius * 3, radius * 11))
        if draw_into is not target:
            self.ctx.copy_framebuffer(target, draw_into)

    def _target(self, fbo: moderngl.Framebuffer, size: tuple[int, int]) -> moderngl.Framebuffer:
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

    def _lit_uniforms(self, mvp: bytes, light: bytes, sun: np.ndarray, day: float) -> dict:
        zenith, _, _ = sky_colors(sun)
        elevation = max(float(sun[1]), 0.0)
        strength = min(elevation * 4.0, 1.0)
        sun_color = (1.05 * (0.4 + 0.6 * elevation) * strength, 0.98 * (0.4 + 0.6 * elevation) * strength,
                     0.85 * strength)
        centre, radius = self._scene_bounds()
        return {"u_mvp": mvp, "u_light_mvp": light, "u_shadow": 1, "u_shadow_texel": 1.0 / SHADOW_SIZE,
                "u_sun_dir": tuple(sun), "u_sun_color": sun_color,
                "u_sky_color": tuple(c * (1.0 + 1.2 * (1.0 - day)) for c in zenith),  # moonlit: always visible
                "u_ground_color": tuple(c * max(day, 0.35) for c in (0.30, 0.28, 0.18)),
                "u_crown_center": tuple(centre + np.array([0.0, radius * 0.25, 0.0])), "u_crown_radius": radius,
                "u_wind": (*self.wind, self.time), "u_autumn": self.autumn, "u_keep": self.leaf_keep,
                "tints": (self.bark_tint, self.leaf_tint, self.blossom_tint)}

    def _shadows(self, light: np.ndarray, sun: np.ndarray, details: list[Detail]) -> None:
        """Redraw the shadow map if the sun turned, a tree changed, or it is simply old."""
        versions = (*((id(p.buffers.view), p.version) for p in self.placed), round(self.leaf_keep, 2))
        old = self._shadow_key
        self._shadow_age += 1
        if (old is not None and old[1] == versions and float(np.dot(old[0], sun)) > SHADOW_TURN
                and self._shadow_age < SHADOW_FRAMES):
            return
        self._shadow_key, self._shadow_age = (sun, versions), 0
        ctx = self.ctx
        self.shadow_fbo.use()
        ctx.viewport = (0, 0, SHADOW_SIZE, SHADOW_SIZE)
        self.shadow_fbo.clear(depth=1.0)
        ctx.enable(moderngl.DEPTH_TEST)
        uniforms = {"u_mvp": _gl(light), "u_light_mvp": _gl(light), "u_wind": (*self.wind, self.time),
                    "u_eye": (0.0, 0.0, 0.0), "u_pixel": 0.0, "u_keep": self.leaf_keep}
        for placed, detail in zip(self.placed, details, strict=True):
            uniforms["u_offset"] = tuple(placed.offset)
            coarser = replace(detail, lod=min(detail.lod + 1, len(SIDES) - 1))
            self.trees.draw(placed.buffers, "shadow", coarser, uniforms, self.textures)

    def release(self) -> None:
        """Free the trees' buffers (GL objects of the renderer itself live with the context)."""
        for placed in self.placed:
            placed.buffers.release()
        self.placed = []
