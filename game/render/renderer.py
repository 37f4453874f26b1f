"""moderngl tree renderer: sky with a visible sun, shadowed ground, lit bark and alpha-tested leaves.

Works on any moderngl context: a pygame OPENGL window, or a headless EGL context (Mesa llvmpipe in
CI) through :func:`headless_context` and :func:`render_image`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import moderngl
import numpy as np

from arbor.engine.geometry.mesh import Mesh, TreeMesh
from arbor.game.paths import ASSETS
from arbor.game.render.backdrop import speckle_texture
from arbor.game.render.camera import OrbitCamera, look_at, orthographic

SHADOW_SIZE = 2048
SKY_ZENITH = (0.30, 0.52, 0.86)
SKY_HORIZON = (0.78, 0.87, 0.95)
GRASS = (0.33, 0.50, 0.22)
BARK_TINT = (1.45, 1.35, 1.25)
LEAF_TINT = (1.0, 1.0, 1.0)


def daylight(sun: np.ndarray) -> float:
    """Brightness of sky and ambient light: 1 by day, dimming through dusk to 0.45 at night."""
    return 0.45 + 0.55 * float(np.clip((sun[1] + 0.15) / 0.35, 0.0, 1.0))


def _scale(color: tuple[float, float, float], k: float) -> tuple[float, float, float]:
    return (color[0] * k, color[1] * k, color[2] * k)


def headless_context() -> moderngl.Context:
    """A standalone OpenGL 3.3 context through EGL (no display needed)."""
    ctx = moderngl.create_standalone_context(backend="egl", require=330)
    ctx.gc_mode = "auto"  # GL objects are freed with their Python objects (a recovered kiosk leaks nothing)
    return ctx


def _gl(m: np.ndarray) -> bytes:
    return np.ascontiguousarray(m.T, dtype="f4").tobytes()


def _load_texture(ctx: moderngl.Context, name: str, repeat: bool) -> moderngl.Texture:
    import pygame

    surf = pygame.image.load(str(ASSETS / "textures" / f"{name}.png"))
    # every texture RGBA (opaque ones with alpha 1): a software GL builds mipmaps with a shader it compiles
    # once per format, and a second format cost a start another compile (76 ms of CPU on llvmpipe)
    data = pygame.image.tobytes(surf, "RGBA", True)
    tex = ctx.texture(surf.get_size(), 4, data)
    tex.build_mipmaps()
    tex.filter = (moderngl.LINEAR_MIPMAP_LINEAR, moderngl.LINEAR)
    tex.repeat_x = tex.repeat_y = repeat
    return tex


@dataclass
class _Part:
    vao: moderngl.VertexArray
    shadow_vao: moderngl.VertexArray
    buffers: list[moderngl.Buffer]
    texture: moderngl.Texture
    kind: int
    uv_scale: tuple[float, float]


class TreeRenderer:
    """Draws one tree (wood, leaves, blossoms) with sky, ground and a sun shadow map."""

    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self.tree_prog = self._program("tree")
        self.shadow_prog = self._program("shadow")
        self.sky_prog = self._program("sky")
        self.ground_prog = self._program("ground")
        self.textures = {
            "bark": _load_texture(ctx, "bark", True),
            "leaf": _load_texture(ctx, "leaf", False),
            "blossom": _load_texture(ctx, "blossom", False),
        }
        self.noise = speckle_texture(ctx)  # (the game's ground's: soft blotches, not squares of one hash each)
        self.shadow_map = ctx.depth_texture((SHADOW_SIZE, SHADOW_SIZE))
        self.shadow_map.compare_func = "<="
        self.shadow_map.filter = (moderngl.LINEAR, moderngl.LINEAR)
        self.shadow_fbo = ctx.framebuffer(depth_attachment=self.shadow_map)
        tri = ctx.buffer(np.array([-1, -1, 3, -1, -1, 3], dtype="f4").tobytes())
        self.sky_vao = ctx.vertex_array(self.sky_prog, [(tri, "2f", "in_pos")])
        self.parts: list[_Part] = []
        self.center = np.zeros(3)
        self.lo, self.hi = -np.ones(3), np.ones(3)
        self.radius = 1.0
        self.height = 1.0
        self.ground_vao: moderngl.VertexArray | None = None
        self.leaf_tint = LEAF_TINT
        self.bark_tint = BARK_TINT

    def _program(self, name: str) -> moderngl.Program:
        shaders = ASSETS / "shaders"
        return self.ctx.program(
            vertex_shader=(shaders / f"{name}.vert").read_text(),
            fragment_shader=(shaders / f"{name}.frag").read_text(),
        )

    def set_tree(self, tree: TreeMesh) -> None:
        """Upload a tree's meshes (replacing the previous tree)."""
        self.release_tree()
        pts = [m.positions for m in (tree.wood, tree.leaves, tree.blossoms) if len(m.positions)]
        allp = np.concatenate(pts) if pts else np.zeros((1, 3), np.float32)
        lo, hi = allp.min(axis=0).astype(float), allp.max(axis=0).astype(float)
        self.lo, self.hi = lo, hi
        self.center = (lo + hi) / 2
        self.radius = max(float(np.linalg.norm(hi - lo)) / 2, 1e-3)
        self.height = max(float(hi[1]), 1e-3)
        wood_scale = (1.0, 1.0)
        for mesh, tex, kind, scale in ((tree.wood, "bark", 0, wood_scale), (tree.leaves, "leaf", 1, (1.0, 1.0)),
                                       (tree.blossoms, "blossom", 2, (1.0, 1.0))):
            if mesh.n_triangles:
                self.parts.append(self._upload(mesh, self.textures[tex], kind, scale))
        self._make_ground()

    def release_tree(self) -> None:
        """Free the GPU buffers of the current tree."""
        for part in self.parts:
            part.vao.release()
            part.shadow_vao.release()
            for b in part.buffers:
                b.release()
        self.parts = []

    def _upload(self, mesh: Mesh, tex: moderngl.Texture, kind: int, uv_scale) -> _Part:
        ctx = self.ctx
        vbo_p = ctx.buffer(mesh.positions.tobytes())
        vbo_n = ctx.buffer(mesh.normals.tobytes())
        vbo_t = ctx.buffer(mesh.uvs.tobytes())
        ibo = ctx.buffer(mesh.indices.tobytes())
        vao = ctx.vertex_array(
            self.tree_prog, [(vbo_p, "3f", "in_pos"), (vbo_n, "3f", "in_normal"), (vbo_t, "2f", "in_uv")], ibo
        )
        shadow_vao = ctx.vertex_array(self.shadow_prog, [(vbo_p, "3f", "in_pos"), (vbo_t, "2f", "in_uv")], ibo)
        return _Part(vao, shadow_vao, [vbo_p, vbo_n, vbo_t, ibo], tex, kind, uv_scale)

    def _make_ground(self) -> None:
        if self.ground_vao is not None:
            self.ground_vao.release()
        r = self.radius * 12
        ang = np.linspace(0, 2 * np.pi, 97)
        ring = np.stack([np.cos(ang) * r, np.zeros_like(ang), np.sin(ang) * r], axis=1)
        fan = np.concatenate([[[0.0, 0.0, 0.0]], ring]).astype("f4")
        idx = np.stack([np.zeros(96), np.arange(1, 97), np.arange(2, 98)], axis=1).astype("u4")
        vbo = self.ctx.buffer(fan.tobytes())
        ibo = self.ctx.buffer(idx.tobytes())
        self.ground_vao = self.ctx.vertex_array(self.ground_prog, [(vbo, "3f", "in_pos")], ibo)

    def light_matrix(self, sun_dir: np.ndarray) -> np.ndarray:
        """Orthographic sun view-projection that covers the tree and the shadow it casts."""
        sun = sun_dir / np.linalg.norm(sun_dir)
        reach = self.radius * (1.2 + 1.0 / max(float(sun[1]), 0.35))
        center = np.array([self.center[0], self.center[1] * 0.5, self.center[2]])
        eye = center + sun * reach * 2
        return orthographic(reach, 0.01, reach * 4) @ look_at(eye, center)

    def render(self, fbo: moderngl.Framebuffer, camera: OrbitCamera, sun_dir: np.ndarray,
               size: tuple[int, int], viewport: tuple[int, int, int, int] | None = None) -> None:
        """Draw the whole scene into ``fbo`` (shadow pass, sky, ground, tree).

        ``viewport`` (x, y, width, height; GL convention, y from the bottom) draws into part of the
        framebuffer only, so several trees can share a screen; ``size`` is then that part's size.
        """
        ctx = self.ctx
        sun = np.asarray(sun_dir, float) / np.linalg.norm(sun_dir)
        light = self.light_matrix(sun)
        self._shadow_pass(light)
        fbo.use()
        area = viewport or (0, 0, *size)
        fbo.clear(*SKY_HORIZON, 1.0, viewport=area)
        ctx.viewport = area  # after the clear: clearing a part restores the framebuffer's own viewport
        day = daylight(sun)
        vp = camera.projection(size[0] / size[1]) @ camera.view()
        ctx.disable(moderngl.DEPTH_TEST | moderngl.CULL_FACE)
        self.sky_prog["u_inv_vp"].write(_gl(np.linalg.inv(vp)))
        self.sky_prog["u_sun_dir"].value = tuple(sun)
        self.sky_prog["u_zenith"].value = _scale(SKY_ZENITH, day)
        self.sky_prog["u_horizon"].value = _scale(SKY_HORIZON, day)
        self.sky_vao.render()
        ctx.enable(moderngl.DEPTH_TEST)
        self.shadow_map.use(location=1)
        self._draw_ground(vp, light, sun)
        if "u_eye" in self.tree_prog:  # (a leaf is shaded on the side that faces the eye)
            self.tree_prog["u_eye"].value = tuple(camera.eye)
        self._draw_tree(vp, light, sun)

    def _shadow_pass(self, light: np.ndarray) -> None:
        ctx = self.ctx
        self.shadow_fbo.use()
        ctx.viewport = (0, 0, SHADOW_SIZE, SHADOW_SIZE)
        self.shadow_fbo.clear(depth=1.0)
        ctx.enable(moderngl.DEPTH_TEST)
        ctx.disable(moderngl.CULL_FACE)
        self.shadow_prog["u_light_mvp"].write(_gl(light))
        for part in self.parts:
            part.texture.use(location=0)
            self.shadow_prog["u_tex"].value = 0
            self.shadow_prog["u_alpha_test"].value = int(part.kind != 0)
            part.shadow_vao.render()

    @staticmethod
    def _lit_uniforms(prog: moderngl.Program, vp: np.ndarray, light: np.ndarray, sun: np.ndarray) -> None:
        """Camera, sun and shadow-map uniforms shared by the ground and the tree shaders."""
        prog["u_mvp"].write(_gl(vp))
        prog["u_light_mvp"].write(_gl(light))
        prog["u_shadow"].value = 1
        if "u_shadow_texel" in prog:
            prog["u_shadow_texel"].value = 1.0 / SHADOW_SIZE
        prog["u_sun_dir"].value = tuple(sun)

    def _draw_ground(self, vp: np.ndarray, light: np.ndarray, sun: np.ndarray) -> None:
        prog = self.ground_prog
        self._lit_uniforms(prog, vp, light, sun)
        self.noise.use(location=2)
        if "u_noise" in prog:
            prog["u_noise"].value = 2
        prog["u_grass"].value = _scale(GRASS, daylight(sun))
        prog["u_horizon"].value = _scale(SKY_HORIZON, daylight(sun))
        prog["u_fade_start"].value = self.radius * 3
        prog["u_fade_end"].value = self.radius * 11
        assert self.ground_vao is not None
        self.ground_vao.render()

    def _draw_tree(self, vp: np.ndarray, light: np.ndarray, sun: np.ndarray) -> None:
        prog = self.tree_prog
        self._lit_uniforms(prog, vp, light, sun)
        prog["u_tex"].value = 0
        elevation = max(float(sun[1]), 0.0)
        day = daylight(sun)
        sun_strength = min(elevation * 4.0, 1.0)
        prog["u_sun_color"].value = _scale((1.05 * (0.4 + 0.6 * elevation), 0.98 * (0.4 + 0.6 * elevation), 0.85),
                                           sun_strength)
        prog["u_sky_color"].value = _scale(SKY_ZENITH, day)
        prog["u_ground_color"].value = _scale((0.30, 0.28, 0.18), day)
        prog["u_crown_center"].value = tuple(self.center + np.array([0, self.radius * 0.25, 0]))
        prog["u_crown_radius"].value = self.radius
        for part in self.parts:
            part.texture.use(location=0)
            prog["u_kind"].value = part.kind
            prog["u_uv_scale"].value = part.uv_scale
            prog["u_tint"].value = self.bark_tint if part.kind == 0 else self.leaf_tint
            part.vao.render()


