"""A lobe edit regrows only its own crown (issue 48), in the real game headless: three outlines, then a
Shape drag moves one lobe; the other two lobes keep every branch piece of their crowns, the moved lobe's
crown is grown anew and fills it, and undo brings the tree back as it was (before, the whole crown was
regrown with every lobe's attractors drawn anew: no lobe kept its branches)."""

import numpy as np

from arbor.engine.modeling.crown_edit import crown_pieces
from arbor.engine.modeling.crown_fill import lobe_fill
from tests.test_modeler_lobes_kept import drag_lobe
from tests.test_modeler_tools import base_pixel, draw, press_bar, press_menu


def pieces_by_lobe(game) -> list[set]:
    """For each lobe, the crown's drawn pieces in it (their parameters: where they start, their heading...)."""
    ls, crown = game.world.tree.lstring, game.world.crown
    segs = game.modeling.segments(ls)
    grown = crown_pieces(ls, crown.base, segs)
    middle = 0.5 * (segs.start + segs.end)
    rows = ls.params[ls.offsets[segs.module][:, None] + np.arange(11)]
    return [{tuple(r) for r in rows[grown & lobe.contains(middle)]} for lobe in crown.lobes]


def test_moving_one_lobe_keeps_the_others_crowns(modeler_game):
    game = modeler_game(seed=3)
    press_menu(game, "crown")
    x0, y0 = base_pixel(game)
    a = np.linspace(0, 2 * np.pi, 48)
    for dx, dy in ((-150, -260), (150, -260), (0, -400)):
        draw(game, [(x0 + dx + 100 * np.cos(t), y0 + dy + 80 * np.sin(t)) for t in a])
    before, tree = pieces_by_lobe(game), game.world.tree.lstring
    press_bar(game, "shape")
    drag_lobe(game, game.world.crown.lobes[0], -60)
    assert "Lobe move" in game.hud_info().message
    after = pieces_by_lobe(game)
    fill = lobe_fill(list(game.world.crown.lobes), game.modeling.segments(game.world.tree.lstring))
    kept = [len(b & a) / max(len(b), 1) for b, a in zip(before, after, strict=True)]
    print(f"crown pieces kept per lobe: {[f'{k:.0%}' for k in kept]}; fills after the move "
          f"{[f'{f:.0%}' for f in fill]}")
    assert kept[1] == 1.0 and kept[2] == 1.0 and after[1] == before[1] and after[2] == before[2]
    assert kept[0] < 0.1 and len(after[0]) >= 100 and fill[0] >= 0.9
    game.modeling.undo()
    assert game.world.tree.lstring is tree
