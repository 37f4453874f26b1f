"""Instanced, LOD-aware rendering of a landscape of many trees (Jung et al. section 6)."""

from __future__ import annotations

from dataclasses import dataclass

import moderngl
import numpy as np

from arbor.engine.forest.landscape import Instances, Preset, lod_levels, terrain_mesh, visible
from arbor.engine.geometry.mesh import LOD_LEVELS, Mesh
from arbor.game.paths import ASSETS
from arbor.game.render.camera import OrbitCamera
from arbor.game.render.renderer import BARK_TINT, GRASS, LEAF_TINT, SKY_HORIZON, SKY_ZENITH, _gl, _load_texture

PARTS = (("wood", "bark", 0), ("leaves", "leaf", 1), ("blossoms", "blossom", 2))


@dataclass
class FrameStats:
    """What one frame drew."""

    drawn: int
    culled: int
    triangles: int
    per_level: list[int]


class LandscapeRenderer:
    """Draws terrain, sky and instances of a few tree presets."""

    def __init__(self, ctx: moderngl.Context, presets: list[Preset], size: float) -> None:
        self.ctx, self.presets, self.size = ctx, presets, size
        shaders = ASSETS / "shaders"
        self.prog = ctx.program(vertex_shader=(shaders / "instanced.vert").read_text(),
                                fragment_shader=(shaders / "instanced.frag").read_text())
        self.sky = ctx.program(vertex_shader=(shaders / "sky.vert").read_text(),
                               fragment_shader=(shaders / "sky.frag").read_text())
        tri = ctx.buffer(np.array([-1, -1, 3, -1, -1, 3], dtype="f4").tobytes())
        self.sky_vao = ctx.vertex_array(self.sky, [(tri, "2f", "in_pos")])
        self.textures = {name: _load_texture(ctx, name, name == "bark") for name in ("bark", "leaf", "blossom")}
        white = ctx.texture((1, 1), 4, bytes([255, 255, 255, 255]))
        self.textures["white"] = white
        self.capacity = 256
        self.batches: dict[tuple[int, int], tuple[moderngl.Buffer, list]] = {}
        for p, preset in enumerate(presets):
            for level, tree in enumerate(preset.levels):
                inst = ctx.buffer(reserve=self.capacity * 20)
                parts = []
                for attr, tex, kind in PARTS:
                    mesh: Mesh = getattr(tree, attr)
                    if mesh.n_triangles:
                        parts.append((self._vao(mesh, inst), tex, kind, mesh.n_triangles))
                self.batches[(p, level)] = (inst, parts)
        pos, nrm, idx = terrain_mesh(size)
        uv = np.zeros((len(pos), 2), np.float32)
        ground = Mesh(pos, nrm, uv, idx, np.zeros(len(idx), np.int64))
        self.ground_inst = ctx.buffer(np.array([0, 0, 0, 0, 1], dtype="f4").tobytes())
        self.ground_vao = self._vao(ground, self.ground_inst)

    def _vao(self, mesh: Mesh, inst: moderngl.Buffer) -> moderngl.VertexArray:
        ctx = self.ctx
        return ctx.vertex_array(self.prog, [
            (ctx.buffer(mesh.positions.tobytes()), "3f", "in_pos"),
            (ctx.buffer(mesh.normals.tobytes()), "3f", "in_normal"),
            (ctx.buffer(mesh.uvs.tobytes()), "2f", "in_uv"),
            (inst, "4f 1f/i", "in_inst", "in_scale"),
        ], ctx.buffer(mesh.indices.tobytes()))

    def render(self, fbo: moderngl.Framebuffer, camera: OrbitCamera, sun: np.ndarray, size: tuple[int, int],
               instances: Instances, lod: int | None = None) -> FrameStats:
        """One frame; ``lod`` forces one level for every tree, None picks levels by distance."""
        ctx = self.ctx
        vp = camera.projection(size[0] / size[1]) @ camera.view()
        fbo.use()
        ctx.viewport = (0, 0, *size)
        fbo.clear(*SKY_HORIZON, 1.0)
        ctx.disable(moderngl.DEPTH_TEST | moderngl.CULL_FACE)
        self.sky["u_inv_vp"].write(_gl(np.linalg.inv(vp)))
        self.sky["u_sun_dir"].value = tuple(sun)
        self.sky["u_zenith"].value = SKY_ZENITH
        self.sky["u_horizon"].value = SKY_HORIZON
        self.sky_vao.render()
        ctx.enable(moderngl.DEPTH_TEST)
        self._uniforms(vp, camera, sun)
        self._draw_part(self.ground_vao, "white", 0, GRASS, 1)
        return self._draw_trees(camera, vp, instances, lod)

    def _uniforms(self, vp: np.ndarray, camera: OrbitCamera, sun: np.ndarray) -> None:
        p = self.prog
        p["u_vp"].write(_gl(vp))
        p["u_sun_dir"].value = tuple(sun)
        p["u_sun_color"].value = (1.0, 0.96, 0.85)
        p["u_sky_color"].value = SKY_ZENITH
        p["u_ground_color"].value = (0.30, 0.28, 0.18)
        p["u_eye"].value = tuple(camera.eye)
        p["u_haze"].value = SKY_HORIZON
        p["u_haze_distance"].value = self.size * 1.3
        p["u_tex"].value = 0

    def _draw_part(self, vao, texture: str, kind: int, tint, count: int) -> None:
        self.textures[texture].use(location=0)
        self.prog["u_kind"].value = kind
        self.prog["u_tint"].value = tint
        vao.render(instances=count)

    def _draw_trees(self, camera: OrbitCamera, vp: np.ndarray, inst: Instances, lod: int | None) -> FrameStats:
        heights = np.array([p.height for p in self.presets])[inst.preset] * inst.scale
        radii = np.array([p.radius for p in self.presets])[inst.preset] * inst.scale
        centers = inst.position + np.stack([np.zeros_like(heights), heights / 2, np.zeros_like(heights)], 1)
        shown = visible(centers, radii, vp)
        levels = np.full(len(inst), lod) if lod is not None else lod_levels(centers, camera.eye, float(heights.mean()))
        triangles, per_level = 0, [0] * len(LOD_LEVELS)
        for (p, level), (buffer, parts) in self.batches.items():
            sel = shown & (inst.preset == p) & (levels == level)
            n = int(sel.sum())
            if n == 0:
                continue
            data = np.concatenate([inst.position[sel], inst.yaw[sel, None], inst.scale[sel, None]], axis=1)
            if n > self.capacity:
                self.capacity = 1 << int(np.ceil(np.log2(n)))
            if buffer.size < n * 20:
                buffer.orphan(self.capacity * 20)
            buffer.write(data.astype("f4").tobytes())
            for vao, texture, kind, tris in parts:
                self._draw_part(vao, texture, kind, BARK_TINT if kind == 0 else LEAF_TINT, n)
                triangles += tris * n
            per_level[level] += n
        drawn = int(shown.sum())
        return FrameStats(drawn, len(inst) - drawn, triangles, per_level)
