"""Landscape mode: N trees of chosen presets scattered on terrain, rendered with instancing and LOD."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from engine.forest.landscape import Instances, Preset, scatter
from engine.geometry.mesh import LOD_LEVELS
from engine.geometry.tree import build_geometry
from engine.lsystem.derive import derive
from engine.lsystem.lsys import load_lsystem
from game.paths import ASSETS
from game.render.camera import OrbitCamera
from game.render.renderer import headless_context, save_png, sun_direction

DEFAULT_PRESETS = (("abop_2_8_tree", 4), ("abop_2_6_monopodial", 7), ("abop_1_24e", 5))


def parse_presets(text: str) -> list[tuple[str, int | None]]:
    """'abop_2_8_tree:4,broadleaf' -> [('abop_2_8_tree', 4), ('broadleaf', None)]."""
    out = []
    for item in filter(None, (part.strip() for part in text.split(","))):
        name, _, steps = item.partition(":")
        out.append((name, int(steps) if steps else None))
    return out


def _grow_preset(name: str, steps: int | None):
    """A GeoMaTree species (assets/presets/NAME.toml) or an L-system (assets/lsystems/NAME.lsys)."""
    species = ASSETS / "presets" / f"{name}.toml"
    if species.exists():
        from engine.forest.geomatree import growth_system, load_species

        system = growth_system(load_species(species), ASSETS / "lsystems" / "geomatree.lsys", seed=1)
    else:
        system = load_lsystem(ASSETS / "lsystems" / f"{name}.lsys")
    return system, derive(system, steps)


def build_presets(specs=DEFAULT_PRESETS) -> list[Preset]:
    """Each (name, steps) grown once and meshed at every LOD level, scaled to about 8 units tall."""
    presets = []
    for name, steps in specs:
        system, ls = _grow_preset(name, steps)
        levels = [build_geometry(ls, system, lod=k).mesh for k in range(len(LOD_LEVELS))]
        height = float(levels[0].wood.positions[:, 1].max())
        for tree in levels:
            for mesh in (tree.wood, tree.leaves, tree.blossoms):
                mesh.positions *= np.float32(8.0 / height)
        presets.append(Preset.from_meshes(name, levels))
    return presets


def landscape_size(count: int, spacing: float = 7.0) -> float:
    """Side of a square holding ``count`` trees about ``spacing`` apart."""
    return math.sqrt(count) * spacing


def overview_camera(size: float) -> OrbitCamera:
    """Standing at the landscape's edge, looking across it."""
    camera = OrbitCamera(yaw=35.0, pitch=14.0, fov_y=50.0)
    camera.target = np.array([0.0, 2.0, 0.0])
    camera.distance = size * 0.62
    return camera


def render_landscape(count: int, out: Path, size: tuple[int, int] = (1280, 720), seed: int = 0,
                     lod: int | None = None, specs=DEFAULT_PRESETS) -> list[Preset]:
    """Headless picture of a landscape of ``count`` trees; returns the presets used."""
    from game.render.landscape import LandscapeRenderer

    presets = build_presets(specs)
    side = landscape_size(count)
    instances: Instances = scatter(count, len(presets), side, seed)
    ctx = headless_context()
    try:
        renderer = LandscapeRenderer(ctx, presets, side)
        msaa = ctx.framebuffer(color_attachments=[ctx.renderbuffer(size, samples=4)],
                               depth_attachment=ctx.depth_renderbuffer(size, samples=4))
        stats = renderer.render(msaa, overview_camera(side), sun_direction(80, 40), size, instances, lod)
        plain = ctx.simple_framebuffer(size)
        ctx.copy_framebuffer(plain, msaa)
        pixels = np.frombuffer(plain.read(components=3), np.uint8).reshape(size[1], size[0], 3)[::-1]
        save_png(pixels, out)
        print(f"{out}: {count:,} trees, {stats.drawn:,} drawn ({stats.culled:,} culled), "
              f"levels {stats.per_level}, {stats.triangles:,} triangles")
    finally:
        ctx.release()
    return presets
