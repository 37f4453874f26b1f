"""Lab outputs: CSV of the time series, PNG charts, a PNG of the trees side by side, saves."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from arbor.engine.base.units import METRE
from arbor.engine.life.experiment.lab import Lab, load_experiment, save_stem
from arbor.engine.life.keep.save import SavedGarden, write_garden
from arbor.engine.life.rules.rules import load_rules
from arbor.game.paths import ASSETS
from arbor.game.render.figures import lab_charts
from arbor.game.render.renderer import headless_context, save_png
from arbor.game.render.scale_bar import frame_for, render_to_scale


def new_lab(experiment_path: Path) -> Lab:
    """A lab for an experiment file, with the game's rules as the base."""
    experiment = load_experiment(experiment_path, ASSETS / "lsystems")
    for note in experiment.notes:
        print(note, file=sys.stderr)
    return Lab(experiment, load_rules(ASSETS / "rules.toml", experiment.pace))


def scene_png(lab: Lab, path: Path, tile: tuple[int, int] = (640, 720), ctx=None) -> None:
    """The trees side by side (at one shared scale with a metre bar, named), as one PNG."""
    import pygame

    pygame.font.init()
    font = pygame.font.Font(None, 40)
    tiles = []
    frame = frame_for(max(float(w.tree.geometry(w.clocks()).turtle.bounds()[1][1]) for w in lab.worlds) / METRE)
    for world, series in zip(lab.worlds, lab.series, strict=True):
        mesh = world.tree.geometry(world.clocks()).mesh
        img = render_to_scale(mesh, tile, frame, pitch=10.0, ctx=ctx)
        surf = pygame.image.frombuffer(np.ascontiguousarray(img).tobytes(), tile, "RGB").copy()
        label = font.render(series.name, True, (20, 20, 20))
        surf.blit(label, ((tile[0] - label.get_width()) // 2, tile[1] - 50))
        tiles.append(pygame.surfarray.array3d(surf).swapaxes(0, 1))
    save_png(np.concatenate(tiles, axis=1), path)


def plot_png(lab: Lab, path: Path, size: tuple[int, int] = (1600, 900), ctx=None, samples: int = 4) -> np.ndarray:
    """Trees sharing a plot (``spacing``) in one scene at their places in the row, lit from the front, each
    tree's name and state (alive, wilt, height; or the day it died) beneath it; written as one PNG and
    returned (H, W, 3)."""
    import pygame

    from arbor.game.render.plot_scene import PlotScene, tree_state

    scene = PlotScene(ctx)
    msaa = ctx.framebuffer(color_attachments=[ctx.renderbuffer(size, samples=samples)],
                           depth_attachment=ctx.depth_renderbuffer(size, samples=samples))
    out = ctx.simple_framebuffer(size)
    try:
        scene.render(msaa, lab.worlds, size)
        ctx.copy_framebuffer(out, msaa)
        pixels = np.frombuffer(out.read(components=3), np.uint8).reshape(size[1], size[0], 3)[::-1].copy()
        bases = scene.bases(lab.worlds, size)
    finally:
        scene.release()
        for thing in (msaa, out):
            thing.release()
    pygame.font.init()
    surf = pygame.image.frombuffer(pixels.tobytes(), size, "RGB").copy()
    name_font, state_font = pygame.font.Font(None, 44), pygame.font.Font(None, 32)
    for (x, y), world, series, meters in zip(bases, lab.worlds, lab.series, lab.meters, strict=True):
        lines = [(name_font.render(series.name, True, (255, 255, 255)), (20, 20, 20, 190)),
                 (state_font.render(tree_state(world, meters), True, (255, 255, 255)),
                  (120, 20, 20, 200) if not world.sim.state.alive else (20, 20, 20, 150))]
        top = min(int(y) + 14, size[1] - 96)
        for text, back in lines:
            box = text.get_rect(midtop=(int(x), top)).inflate(18, 8)
            box.clamp_ip(surf.get_rect())
            panel = pygame.Surface(box.size, pygame.SRCALPHA)
            panel.fill(back)
            surf.blit(panel, box)
            surf.blit(text, text.get_rect(center=box.center))
            top = box.bottom + 4
    pixels = pygame.surfarray.array3d(surf).swapaxes(0, 1).copy()
    save_png(pixels, path)
    return pixels


def run_headless(experiment_path: Path, out: Path) -> list[Path]:
    """Run the experiment without a window; write results.csv, charts (PNG and SVG), scene.png and saves."""
    lab = new_lab(experiment_path)
    lab.run()
    out.mkdir(parents=True, exist_ok=True)
    lab.write_csv(out / "results.csv")
    charts = lab_charts(lab.series, out / "charts",
                        title=f"{lab.experiment.title} ({lab.worlds[0].sim.state.sun_turns:.0f} game days)")
    files = [out / "results.csv", *charts, out / "scene.png"]
    ctx = headless_context()
    try:
        if lab.experiment.spacing:  # trees sharing a plot: one scene, the row as it stands
            plot_png(lab, out / "scene.png", ctx=ctx)
        else:
            scene_png(lab, out / "scene.png", ctx=ctx)
    finally:
        ctx.release()
    for world, regime in zip(lab.worlds, lab.experiment.regimes, strict=True):
        path = out / f"{save_stem(regime.name)}.arbor"
        write_garden(SavedGarden([world], lsystem_name=lab.experiment.lsystem.name), path)
        files.append(path)
    return files
