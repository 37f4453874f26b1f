"""Per-branch editing (issue 48), in the real game headless: Prune's option button chooses cut, width,
angle or length; a tap picks the branch under it (its pieces lit), an up drag changes it, shown live and
committed as one undoable step when let go. The branch's width, its angle from its parent's axis and its
length change by what the drag asked, the rest of the tree not at all; a cut still cuts; undo puts each
back. Screenshots of the edits as the artist sees them (the picked branch lit) go to ARBOR_SHOTS if set."""

import os

import numpy as np
import pytest

from arbor.game.input.events import DOWN, MOVE, UP
from arbor.game.render.renderer import save_png
from tests.test_modeler_tools import base_pixel, draw, frame, overlay, press_bar, press_menu, touch


@pytest.fixture
def game(modeler_game):
    game = modeler_game(seed=3)
    press_menu(game, "modeler")
    x0, y0 = base_pixel(game)
    draw(game, [(x0 + 6 * i, y0 - 8 * i) for i in range(40)])  # a branch from the sapling's trunk
    game.branch_pixel = (x0 + 6 * 30, y0 - 8 * 30)
    press_bar(game, "prune")
    return game


def drag_up(game, pixels, shot=""):
    """An up drag of ``pixels`` away from the tree (the picked branch is what it edits)."""
    touch(game, DOWN, 0, 900, 500)
    for i in range(1, 11):
        game.clock_box[0] += 0.05
        touch(game, MOVE, 0, 900, 500 - pixels * i / 10)
    if shot and os.environ.get("ARBOR_SHOTS"):
        save_png(frame(game).astype(np.uint8), os.path.join(os.environ["ARBOR_SHOTS"], f"branch_{shot}.png"))
    game.clock_box[0] += 0.05
    touch(game, UP, 0, 900, 500 - pixels)


def picked(game):
    segs = game.modeling.segments(game.world.tree.lstring)
    first = game.modeling.prune_tool._first(segs)
    return segs, first, game.modeling.prune_tool._chosen(segs, first)


def angle_from_parent(segs, k):
    h, p = segs.end[k] - segs.start[k], segs.end[segs.parent[k]] - segs.start[segs.parent[k]]
    return float(np.degrees(np.arccos(h @ p / np.linalg.norm(h) / np.linalg.norm(p))))


def test_width_angle_and_length_of_one_branch(game):
    tree = game.world.tree.lstring
    press_bar(game, "edit")
    assert game.modeling.bar.widgets["edit"].label == "Branch: width"
    touch(game, DOWN, 0, *game.branch_pixel)
    touch(game, UP, 0, *game.branch_pixel)
    assert "Picked a branch of" in game.hud_info().message and not game.menu.visible
    segs0, first, branch = picked(game)
    assert branch.sum() >= 10 and first > 0
    lit = (np.abs(overlay(game)[..., :3].astype(int) - (255, 230, 90)).sum(axis=2) < 40).sum()
    assert lit > 100  # the picked branch is shown lit
    drag_up(game, 90, "width")  # 90 px: x2^(90/150) = x1.52
    segs1, _, _ = picked(game)
    ratio = segs1.radius / segs0.radius
    assert np.allclose(ratio[branch], 1.52, atol=0.01) and np.allclose(ratio[~branch], 1.0)
    assert "Branch width x1.52" in game.hud_info().message
    before = angle_from_parent(segs1, first)
    press_bar(game, "edit")
    drag_up(game, 100, "angle")  # 0.3 deg per pixel: 30 deg further from the trunk
    segs2, first2, _ = picked(game)
    print(f"width x{ratio[branch].mean():.2f}; angle {before:.1f} -> {angle_from_parent(segs2, first2):.1f} deg")
    assert abs(angle_from_parent(segs2, first2) - before - 30.0) < 0.5
    assert np.allclose(segs2.end[~branch], segs1.end[~branch])  # the rest of the tree stays
    assert np.allclose(np.linalg.norm(segs2.end - segs2.start, axis=1), np.linalg.norm(segs1.end - segs1.start, axis=1))
    press_bar(game, "edit")
    drag_up(game, 150, "length")  # x2
    segs3, _, _ = picked(game)
    length = np.linalg.norm(segs3.end - segs3.start, axis=1) / np.linalg.norm(segs2.end - segs2.start, axis=1)
    assert np.allclose(length[branch], 2.0) and np.allclose(length[~branch], 1.0)
    for _ in range(3):
        game.modeling.undo()
    assert game.world.tree.lstring.equals(tree)


