"""A crown grows with the light it catches, not with the number of its buds (engine/life/plant/growth.py)."""

from __future__ import annotations

import numpy as np
import pytest

from arbor.engine.base.assets import assets_dir
from arbor.engine.life.form.interpret import CLUSTER_AREA, LEAF_ASPECT, Clocks
from arbor.engine.life.plant import growth
from arbor.engine.life.plant.growth import GrowingTree
from arbor.engine.life.plant.light import exposure
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.lsystem.lstring import parse_lstring
from arbor.engine.lsystem.lsys import load_lsystem

NOW = 100.0


def _bush(twigs: int, leaves: int) -> str:
    """A trunk with ``twigs`` short lit shoots, each with an apex, and ``leaves`` leaf clusters on the trunk."""
    trunk = "".join(f"+(0)^(0)/(137.5)I({k},{k},0,0,0)[&(60)L(50,1,0)]" for k in range(leaves))
    shoots = "".join(f"[&(50)/({k * 37 % 360})I(60,60,1,0,0)A(0,1,0,1,0,0)]" for k in range(twigs))
    return "I(0,0,0,0,0)" + trunk + shoots + "A(0,0,0,1,0,0)"


def _read(tree: GrowingTree) -> tuple[np.ndarray, float]:
    """One light reading at noon (with a memory so short that it is all the apices remember); returns the
    apices' remembered vigour and the tree's light income (fully lit leaf clusters' worth)."""
    rules = load_rules(assets_dir() / "rules.toml")
    clocks = Clocks(NOW, NOW, 0.0)
    scene = tree.light_scene(clocks)
    sun = np.array([0.3, 1.0, 0.2])
    light = exposure(scene.leaf_center, scene.leaf_area, scene.queries, sun, rules.light,
                     np.concatenate([np.arange(len(scene.leaf_idx)), np.full(len(scene.queries) - len(scene.leaf_idx),
                                                                              -1)]))
    tree.last_sense_length, tree.last_sense_girth = NOW - 1.0, NOW
    tree.sense(scene, light, clocks, 1.0, sun, 0.01)  # (a short memory: the reading is all it remembers)
    income = float((light[:len(scene.leaf_idx)] * scene.leaf_area).sum()) / (
        CLUSTER_AREA * LEAF_ASPECT * tree.geometry_constants["LS"] ** 2)
    ls = tree.lstring
    apex = np.flatnonzero((ls.sym == ord("A")) & (ls.nparams == 6))
    return ls.params[ls.offsets[apex] + 3], income


@pytest.mark.parametrize(("twigs", "leaves"), [(2, 120), (40, 30)])
def test_the_apices_share_no_more_vigour_than_the_leaves_light_sustains(twigs, leaves, monkeypatch):
    system = load_lsystem(assets_dir() / "lsystems" / "game_tree.lsys")
    text = _bush(twigs, leaves)
    vigour, income = _read(GrowingTree(system, seed=1, lstring=parse_lstring(text)))
    cap = growth.GROWTH_PER_LIGHT * income + growth.FREE_VIGOUR
    monkeypatch.setattr(growth, "GROWTH_PER_LIGHT", np.inf)
    own, _ = _read(GrowingTree(system, seed=1, lstring=parse_lstring(text)))  # each apex's own light
    assert len(vigour) == twigs + 1 and vigour.sum() <= cap * (1 + 1e-9)
    if twigs == 2:  # a few buds on a leafy trunk: each grows as its own light allows
        assert own.sum() < cap and vigour == pytest.approx(own)
    else:  # many buds share what the same leaves catch, in proportion to their own light
        assert own.sum() > 2 * cap and vigour == pytest.approx(own * cap / own.sum())
