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
        scene_png(lab, out / "scene.png", ctx=ctx)
    finally:
        ctx.release()
    for world, regime in zip(lab.worlds, lab.experiment.regimes, strict=True):
        path = out / f"{save_stem(regime.name)}.arbor"
        write_garden(SavedGarden([world], lsystem_name=lab.experiment.lsystem.name), path)
        files.append(path)
    return files
