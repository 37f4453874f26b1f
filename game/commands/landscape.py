"""Landscape mode: N trees of chosen presets scattered on terrain, rendered with instancing and LOD."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from arbor.engine.forest.landscape import Instances, Preset, scatter
from arbor.engine.geometry.mesh import LOD_LEVELS
from arbor.engine.geometry.tree import build_geometry
from arbor.engine.lsystem.derive import derive
from arbor.engine.lsystem.lsys import load_lsystem
from arbor.game.errors import UserError
from arbor.game.paths import ASSETS
from arbor.game.render.camera import OrbitCamera
from arbor.game.render.renderer import headless_context, save_png, sun_direction
from arbor.game.report import say

DEFAULT_PRESETS = (("abop_2_8_tree", 4), ("abop_2_6_monopodial", 7), ("abop_1_24e", 5))


MAX_PRESET_STEPS = 10  # derivation steps of a landscape preset
PRESET_BUDGET = 400_000  # modules of one preset tree (it is meshed at every level of detail)


def parse_presets(text: str) -> list[tuple[str, int | None]]:
    """'abop_2_8_tree:4,broadleaf' -> [('abop_2_8_tree', 4), ('broadleaf', None)]; bad entries are
    errors that say what is allowed."""
    out = []
    items = [part.strip() for part in text.split(",") if part.strip()]
    if not 1 <= len(items) <= 8:
        raise UserError("--presets takes 1 to 8 comma-separated names")
    for item in items:
        name, _, steps = item.partition(":")
        if not name.replace("_", "").isalnum():
            raise UserError(f"--presets: {name!r} is not a preset name (letters, digits and _)")
        if steps and (not steps.isdigit() or int(steps) > MAX_PRESET_STEPS):
            raise UserError(f"--presets {item}: steps must be a whole number from 0 to {MAX_PRESET_STEPS}")
        out.append((name, int(steps) if steps else None))
    return out


def _grow_preset(name: str, steps: int | None):
    """A GeoMaTree species (assets/presets/NAME.toml) or an L-system (assets/lsystems/NAME.lsys)."""
    species = ASSETS / "presets" / f"{name}.toml"
    if species.exists():
        from arbor.engine.forest.geomatree import growth_system, load_species

        system = growth_system(load_species(species), ASSETS / "lsystems" / "geomatree.lsys", seed=1)
    else:
        source = ASSETS / "lsystems" / f"{name}.lsys"
        if not source.is_file():
            known = sorted(p.stem for p in (ASSETS / "presets").glob("*.toml"))
            raise UserError(f"--presets: no preset or L-system called {name!r} (species: {', '.join(known)}; "
                            "or any file name in assets/lsystems)")
        system = load_lsystem(source)
    if system.externs:
        raise UserError(f"--presets: {name} grows only inside the game (it needs #extern values); pick another")
    steps = min(steps if steps is not None else system.iterations, MAX_PRESET_STEPS)
    return system, derive(system, steps, budget=PRESET_BUDGET)


PRESET_SECONDS = 0.4  # growing and meshing one preset at every level (0.03-1.5 s, measured at load 8)
DRAW_SECONDS, TREE_SECONDS = 3.0, 1.2e-3  # drawing: set-up and read-back, then each tree (500: 4 s, 2000: 5.5 s)


def build_presets(specs=DEFAULT_PRESETS, progress=None, after: float = 0.0) -> list[Preset]:
    """Each (name, steps) grown once and meshed at every LOD level, scaled to about 8 units tall.
    ``progress`` hears of each preset (``after``: the estimated seconds of the stages that follow)."""
    import time

    presets, started = [], time.perf_counter()
    for k, (name, steps) in enumerate(specs):
        if progress is not None:
            spent = time.perf_counter() - started
            each = spent / k if k else PRESET_SECONDS
            progress.to(spent, f"growing {name} ({k + 1} of {len(specs)})",
                        total=spent + each * (len(specs) - k) + after)
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
    from arbor.game.progress import Progress

    drawing = DRAW_SECONDS + count * TREE_SECONDS
    with Progress(f"landscape {out.name}", len(specs) * PRESET_SECONDS + drawing, unit="s") as bar:
        presets = build_presets(specs, bar, drawing)
        with bar.timed(f"drawing {count:,} trees", drawing):
            stats = _draw(count, out, size, seed, lod, presets)
    say(f"{out}: {count:,} trees, {stats.drawn:,} drawn ({stats.culled:,} culled), "
        f"levels {stats.per_level}, {stats.triangles:,} triangles")
    return presets


def _draw(count: int, out: Path, size: tuple[int, int], seed: int, lod: int | None, presets: list[Preset]):
    """Scatter ``count`` trees of ``presets``, draw them and write the picture; the renderer's statistics."""
    from arbor.game.render.landscape import LandscapeRenderer

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
    finally:
        ctx.release()
    return stats
