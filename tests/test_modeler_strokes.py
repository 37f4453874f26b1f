"""Strokes an artist can trust (issue 48): hand jitter never reads as a bend (1 % jitter on a straight
stroke: its path within 2 % of the clean length, median turn <= 2 deg; real bends kept within 0.3 %),
also for a jittery mouse stroke drawn in the real game; figures from benchmarks.strokes."""

import numpy as np
import pytest

from benchmarks.strokes import jitter_figures, path_length, turns
from tests.test_modeler_tools import base_pixel, draw, press_menu


def test_one_percent_jitter_on_a_straight_stroke_is_smoothed_away_and_bends_are_kept():
    figures = jitter_figures()
    for longer, median, _ in figures["straight"]:
        assert abs(longer) <= 0.02 and median <= 2.0
    for name, (longer, stray) in figures["bends"].items():
        assert abs(longer) <= 0.003 and stray <= 0.003, name


def drawn_path(game):
    ls = game.world.tree.lstring
    segs = game.modeling.segments(ls)
    drawn = (ls.sym[segs.module] == ord("F")) & (ls.nparams[segs.module] == 11)
    order = np.argsort(segs.module[drawn])
    start, end = segs.start[drawn][order], segs.end[drawn][order]
    return np.r_[start[:1], end]


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_a_jittery_mouse_stroke_in_the_game_draws_as_straight_as_a_clean_one(modeler_game, seed):
    paths = []
    for jitter in (0.0, 1.5):  # pixels
        game = modeler_game(seed=3)
        press_menu(game, "modeler")
        x0, y0 = base_pixel(game)
        shake = np.random.default_rng(seed).normal(0, jitter, (30, 2))  # a short stroke: 30 moves, 100 px
        draw(game, [(x0 + 1.5 * i + shake[i, 0], y0 - 60 - 3 * i + shake[i, 1]) for i in range(30)])
        paths.append(drawn_path(game))
    clean, shaky = paths
    longer, turn = path_length(shaky) / path_length(clean) - 1, float(np.median(turns(shaky)))
    print(f"mouse stroke, 1.5 px jitter, seed {seed}: {longer:+.2%} longer, median turn {turn:.2f} deg "
          f"(clean {float(np.median(turns(clean))):.2f})")
    assert abs(longer) <= 0.02 and turn <= 2.0
