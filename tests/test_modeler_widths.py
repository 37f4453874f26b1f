"""Widths an artist can trust (issue 48), in the real game headless: a trunk drawn fast (thin) from the
sapling's foot under a three-lobe crown is at least the pipe model's width at every height (the drawn
width is a floor, not a cap), and never tapers into the sapling's twig where the sapling carries on
from its top."""

import numpy as np
import pygame

from arbor.engine.life.form.interpret import pipe_area
from tests.test_modeler_tools import draw, press_bar, press_menu

LOBES = ((-120, 40), (0, -30), (120, 40))  # outline centres: pixels from the drawn trunk's top


def trunk_chain(segs) -> list[int]:
    """The main axis: from the base, the piece continuing each one (the tallest when several do)."""
    chain, k = [], 0
    while k >= 0:
        chain.append(k)
        children = np.flatnonzero((segs.parent == k) & segs.continues)
        k = int(children[np.argmax(segs.end[children, 1])]) if len(children) else -1
    return chain


def crowned_trunk(modeler_game):
    """A trunk drawn fast from the sapling's foot to above its top, the view framed (F), three outlines
    round its top; the main axis's heights, radii, pipe radii, which of its pieces are drawn, and the
    tree's segments."""
    game = modeler_game(seed=3)
    press_menu(game, "modeler")
    camera = game.camera()
    segs = game.modeling.segments(game.world.tree.lstring)
    (x0, y0), (_, y1) = (game.hud.project(camera, p) for p in ((0.0, 0.0, 0.0), (0.0, 1.5 * segs.end[:, 1].max(), 0.0)))
    draw(game, [(x0 + 1.5 * np.sin(i / 4), y0 + (y1 - y0) * i / 29) for i in range(30)], dt=0.004)  # fast: thin
    assert "became the trunk" in game.hud_info().message
    game.handle_event(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_f, mod=0, scancode=0, unicode="f"))  # frame
    press_bar(game, "crown")
    x0, y0 = game.hud.project(game.camera(), (0.0, 0.0, 0.0))
    _, top = game.hud.project(game.camera(), (0.0, 1.5 * segs.end[:, 1].max(), 0.0))
    a = np.linspace(0, 2 * np.pi, 48)
    for cx, cy in LOBES:
        draw(game, [(x0 + cx + 95 * np.cos(t), top + cy + 80 * np.sin(t)) for t in a])
    assert len(game.world.crown.lobes) == 3
    ls = game.world.tree.lstring
    segs = game.modeling.segments(ls)
    pipes = np.sqrt(pipe_area(ls, segs, game.world.tree.geometry_constants))
    chain = np.array(trunk_chain(segs))
    drawn = (ls.sym[segs.module[chain]] == ord("F")) & (ls.nparams[segs.module[chain]] == 11)
    return segs.start[chain, 1], segs.radius[chain], pipes[chain], drawn, segs


def test_a_drawn_trunk_under_a_crown_is_at_least_the_pipe_width_at_every_height(modeler_game):
    height, radius, pipe, drawn, segs = crowned_trunk(modeler_game)
    top = height.max()
    at = int(np.argmin(np.abs(height - 0.37 * top)))
    print(f"trunk: {drawn.sum()} drawn pieces, {len(drawn) - drawn.sum()} grown; at 37 % of its height radius "
          f"{radius[at]:.3f} m, pipe model {pipe[at]:.3f} m; base {radius[0]:.3f} m (pipe {pipe[0]:.3f} m)")
    assert drawn.sum() >= 5 and (~drawn).sum() >= 1  # drawn from the foot, the sapling on top
    assert (radius >= pipe * 0.999).all()  # every height
    crown_width = float(np.ptp(segs.end[:, 0]))
    assert radius[at] >= 0.02 * crown_width  # not a twig under a crown this wide
    carried = height < height[~drawn].min() + 0.5  # the drawn trunk and where the sapling carries on
    assert (np.diff(radius[carried]) <= 1e-9).all()  # it tapers upward only, never down into a twig