def test_a_drag_on_a_branch_picks_it_and_cut_still_cuts(game):
    press_bar(game, "edit")
    press_bar(game, "edit")
    press_bar(game, "edit")
    assert game.modeling.prune_tool.op == "length"
    segs0 = game.modeling.segments(game.world.tree.lstring)
    x, y = game.branch_pixel
    touch(game, DOWN, 0, x, y)  # a drag that starts on the branch picks it and edits it at once
    for i in range(1, 11):
        game.clock_box[0] += 0.05
        touch(game, MOVE, 0, x, y - 6 * i)
    touch(game, UP, 0, x, y - 60)
    assert "Branch length x1.32" in game.hud_info().message
    assert len(game.modeling.segments(game.world.tree.lstring)) == len(segs0)
    press_bar(game, "edit")
    press_bar(game, "edit")  # (brush, then cut)
    assert game.modeling.prune_tool.op == "cut"
    touch(game, DOWN, 0, x + 20, y - 27)
    touch(game, UP, 0, x + 20, y - 27)
    assert "Cut" in game.hud_info().message
    assert len(game.modeling.segments(game.world.tree.lstring)) < len(segs0)


def test_an_angle_edit_turns_the_branch_rigidly_about_its_base():
    """engine/modeling/branch_edit.py: the branch (a stroke with a stroke drawn from it) turns as one rigid
    body about its base, about the axis at right angles to its parent's heading and its own; the drawn
    pieces' records of start and heading follow (a roll of the wrong sign bent it by 0.03 units)."""
    from arbor.engine.geometry.turtle import TurtleConfig, interpret, unit
    from arbor.engine.modeling.branch_edit import _rotation, branch_of, branch_span, edited, refreshed
    from arbor.engine.modeling.modeler import Modeler
    from arbor.engine.modeling.strokes import Stroke

    modeler, u = Modeler(), np.linspace(0, 1, 60)
    paths = ([0 * u, 3 * u, 0 * u], [1.5 * u, 2.0 + 1.2 * u, 0.4 * u], [1.0 + 0.3 * u, 2.7 + 0.8 * u, 0.25 - 0.6 * u])
    for path in paths:
        modeler.add_stroke(Stroke(np.stack(path, 1), np.linspace(0, 1.2, 60)))
    config = TurtleConfig(pipe_model=False, leaves_at_tips=0)
    ls = modeler.lstring
    segs = interpret(ls, config).segments
    first = branch_of(segs, int(np.argmax(segs.end[:, 0])))
    start, end = branch_span(ls, segs, first)
    branch = (segs.module >= start) & (segs.module < end)
    assert branch.sum() > 20 and (~branch).sum() > 10
    for degrees in (30.0, -20.0):
        new = edited(ls, segs, first, "angle", degrees)
        turned = interpret(new, config).segments
        h, parent = segs.frame[first][:, 0], segs.frame[segs.parent[first]][:, 0]
        q = _rotation(unit(np.cross(parent, h)), np.radians(degrees))
        expect = (segs.end[branch] - segs.start[first]) @ q.T + segs.start[first]
        assert np.abs(turned.end[branch] - expect).max() < 1e-9
        assert np.abs(turned.end[~branch] - segs.end[~branch]).max() == 0.0
        kept = refreshed(new, turned)
        rows = kept.params[kept.offsets[turned.module][:, None] + np.arange(1, 7)]
        assert np.allclose(rows, np.c_[turned.start, turned.frame[:, :, 0]])


def test_the_width_brush_widens_the_branches_it_passes_over(game):
    for _ in range(4):
        press_bar(game, "edit")
    assert game.modeling.prune_tool.op == "brush" and "Width brush" in game.modeling.hint()
    tree = game.world.tree.lstring
    segs0 = game.modeling.segments(tree)
    x, y = game.branch_pixel
    touch(game, DOWN, 0, x - 60, y - 40)  # a stroke across the drawn branch
    for i in range(1, 13):
        game.clock_box[0] += 0.03
        touch(game, MOVE, 0, x - 60 + 10 * i, y - 40 + 7 * i)
    touch(game, UP, 0, x + 60, y + 44)
    assert "Width brush: 1 branch made x1.25 as wide" in game.hud_info().message
    segs1 = game.modeling.segments(game.world.tree.lstring)
    ratio = segs1.radius / segs0.radius
    widened = ratio > 1.01
    assert widened.sum() >= 10 and np.allclose(ratio[widened], 1.25) and np.allclose(ratio[~widened], 1.0)
    touch(game, DOWN, 0, x, y)  # a tap brushes the branch again
    touch(game, UP, 0, x, y)
    ratio = game.modeling.segments(game.world.tree.lstring).radius / segs0.radius
    assert np.allclose(ratio[widened], 1.25**2)
    game.modeling.undo()
    game.modeling.undo()
    assert game.world.tree.lstring.equals(tree)
