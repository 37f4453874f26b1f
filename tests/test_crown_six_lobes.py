"""Six lobes round a tree with the game's budget (issue 48): each lobe at least 85 % filled, with the
engine's cases (benchmarks.lobes six_lobe_cases: six lobes round a drawn tree) and in the real game
headless (six small outlines drawn round the sapling with a shaky hand until the budget binds). Before:
the top one of six 0.9 m lobes filled 2.5 % (no axis of its own), and six 0.55 m lobes 63-91 % (a try
just over the budget fell to the node bound, and the node bound was shared only at the last step: the
lobes round the drawn branches' combs took it)."""

import numpy as np

from arbor.engine.modeling.crown_fill import lobe_fill
from arbor.game.input.events import WHEEL, InputEvent
from benchmarks.lobes import six_lobe_cases
from tests.test_modeler_tools import base_pixel, draw, press_menu

SPOTS = ((-300, -150), (-170, -300), (0, -380), (170, -300), (300, -150), (0, -170))  # pixels from the foot


def test_each_of_six_lobes_is_filled():
    for name, (fill, ms) in six_lobe_cases().items():
        print(f"{name}: fill {[round(f, 3) for f in fill]}, {ms:.0f} ms")
        assert min(fill) >= 0.85, name


def test_six_small_outlines_in_the_game_each_fill(modeler_game):
    game = modeler_game(seed=3)
    press_menu(game, "crown")
    for _ in range(3):  # the wheel: the view a little farther out, room for six outlines round the sapling
        game.handle_input(InputEvent(WHEEL, game.clock_box[0], "mouse", amount=-1.0))
    x0, y0 = base_pixel(game)
    a = np.linspace(0, 2 * np.pi, 40)
    rng = np.random.default_rng(2)
    for dx, dy in SPOTS:
        points = np.stack([x0 + dx + 95 * np.cos(a), y0 + dy + 80 * np.sin(a)], 1) + rng.normal(0, 1.5, (40, 2))
        draw(game, [tuple(p) for p in points])
    world = game.world
    lobes = list(world.crown.lobes)
    fill = lobe_fill(lobes, game.modeling.segments(world.tree.lstring))
    sizes = [float(np.ptp(lobe.vertices, axis=0).max()) for lobe in lobes]
    print(f"six outlines in the game ({min(sizes):.2f}-{max(sizes):.2f} units across): fill "
          f"{[f'{f:.0%}' for f in fill]}, {len(world.tree.lstring)} of {world.tree.deriver.budget} modules; "
          f"{game.hud_info().message}")
    assert len(lobes) == 6 and min(fill) >= 0.85
    assert len(world.tree.lstring) > 0.9 * world.tree.deriver.budget  # the budget binds
