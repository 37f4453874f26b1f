"""Region edits that ask before they cut drawn work (issue 48), in the real game headless: Prune here over
the base of a drawn branch says what it would cut (the drawn pieces, the modules, the share of the tree)
and cuts nothing; a second tap inside the same region within 5 s cuts it (one undoable step). Before,
it cut the drawn branch at once without a word. A prune of a little grown wood is done at once; one of
more than a quarter of the tree is asked about too."""

import numpy as np

from arbor.engine.modeling.regions import Sphere
from arbor.game.input.events import DOWN, UP
from tests.test_modeler_tools import base_pixel, draw, press_bar, press_menu, touch


def tap(game, x, y):
    touch(game, DOWN, 0, x, y)
    touch(game, UP, 0, x, y)


def drawn(ls) -> int:
    return int(((ls.sym == ord("F")) & (ls.nparams == 11)).sum())


def prune_here(game, centre):
    """The symbols tool with Prune here chosen and a sphere region round ``centre`` (scene units)."""
    press_bar(game, "symbols")
    while game.modeling.edit != "prune":
        press_bar(game, "edit")
    x, y = game.hud.project(game.camera(), centre)
    draw(game, [(x - 16 + 4 * i, y) for i in range(5)], dt=0.1)  # a short drag ending there: a sphere there
    assert isinstance(game.modeling.region_tool.region, Sphere)
    return x, y


def _a_drawn_branch(modeler_game):
    """The game in the modeler with a branch drawn up from the sapling's foot: (game, tree, its segments)."""
    game = modeler_game(seed=3)
    press_menu(game, "modeler")
    x0, y0 = base_pixel(game)
    draw(game, [(x0 + 6 * i, y0 - 8 * i) for i in range(40)])
    tree = game.world.tree.lstring
    segs = game.modeling.segments(tree)
    return game, tree, segs


def test_prune_here_asks_before_cutting_a_drawn_branch(modeler_game):
    game, tree, segs = _a_drawn_branch(modeler_game)
    branch = np.flatnonzero((tree.sym[segs.module] == ord("F")) & (tree.nparams[segs.module] == 11))
    x, y = prune_here(game, tuple(segs.start[branch[0]] + 0.3 * (segs.end[branch[3]] - segs.start[branch[0]])))
    tap(game, x, y)
    message = game.hud_info().message
    print(message)
    assert "would cut" in message and "drawn piece" in message and "tap inside again" in message
    assert game.world.tree.lstring is tree  # nothing cut yet
    game.clock_box[0] += 1.0
    tap(game, x, y)
    assert drawn(game.world.tree.lstring) < drawn(tree) and "modules cut" in game.hud_info().message
    game.modeling.undo()
    assert game.world.tree.lstring is tree


def test_prune_here_of_a_little_grown_wood_is_done_at_once_and_of_much_asked(modeler_game):
    game, tree, segs = _a_drawn_branch(modeler_game)
    grown = np.flatnonzero(tree.sym[segs.module] == ord("I"))
    x, y = prune_here(game, tuple(segs.start[grown[np.argmax(segs.start[grown, 1])]]))  # the sapling's top piece
    tap(game, x, y)
    assert "modules cut" in game.hud_info().message and game.world.tree.lstring is not tree
    assert drawn(game.world.tree.lstring) == drawn(tree)
    game.modeling.undo()
    press_bar(game, "draw")
    x, y = prune_here(game, tuple(segs.start[grown[1]]))  # low on the sapling: most of the tree
    tap(game, x, y)
    assert "of the tree" in game.hud_info().message and game.world.tree.lstring is tree  # asked, not cut
