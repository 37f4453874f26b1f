"""A crown's leaves held within the lobe drawn (issue 48), in the real game headless: one outline drawn
with a shaky hand, and every corner of every leaf blade of the crown, as shown now and fully grown, is
within 10 % of the outline's size from the outline in the view it was drawn in (before: up to 56 %
outside, the leaf cards standing well clear of the drawn crown), while the leaves keep a visible size."""

import numpy as np
from matplotlib.path import Path
from scipy.spatial import cKDTree

from arbor.engine.life.form.interpret import LEAF_ASPECT, grown_turtle
from arbor.game.render.camera import project_points
from tests.conftest import MODELER_SIZE
from tests.test_modeler_tools import base_pixel, draw, press_menu


def outside_share(pixels: np.ndarray, outline: np.ndarray) -> np.ndarray:
    """Each pixel's distance outside the closed ``outline`` (0 inside), over the outline's size."""
    dense = np.concatenate([np.linspace(outline[i], outline[(i + 1) % len(outline)], 12, endpoint=False)
                            for i in range(len(outline))])
    gap = np.where(Path(outline).contains_points(pixels), 0.0, cKDTree(dense).query(pixels)[0])
    return gap / float(np.ptp(outline, axis=0).max())


def corners(leaves, grown: float = 1.0) -> np.ndarray:
    """The four corners of every blade (engine/geometry/mesh.py leaf_mesh), its size times ``grown``."""
    h, lft = leaves.frame[:, :, 0], leaves.frame[:, :, 1]
    s = leaves.size[:, None] * grown
    half = lft * s * LEAF_ASPECT * 0.5
    p = leaves.position
    return np.stack([p - half, p + half, p + half + h * s, p - half + h * s], axis=1).reshape(-1, 3)


def test_one_lobe_drawn_holds_its_leaves(modeler_game):
    game = modeler_game(seed=3)
    press_menu(game, "crown")
    x0, y0 = base_pixel(game)
    a = np.linspace(0, 2 * np.pi, 48)
    outline = np.stack([x0 + 110 * np.cos(a), y0 - 300 + 90 * np.sin(a)], 1)
    outline += np.random.default_rng(1).normal(0.0, 1.5, outline.shape)  # a shaky hand
    camera = game.camera()  # the view it is drawn in
    draw(game, [tuple(p) for p in outline])
    assert "into the outline" in game.hud_info().message
    world = game.world
    ls = world.tree.lstring
    leaves = grown_turtle(ls, world.clocks(), world.tree.geometry_constants).leaves
    crown = ls.nparams[leaves.module] == 2  # the crown's leaves, L(birth, size)
    assert crown.sum() >= 300
    blades = type(leaves)(leaves.position[crown], leaves.frame[crown], leaves.size[crown], leaves.module[crown])
    shown = outside_share(project_points(camera, MODELER_SIZE, corners(blades)), outline)
    full = outside_share(project_points(camera, MODELER_SIZE, corners(blades, 1 / (1 - np.exp(-1)))), outline)
    sizes = ls.params[ls.offsets[np.unique(blades.module)] + 1]
    print(f"leaf corners outside the outline: {np.mean(shown > 0):.1%}; farthest {shown.max():.1%} of the outline's"
          f" size as shown, {full.max():.1%} fully grown; leaf sizes median {np.median(sizes):.2f}")
    assert shown.max() <= 0.10 and full.max() <= 0.10
    assert np.median(sizes) >= 0.25  # leaves, not specks: turned back along their twigs where room is short