class Overlay:
    """The HUD/menu layer: an RGBA texture blended over the scene.

    :meth:`draw_surface` is the cheap path for a pygame surface that changes now and then: only tiles
    with something in them are drawn, and the texture is uploaded only when the caller says it changed
    (on a software GL, blending a full-screen texture every frame costs as much as the whole scene).
    """

    TILE = 64

    def __init__(self, ctx: moderngl.Context, size: tuple[int, int]) -> None:
        self.ctx = ctx
        self.size = size
        shaders = ASSETS / "shaders"
        self.prog = ctx.program(vertex_shader=(shaders / "overlay.vert").read_text(),
                                fragment_shader=(shaders / "overlay.frag").read_text())
        self.tile_prog = ctx.program(vertex_shader=(shaders / "overlay_tiles.vert").read_text(),
                                     fragment_shader=(shaders / "overlay.frag").read_text())
        self.texture = ctx.texture(size, 4)
        quad = ctx.buffer(np.array([-1, -1, 3, -1, -1, 3], dtype="f4").tobytes())
        self.vao = ctx.vertex_array(self.prog, [(quad, "2f", "in_pos")])
        self.tiles = ctx.buffer(reserve=4)
        self.tile_vao = ctx.vertex_array(self.tile_prog, [(self.tiles, "2f", "in_pos")])
        self.tile_vertices = 0

    def draw(self, rgba_bottom_up: bytes) -> None:
        """Upload the overlay pixels (RGBA rows bottom to top) and blend them over the framebuffer."""
        self.ctx.viewport = (0, 0, *self.size)
        self.texture.swizzle = "RGBA"
        self.texture.write(rgba_bottom_up)
        self._blend(self.vao)

    def draw_surface(self, surface, changed: bool) -> None:
        """Blend a pygame surface's non-empty tiles over the framebuffer; re-upload only if ``changed``.

        The surface's own pixel memory goes to the texture as it is (rows top first, channels in the
        surface's byte order, put right by the texture's swizzle): converting 3.7 MB to RGBA rows
        bottom first took 3.6 ms of every repaint."""
        if changed:
            order = [int(mask).bit_length() // 8 - 1 for mask in surface.get_masks()]  # byte of R, G, B, A
            view = surface.get_view("1")  # (the surface stays locked while the view lives)
            self.texture.swizzle = "".join("RGBA"[k] for k in order)
            self.texture.write(view)
            self._layout_tiles(np.frombuffer(view, np.uint8)[order[3]::4].reshape(self.size[1], self.size[0])[::-1])
            del view
        if self.tile_vertices:
            self.ctx.viewport = (0, 0, *self.size)
            self._blend(self.tile_vao, self.tile_vertices)

    def _layout_tiles(self, alpha: np.ndarray) -> None:
        """Two triangles for each TILE-square of the overlay with a visible pixel (``alpha``: rows from
        the bottom, as GL has them), found in one pass over the alpha channel."""
        w, h, t = self.size[0], self.size[1], self.TILE
        rows, cols = -(-h // t), -(-w // t)
        padded = np.zeros((rows * t, cols * t), np.uint8)
        padded[:h, :w] = alpha
        ty, tx = np.nonzero(padded.reshape(rows, t, cols, t).max(axis=(1, 3)))
        x0, x1 = 2 * tx * t / w - 1, 2 * np.minimum((tx + 1) * t, w) / w - 1
        y0, y1 = 2 * ty * t / h - 1, 2 * np.minimum((ty + 1) * t, h) / h - 1
        data = np.stack([x0, y0, x1, y0, x1, y1, x0, y0, x1, y1, x0, y1], axis=1).astype("f4").ravel()
        if len(data):
            self.tiles.orphan(data.nbytes)
            self.tiles.write(data.tobytes())
        self.tile_vertices = len(data) // 2

    def _blend(self, vao, vertices: int = -1) -> None:
        self.texture.use(location=0)
        self.prog["u_tex"].value = 0
        if "u_tex" in self.tile_prog:
            self.tile_prog["u_tex"].value = 0
        self.ctx.disable(moderngl.DEPTH_TEST)
        self.ctx.enable(moderngl.BLEND)
        self.ctx.blend_func = moderngl.SRC_ALPHA, moderngl.ONE_MINUS_SRC_ALPHA
        vao.render(vertices=vertices)
        self.ctx.disable(moderngl.BLEND)


def sun_direction(azimuth_deg: float = 135.0, elevation_deg: float = 50.0) -> np.ndarray:
    """Unit vector towards the sun from azimuth (about +Y, from +Z) and elevation."""
    az, el = math.radians(azimuth_deg), math.radians(elevation_deg)
    return np.array([math.sin(az) * math.cos(el), math.sin(el), math.cos(az) * math.cos(el)])


def shared_camera(frame_height: float, size: tuple[int, int], yaw: float = 30.0, pitch: float = 12.0) -> OrbitCamera:
    """The camera :func:`render_image` frames a box ``frame_height`` scene units high round the trunk with:
    the same for every tree, so trees rendered with it share one scale (and a scale bar can be measured)."""
    camera = OrbitCamera(yaw=yaw, pitch=pitch)
    half = frame_height * 0.35
    camera.frame_bounds(np.array([-half, 0.0, -half]), np.array([half, frame_height, half]), size[0] / size[1])
    return camera


def render_image(tree: TreeMesh, size: tuple[int, int] = (1280, 720), yaw: float = 30.0, pitch: float = 12.0,
                 sun: np.ndarray | None = None, ctx: moderngl.Context | None = None, samples: int = 4,
                 frame_height: float | None = None) -> np.ndarray:
    """Render a tree headless and return the picture as an (H, W, 3) uint8 array, top row first.

    ``frame_height`` frames a box of that height around the trunk instead of the tree's own bounds
    (so several trees rendered alike can be compared side by side).
    """
    own = ctx is None
    ctx = ctx or headless_context()
    try:
        renderer = TreeRenderer(ctx)
        renderer.set_tree(tree)
        if frame_height is None:
            camera = OrbitCamera(yaw=yaw, pitch=pitch)
            camera.frame_bounds(renderer.lo, renderer.hi, size[0] / size[1])
        else:
            camera = shared_camera(frame_height, size, yaw, pitch)
            if renderer.radius < frame_height * 0.6:  # ground and shadows at the shared scale
                renderer.radius = frame_height * 0.6
                renderer._make_ground()
        msaa = ctx.framebuffer(
            color_attachments=[ctx.renderbuffer(size, samples=samples)],
            depth_attachment=ctx.depth_renderbuffer(size, samples=samples),
        )
        out = ctx.simple_framebuffer(size)
        renderer.render(msaa, camera, sun if sun is not None else sun_direction(yaw + 55.0, 48.0), size)
        ctx.copy_framebuffer(out, msaa)
        pixels = np.frombuffer(out.read(components=3), dtype=np.uint8).reshape(size[1], size[0], 3)
        renderer.release_tree()
        return pixels[::-1].copy()
    finally:
        if own:
            ctx.release()


def _surface(pixels: np.ndarray):
    """An (H, W, 3) uint8 picture as a pygame Surface."""
    import pygame

    return pygame.image.frombuffer(np.ascontiguousarray(pixels).tobytes(), (pixels.shape[1], pixels.shape[0]), "RGB")


def save_png(pixels: np.ndarray, path: str | Path) -> None:
    """Write an (H, W, 3) uint8 picture as PNG."""
    import pygame

    try:
        pygame.image.save(_surface(pixels), str(path))
    except pygame.error as exc:  # e.g. a folder that does not exist: report it like any file error
        raise OSError(0, str(exc), str(path)) from None


def png_bytes(pixels: np.ndarray) -> bytes:
    """An (H, W, 3) uint8 picture as the bytes of a PNG file (for writers that add to it: postcards)."""
    import io

    import pygame

    out = io.BytesIO()
    pygame.image.save(_surface(pixels), out, "picture.png")
    return out.getvalue()
