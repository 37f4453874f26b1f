"""The first minute of a new game (issue 28): when does the seedling show its first leaves?

A new game on a fresh saves folder at the default pace (rules.toml's, the home pace), headless (SDL dummy
video, an EGL context), played frame by frame at 30 frames a second of a fake clock with nobody
touching it. Printed: the seconds until the first leaf is drawn (a leaf record longer than 5 % of a
unit) and until the seedling stands at its planted size, the hint shown, and the seconds of each
picture written. ``--out DIR`` writes the frames at 0, 8, 14 and 30 s and a strip of the four.

    python -m benchmarks.first_minute [--out docs] [--pace home]
"""

from __future__ import annotations

import argparse
import os
import tempfile
from pathlib import Path

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("SDL_AUDIODRIVER", "dummy")

import numpy as np

FPS = 30
SHOTS = (0, 8, 14, 30)  # seconds of the pictures
LEAF_LENGTH = 9  # the leaf record's column holding its drawn length (engine/geometry/instances.py)


def leaf_length(game) -> float:
    """The longest leaf of the cared-for tree as drawn in the last frame (0 without leaves)."""
    entry = game.view.views.get(id(game.world))
    data = entry[1].leaves.data if entry else np.zeros((0, LEAF_LENGTH + 1))
    return float(data[:, LEAF_LENGTH].max()) if len(data) else 0.0


def run(pace: str | None, out: Path | None, seconds: float = 60.0) -> dict:
    """Play a new game's first ``seconds``; returns the figures printed (see module docstring)."""
    import pygame

    from arbor.game.render.renderer import headless_context, save_png
    from arbor.game.screens.game import Game, GameConfig

    pygame.init()
    pygame.display.set_mode((64, 64))
    ctx, size = headless_context(), (1280, 720)
    clock = type("Clock", (), {"t": 100.0, "__call__": lambda self: self.t})()
    game = Game(ctx, size, GameConfig(saves=Path(tempfile.mkdtemp()), seed=5, resume=False, pace=pace,
                                                sprout=True), clock=clock)
    fbo = ctx.framebuffer(color_attachments=[ctx.renderbuffer(size)], depth_attachment=ctx.depth_renderbuffer(size))
    draw_hud = game.hud.draw
    game.hud.draw = lambda camera: (fbo.use(), draw_hud(camera))  # (headless, the HUD goes over this target)
    figures, shots, full = {"first_leaf": None, "full_size": None, "hint": game.hud_info().hint}, [], None
    for frame in range(int(seconds * FPS) + 1):
        t = frame / FPS
        game.update(1 / FPS if frame else 0.0)
        game.draw(fbo)
        length = leaf_length(game)
        if figures["first_leaf"] is None and length > 0.05:
            figures["first_leaf"] = t
        if figures["full_size"] is None and game.state.sprout_from is None:
            figures["full_size"], full = t, length
        if out is not None and any(abs(t - s) < 0.5 / FPS for s in SHOTS):
            pixels = np.frombuffer(fbo.read(components=3), np.uint8).reshape(size[1], size[0], 3)[::-1]
            shots.append(pixels)
            save_png(pixels, out / f"kind_first_minute_{round(t):02d}s.png")
        clock.t += 1 / FPS
    figures["full_length"] = full
    if out is not None and shots:
        save_png(np.concatenate([p[200:700, 330:950] for p in shots], axis=1), out / "kind_first_minute.png")
    return figures


def main() -> None:
    """Parse the arguments, run, print."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, help="folder for the pictures")
    parser.add_argument("--pace", default=None, help="a pace of rules.toml (default: rules.toml's own)")
    args = parser.parse_args()
    f = run(args.pace, args.out)
    first = "never" if f["first_leaf"] is None else f"{f['first_leaf']:.1f} s"
    print(f"first leaf drawn after {first}; the seedling at its planted size after {f['full_size']:.1f} s "
          f"(longest leaf {f['full_length']:.2f} units); hint at the start: {f['hint']!r}")
    if args.out:
        print(f"pictures at {', '.join(f'{s} s' for s in SHOTS)} in {args.out}/kind_first_minute*.png")


if __name__ == "__main__":
    main()
