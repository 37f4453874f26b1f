"""The confinement a Grow edit sets is kept in the save (issue 48): a Grow in a region (a sphere, or a
supertoroid from two outlines) holds the tree's growth there for 20 rewrites, and a save and load keep
the region and the rewrites left ([trees.confine], format 3; before, a load dropped it and the tree grew
everywhere). A hostile [trees.confine] is refused with the file, line and column."""

import re

import pytest

from arbor.engine.life.keep.save import read_garden
from arbor.engine.life.keep.save_check import SaveError
from arbor.engine.life.world.commands import RegionEdit
from arbor.engine.modeling.regions import Sphere, Supertoroid
from tests.test_modeler_tools import press_menu


@pytest.mark.parametrize("region", [Sphere((0.1, 0.6, 0.0), 0.5),
                                    Supertoroid(0.8, 0.6, 0.7, 0.9, n=0.8, e=1.2, yaw=30.0, slope_x=0.1)])
def test_a_grow_confinement_survives_save_and_load(modeler_game, tmp_path, region):
    game = modeler_game(seed=3)
    press_menu(game, "modeler")
    game.world.apply(RegionEdit("grow", region, game.modeling.edit_sets["grow"]))
    tree = game.world.tree
    assert tree.confine is region and tree.confine_left == 20
    press_menu(game, "modeler")  # Done
    assert game.save()
    path = tmp_path / "autosave.arbor"
    back = read_garden(path).world.tree
    assert back.confine == region and back.confine_left == 20
    text = path.read_text()
    path.write_text(re.sub(r"left = 20", "left = 0", text))
    with pytest.raises(SaveError, match="'left' must be a whole number from 1") as err:
        read_garden(path)
    assert re.search(r"autosave\.arbor:\d+:\d+", str(err.value))
