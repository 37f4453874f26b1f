"""The crown's lobes are part of the tree (issue 48), through the real game headless: after Done they are
there again with Shape (drawn, and a drag regrows the crown into the moved lobe); a save and a restart
keep them (format 3's [trees.crown]); undo takes a lobe away and redo brings it back; a hostile
[trees.crown] is refused with the file, line and column; a format 2 save loads without lobes."""

import re

import numpy as np
import pytest

from arbor.engine.life.keep.save import read_garden
from arbor.engine.life.keep.save_check import SaveError
from arbor.game.screens.game import Game, GameConfig
from tests.conftest import MODELER_SIZE
from tests.test_modeler_tools import SCENE, base_pixel, draw, overlay, press_bar, press_menu


@pytest.fixture
def game(modeler_game):
    return modeler_game(seed=3)


def outline(game, dx=0.0):
    x0, y0 = base_pixel(game)
    a = np.linspace(0, 2 * np.pi, 48)
    draw(game, [(x0 + dx + 110 * np.cos(t), y0 - 300 + 90 * np.sin(t)) for t in a])


def rings_shown(game):
    return int((overlay(game)[SCENE][..., 3] > 0).sum())


def drag_lobe(game, lobe, dx):
    """A Shape drag from the lobe's middle ``dx`` pixels to the right."""
    x, y = game.hud.project(game.camera(), tuple(lobe.vertices.mean(axis=0)))
    draw(game, [(x + dx * k / 10, y) for k in range(11)], dt=0.05)


def test_lobes_stay_after_done_and_are_edited_again(game):
    press_menu(game, "modeler")
    press_bar(game, "crown")
    outline(game)
    lobe = game.world.crown.lobes[0]
    press_bar(game, "modeler")  # Done
    assert not game.modeling.active and game.world.crown.lobes[0] is lobe  # kept with the tree
    press_menu(game, "modeler")
    assert rings_shown(game) == 0  # (Draw shows no lobes)
    press_bar(game, "shape")
    assert rings_shown(game) > 800 and game.modeling.crown_tool.state().lobes == [lobe]  # shown with Shape
    before = game.world.tree.lstring
    drag_lobe(game, lobe, 80)
    moved = game.world.crown.lobes[0]
    shift = moved.vertices.mean(axis=0) - lobe.vertices.mean(axis=0)
    assert np.hypot(shift[0], shift[2]) > 0.3 and "Lobe move" in game.hud_info().message
    assert game.world.tree.lstring is not before
    game.modeling.undo()
    assert game.world.crown.lobes[0] is lobe and game.world.tree.lstring is before  # undo: the old lobe back
    game.modeling.redo()
    assert game.world.crown.lobes[0] is moved


def test_undo_takes_a_lobe_away_and_says_so(game):
    press_menu(game, "crown")
    outline(game, -120)
    outline(game, 120)
    assert len(game.world.crown.lobes) == 2
    game.modeling.undo()
    assert len(game.world.crown.lobes) == 1 and "the crown in 1 lobe" in game.hud_info().message
    game.modeling.undo()
    assert game.world.crown is None and "no crown lobes" in game.hud_info().message
    game.modeling.redo()
    assert len(game.world.crown.lobes) == 1


def test_lobes_are_saved_and_come_back_after_a_restart(game, gl_ctx, tmp_path):
    press_menu(game, "crown")
    outline(game)
    crown, tree = game.world.crown, game.world.tree.lstring.to_text()
    press_bar(game, "modeler")
    assert game.save()
    text = (tmp_path / "autosave.arbor").read_text()
    assert "format = 3" in text and "[trees.crown]" in text and "crown_base = '''" in text
    back = read_garden(tmp_path / "autosave.arbor").world  # loaded as saved: the crown regrows from its base
    assert back.crown.base.to_text() == crown.base.to_text()
    assert back.crown.base_for(back.tree.lstring) is back.crown.base
    assert np.allclose(back.crown.lobes[0].vertices, crown.lobes[0].vertices, atol=1e-5)
    assert (back.crown.lobes[0].faces == crown.lobes[0].faces).all() and back.tree.lstring.to_text() == tree
    clock = [0.0]
    again = Game(gl_ctx, MODELER_SIZE, GameConfig(saves=tmp_path, seed=3, resume=True), clock=lambda: clock[0])
    again.clock_box = clock
    assert again.world.crown is not None and len(again.world.crown.lobes) == 1  # the restart kept it
    press_menu(again, "modeler")
    press_bar(again, "shape")
    assert rings_shown(again) > 800
    drag_lobe(again, again.world.crown.lobes[0], -70)
    assert "Lobe move" in again.hud_info().message and again.world.crown.lobes[0] is not crown.lobes[0]


