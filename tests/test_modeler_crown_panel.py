"""The crown panel with presets (issue 48), in the real game headless: the Crown tool's option button
opens it; a press on - regrows the crown with that option one step down (leaf size: no crown leaf over
0.7 of a species leaf after three presses), the preset row takes the next preset (each a data file's values,
assets/crowns.toml), each change one undoable step; undo gives the crown back as it was. A screenshot
of the panel goes to ARBOR_SHOTS if set. assets/crowns.toml is read strictly."""

import os

import numpy as np
import pytest

from arbor.engine.base.errors import SettingsError
from arbor.engine.modeling.crown_style import load_styles
from arbor.game.render.renderer import save_png
from tests.test_modeler_tools import base_pixel, draw, frame, press_bar, press_menu


def crown_leaf_sizes(game) -> np.ndarray:
    ls = game.world.tree.lstring
    idx = np.flatnonzero((ls.sym == ord("L")) & (ls.nparams == 2))
    return ls.params[ls.offsets[idx] + 1]


def press(game, rect):
    """A finger on a panel button (real SDL finger events through the game's translator)."""
    from arbor.game.input.events import DOWN, UP
    from tests.test_modeler_tools import finger

    finger(game, DOWN, *rect.center)
    finger(game, UP, *rect.center)


def test_the_panel_regrows_the_crown_one_undoable_step_at_a_time(modeler_game):
    game = modeler_game(seed=3)
    press_menu(game, "crown")
    x0, y0 = base_pixel(game)
    a = np.linspace(0, 2 * np.pi, 48)
    draw(game, [(x0 + 110 * np.cos(t), y0 - 300 + 90 * np.sin(t)) for t in a])
    panel, bar = game.modeling.crown_panel, game.modeling.bar
    assert not panel.visible and bar.widgets["edit"].label == "Crown style"
    press_bar(game, "edit")
    assert panel.visible and bar.widgets["edit"].label == "Style: close"
    tree, sizes = game.world.tree.lstring, crown_leaf_sizes(game)
    for _ in range(3):
        press(game, panel.buttons[("minus", "leaf_size")].rect)
    assert game.world.crown.style.leaf_size == pytest.approx(0.7)
    assert "Crown regrown with Leaf size 0.7 x leaf" in game.hud_info().message
    smaller = crown_leaf_sizes(game)
    print(f"crown leaves' size at most {sizes.max():.2f} -> {smaller.max():.2f} of a species leaf (median "
          f"{np.median(sizes):.2f} -> {np.median(smaller):.2f})")
    assert smaller.max() <= 0.7 + 1e-9 and np.median(smaller) < 0.8 * np.median(sizes)
    press(game, panel.buttons[("preset", "")].rect)  # default -> dense: two leaves a tip, shorter twigs
    assert panel.preset == "dense" and game.world.crown.style.leaves == 2.0
    assert len(crown_leaf_sizes(game)) > 1.5 * len(sizes)
    if os.environ.get("ARBOR_SHOTS"):
        save_png(frame(game).astype(np.uint8), os.path.join(os.environ["ARBOR_SHOTS"], "crown_panel.png"))
    game.modeling.undo()
    assert game.world.crown.style.leaf_size == pytest.approx(0.7) and game.world.crown.style.leaves == 1.0
    for _ in range(3):
        game.modeling.undo()
    assert game.world.tree.lstring is tree
    press_bar(game, "draw")
    assert not panel.visible  # (another tool closes it)


def test_a_strict_reader_for_the_panels_file(tmp_path):
    options, presets = load_styles()
    assert {"twig", "fork", "straight", "rise", "leaf_size", "leaves"} <= set(options)
    assert all(o.meaning and o.low <= o.default <= o.high for o in options.values()) and "default" in presets
    bad = tmp_path / "crowns.toml"
    bad.write_text('[options.leaf_size]\ndefault = 9.0\nmin = 0.3\nmax = 2.0\nstep = 0.1\nunit = "x"\nmeaning = "m"\n')
    with pytest.raises(SettingsError, match="min <= default <= max"):
        load_styles(bad)
    bad.write_text("[presets.x]\ncolour = 3\n")
    with pytest.raises(SettingsError, match="may set only"):
        load_styles(bad)
    bad.write_text("[options\n")
    with pytest.raises(SettingsError, match=r"crowns.toml:1"):
        load_styles(bad)


def test_the_crown_style_is_kept_in_the_save(modeler_game, tmp_path):
    """A crown grown with a preset keeps its style through a save (format 3's [trees.crown] crown_style);
    a style out of its range is refused with the key's line."""
    import re

    from arbor.engine.life.keep.save import read_garden
    from arbor.engine.life.keep.save_check import SaveError

    game = modeler_game(seed=3)
    press_menu(game, "crown")
    x0, y0 = base_pixel(game)
    draw(game, [(x0 + 110 * np.cos(t), y0 - 300 + 90 * np.sin(t)) for t in np.linspace(0, 2 * np.pi, 48)])
    press_bar(game, "edit")
    press(game, game.modeling.crown_panel.buttons[("preset", "")].rect)
    style = game.world.crown.style
    press_bar(game, "modeler")
    assert game.save()
    path = tmp_path / "autosave.arbor"
    assert "crown_style = {" in path.read_text()
    assert read_garden(path).world.crown.style == style
    path.write_text(re.sub(r"leaf_size = [\d.]+", "leaf_size = 99", path.read_text()))
    with pytest.raises(SaveError, match=r"leaf_size must be a number from 0\.3 to 2") as err:
        read_garden(path)
    assert ":" in str(err.value).split("autosave.arbor")[1]  # file:line:column
