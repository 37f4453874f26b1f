"""A branch drawn from the sapling's trunk is shown where it was drawn (issue 48, 'joints at the pressed
point'), in the real game headless: the renderer's records of the growing tree (GrowthView, young
internodes moved each frame) stand where the modeler's geometry has them. A stroke that joins an
internode splits it into two pieces of a share of its length each; the renderer grew each young half to
a whole internode, so the branch and the sapling above it stood up to 70 px higher than drawn."""

import numpy as np

from tests.test_modeler_tools import base_pixel, draw, press_menu


def test_the_renderer_draws_the_tree_where_the_modeler_has_it(modeler_game):
    game = modeler_game(seed=3)
    press_menu(game, "modeler")
    x0, y0 = base_pixel(game)
    draw(game, [(x0 + 6 * i, y0 - 8 * i) for i in range(40)])
    game.draw(game.fbo)
    world = game.world
    view = game.view.views[id(world)][1]
    segs = game.modeling.segments(world.tree.lstring)
    assert len(view.end) == len(segs)
    gap = np.linalg.norm(view.end - segs.end, axis=1).max()
    print(f"farthest segment end from the modeler's: {gap:.2e} units")
    assert gap < 1e-6
