"""Pruning as an experiment factor (issue 30): a lab tree on a pruning schedule is cut back (World.prune),
the cut is booked in the journal and the carbon budget, and the pruned tree ends smaller than an
unpruned one of the same seed."""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest

from arbor.engine.base.units import METRE
from arbor.engine.life.experiment.lab import Lab, load_experiment
from arbor.engine.life.experiment.measure import measure
from arbor.engine.life.keep.save import read_garden, save_text
from arbor.engine.life.plant.carbon import AREA
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.rules.schema import find_rule
from arbor.engine.life.world.commands import Prune
from arbor.game.paths import ASSETS

DAY = 2 * math.pi / find_rule("sun.speed").default  # s: a day of the sun at the default sun speed
LAB = f"""title = "Pruning"
seed = 4
duration = {10 * DAY:.0f}
sample_every = {DAY}
seasons = false

[[tree]]
name = "Unpruned"
watering = {{ below = 0.5, until = 0.7 }}

[[tree]]
name = "Topped"
watering = {{ below = 0.5, until = 0.7 }}
prune = {{ every_days = 3, keep_height = 0.5 }}

[[tree]]
name = "Raised"
watering = {{ below = 0.5, until = 0.7 }}
prune = {{ every_days = 3, lowest = 0.4 }}
"""


@pytest.fixture(scope="module")
def lab(tmp_path_factory):
    path = tmp_path_factory.mktemp("prune") / "prune.toml"
    path.write_text(LAB, encoding="utf-8")
    lab = Lab(load_experiment(path, ASSETS / "lsystems"), load_rules(ASSETS / "rules.toml", "demo"))
    lab.run()
    return lab


def finals(lab) -> dict[str, dict[str, float]]:
    return {s.name: {k: v[-1] for k, v in s.values.items()} for s in lab.series}


def test_a_pruned_tree_is_smaller_than_an_unpruned_one_of_the_same_seed(lab):
    end = finals(lab)
    free, topped, raised = end["Unpruned"], end["Topped"], end["Raised"]
    assert free["height"] > 0.7 and topped["height"] < 0.5 + 0.2  # (a day's growth since the last cut)
    assert topped["biomass"] < 0.9 * free["biomass"] and topped["leaf_area"] < free["leaf_area"]
    assert raised["biomass"] < 0.6 * free["biomass"]  # the lowest branches carry most of the leaves
    assert raised["height"] > 0.9 * free["height"]  # crown raising leaves the leader alone
    assert free["pruned"] == 0 and topped["pruned"] > 0 and raised["pruned"] > 0
    low = [float(w.tree.geometry(w.clocks()).turtle.leaves.position[:, 1].min()) / METRE for w in lab.worlds]
    assert low[2] > low[0] + 0.2  # raised: the crown starts higher up the trunk (its lowest leaf, m)


def test_the_journal_records_each_pruning_and_a_save_keeps_it(lab, tmp_path):
    raised = lab.worlds[2]
    cuts = [(t, v) for t, kind, v in raised.journal.entries if kind == "pruned"]
    assert [round(t / DAY) for t, _ in cuts] == [3, 6, 9]  # every 3 game days (the first after 3)
    assert sum(v for _, v in cuts) == finals(lab)["Raised"]["pruned"]
    path = tmp_path / "raised.arbor"
    path.write_text(save_text(raised, "game_tree.lsys"), encoding="utf-8")
    back = read_garden(path).worlds[0]
    assert [e for e in back.journal.entries if e[1] == "pruned"] == [e for e in raised.journal.entries
                                                                     if e[1] == "pruned"]


def test_a_cut_keeps_the_carbon_budget_and_the_wood_consistent(lab):
    world = copy.deepcopy(lab.worlds[0])
    before = measure(world)
    girth, pool, built = before["girth"], world.carbon.pool, world.carbon.built
    sapwood, modules = world.carbon.sapwood, len(world.tree.lstring)
    cut = world.apply(Prune(keep_height=0.6))
    after = measure(world)
    assert cut > 0 and after["height"] <= 0.6 + 1e-9 and len(world.tree.lstring) < modules
    now = world.sim.state.length_time
    assert math.isclose(world.carbon.leaf_area, world.tree.leaf_area(now) * AREA, rel_tol=1e-9)  # measured anew
    assert world.carbon.leaf_area < before["leaf_area"] and world.carbon.sapwood < sapwood  # less upkeep
    assert after["girth"] == girth  # the trunk keeps the wood it built
    assert world.carbon.pool == pool and world.carbon.built == built  # store and totals untouched
    fallen = world.tree.fallen[-1]
    assert len(fallen.segments) > 0 and float(fallen.segments.end[:, 1].max()) > 0.6 * METRE
    assert world.journal.entries[-1][1:] == ("pruned", float(cut))


def test_a_cut_counts_branches_once_and_keeps_the_trunks_base(lab):
    world = copy.deepcopy(lab.worlds[0])
    assert world.apply(Prune(keep_height=0.001)) == 1  # everything above the first piece: one cut
    segs = world.tree.geometry(world.clocks()).turtle.segments
    assert len(segs) == 1 and np.isclose(segs.start[0, 1], 0.0)
    assert world.apply(Prune(lowest=1.0)) == 0 and world.apply(Prune()) == 0  # nothing left to cut, nothing asked


def test_a_cut_inside_a_branch_already_cut_is_not_counted_again():
    from arbor.engine.life.world.prune import branches_cut
    from arbor.engine.lsystem.lstring import parse_lstring

    sym = parse_lstring("F[F[F]F]F").sym  # 0 F, 1 [, 2 F, 3 [, 4 F, 5 ], 6 F, 7 ], 8 F
    assert branches_cut(sym, np.array([2, 4])) == 1  # 4 grows from 2
    assert branches_cut(sym, np.array([2, 8])) == 2  # a branch and the leader above it
    assert branches_cut(sym, np.array([4, 6])) == 2  # two pieces of one branch, neither inside the other's cut