def hostile(game, tmp_path, change):
    press_menu(game, "crown")
    outline(game)
    assert game.save()
    path = tmp_path / "autosave.arbor"
    text = change(path.read_text())
    path.write_text(text)
    with pytest.raises(SaveError) as err:
        read_garden(path)
    return str(err.value), text


@pytest.mark.parametrize("change, words, key", [
    (lambda t: re.sub(r'lobe_faces = \["\d+', 'lobe_faces = ["99999', t), "triangles", "lobe_faces"),
    (lambda t: re.sub(r'lobe_vertices = \["[-\d.e]+', 'lobe_vertices = ["nan', t), "finite", "lobe_vertices"),
    (lambda t: re.sub(r'lobe_vertices = \["[-\d.e]+', 'lobe_vertices = ["x', t), "numbers only", "lobe_vertices"),
    (lambda t: t.replace("lobe_rings = [", "lobe_rings = [" + "7, " * 16), "at most 16", "lobe_rings"),
    (lambda t: t.replace("lobe_ring_sizes = [", "lobe_ring_sizes = [999, "), "same length", "lobe_faces"),
    (lambda t: re.sub(r"lobe_rings = \[\d+", "lobe_rings = [900", t), "whole number from 0", "lobe_rings"),
    (lambda t: re.sub(r"lobe_rings = \[\d+", "lobe_rings = [100", t), "rings of", "lobe_rings"),
    (lambda t: re.sub(r"lobe_ring_sizes = \[\d+", "lobe_ring_sizes = [0", t), "rings of", "lobe_rings"),
    (lambda t: re.sub(r"lobe_rings = \[\d+", "lobe_rings = [1", t), "rings of", "lobe_rings"),
    (lambda t: t.replace("crown_base = '''\n", "crown_base = '''\n]]"), "without a matching", "crown_base"),
    (lambda t: t.replace("crown_base = '''\n", "crown_base = '''\nF(zz)"), "crown base", "crown_base+1:3"),
])
def test_a_hostile_crown_is_refused_with_where_it_is(game, tmp_path, change, words, key):
    message, text = hostile(game, tmp_path, change)
    key, _, below = key.partition("+")  # (an error inside the crown base's block: the line below the key)
    line = next(i for i, row in enumerate(text.splitlines(), 1) if row.startswith(f"{key} ="))
    at = f"{line + int(below[0])}:{below[2:]}" if below else f"{line}:"
    assert words in message and f"autosave.arbor:{at}" in message.replace(str(tmp_path) + "/", ""), message


def test_a_format_2_save_loads_without_lobes(game, tmp_path):
    press_menu(game, "crown")
    outline(game)
    assert game.save()
    path = tmp_path / "autosave.arbor"
    text = path.read_text()
    path.write_text(text[:text.index("[trees.crown]")].replace("format = 3", "format = 2"))
    back = read_garden(path).world
    assert back.crown is None and back.tree.lstring.to_text() == game.world.tree.lstring.to_text()


def test_a_crown_the_tree_could_not_keep_is_not_grown_and_says_why(game):
    """More lobes, or a lobe of more points, than a save holds: the crown is refused with its reason and the
    tree stays as it was (before, the save dropped lobes past the 16th or wrote one its reader refused)."""
    from arbor.engine.life.world.commands import Crown
    from arbor.engine.modeling.crowned import MAX_LOBE_VERTICES, MAX_LOBES
    from arbor.engine.modeling.lobes import Lobe

    press_menu(game, "crown")
    outline(game)
    world, lobe = game.world, game.world.crown.lobes[0]
    before = world.tree.lstring
    many = world.apply(Crown(before, (lobe,) * (MAX_LOBES + 1)))
    huge = Lobe(np.zeros((MAX_LOBE_VERTICES + 1, 3)), lobe.faces, lobe.ring_size, 0)
    big = world.apply(Crown(before, (huge,)))
    assert f"at most {MAX_LOBES}" in many.refused and "points" in big.refused and world.tree.lstring is before

