"""`arbor render --scale-bar`: trees rendered at one shared scale with a metre bar (issue 30). Two trees of
different heights stand at different heights in the picture, the bar is as long in both, and the bar
and the trees agree on what a metre is."""

from __future__ import annotations

import numpy as np
import pygame

from arbor.game.cli import main
from arbor.game.commands.trees import TreeSource, tree_geometry
from arbor.game.render.scale_bar import BAR_RGB, bar_metres, bar_pixels
from tests.conftest import LSYSTEMS

TREE = LSYSTEMS / "abop_2_8_tree.lsys"
SIZE, FRAME = (320, 240), 8.0  # a frame 8 m high: both trees fit (the ABOP tree declares 'unit: 0.01', centimetres)


def picture(path) -> np.ndarray:
    return pygame.surfarray.array3d(pygame.image.load(str(path))).swapaxes(0, 1).astype(int)


def bar_length(pixels: np.ndarray) -> int:
    """Pixels of the bar's white fill in its middle column."""
    column = pixels[:, max(8, pixels.shape[1] // 25) + 1]
    return int((column == BAR_RGB).all(axis=1).sum())


def tree_top(pixels: np.ndarray) -> int:
    """The highest row holding something that is not sky (right of the bar; the horizon is low: pitch 0)."""
    sky = pixels[..., 2] > pixels[..., 0] + 15
    return int(np.flatnonzero((~sky[:, pixels.shape[1] // 5:]).any(axis=1))[0])


def test_two_trees_at_one_scale_differ_in_pixels_with_the_same_bar(tmp_path, capsys):
    shots, metres = [], []
    for steps in (2, 4):
        out = tmp_path / f"tree{steps}.png"
        assert main(["render", str(TREE), "--steps", str(steps), "--scale-bar", f"{FRAME:g}", "--pitch", "0",
                     "--size", "x".join(map(str, SIZE)), "--out", str(out)]) == 0
        shots.append(picture(out))
        geometry, _ = tree_geometry(TreeSource(TREE, steps), 0)
        metres.append(float(geometry.turtle.bounds()[1][1]) * 0.01)
    assert "in a frame 8 m high" in capsys.readouterr().out
    _, ground, per_metre = bar_pixels(FRAME, SIZE, 30.0, 0.0)
    bars = [bar_length(p) for p in shots]
    assert bars[0] == bars[1] and abs(bars[0] - bar_metres(FRAME) * per_metre) <= 1.5  # 20 m in both
    tall = [ground - tree_top(p) for p in shots]
    assert metres[1] > 1.5 * metres[0] and tall[1] > tall[0] + 40  # the taller tree stands taller
    for pixels_high, m in zip(tall, metres, strict=True):
        read = pixels_high / bars[0] * bar_metres(FRAME)  # the tree's height read off with the bar
        assert abs(read - m) < 0.12 * m, (read, m)  # (within perspective: the crown leans toward the camera)


def test_without_a_frame_the_tree_sets_it_in_whole_metres(tmp_path, capsys):
    out = tmp_path / "own.png"
    assert main(["render", str(TREE), "--steps", "2", "--scale-bar", "--size", "160x120", "--out", str(out)]) == 0
    assert "4.49 m tall (top of the wood) in a frame 5 m high" in capsys.readouterr().out
    assert bar_length(picture(out)) > 0
