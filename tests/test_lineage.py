"""Lineage: crossing L-systems, family records that survive saves (and hostile ones that do not), roots
grown by a second L-system that spare water, shoots that grow around rocks and neighbours."""

import copy
import math
import re
from pathlib import Path

import numpy as np
import pytest

from arbor.engine.life.experiment.lab import measure
from arbor.engine.life.keep.save import SavedGarden, read_garden, write_garden
from arbor.engine.life.lineage.breed import cross
from arbor.engine.life.lineage.lineage import Family, lineage_from_row, new_lineage
from arbor.engine.life.plant.collide import Obstacles, rocks
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.garden import Garden
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import load_lsystem

ASSETS = Path(__file__).resolve().parent.parent / "assets"


@pytest.fixture(scope="module")
def parents():
    return load_lsystem(ASSETS / "lsystems" / "game_tree.lsys"), load_lsystem(ASSETS / "lsystems" / "game_poplar.lsys")


def rules(seasons=False):
    r = load_rules(ASSETS / "rules.toml", pace="demo")
    r.seasons.enabled = seasons
    return r


def grow(world: World, days: float, garden: Garden | None = None) -> World:
    garden = garden or Garden([world])
    world.sim.state.sun_meter = world.sim.state.water_meter = 0.9
    for _ in range(int(days * 2 * math.pi / world.sim.state.sun_speed / 0.5)):
        for w in garden.worlds:
            s = w.sim.state
            w.apply(Action.WATER, float(s.water_meter < 0.75 if s.watering else s.water_meter < 0.55))
        garden.step(0.5)
    return world


def test_a_cross_is_deterministic_and_takes_from_both_parents(parents):
    tree, poplar = parents
    a, b = cross(tree, poplar, 7), cross(tree, poplar, 7)
    assert a.source == b.source
    assert cross(tree, poplar, 8).source != a.source
    for seed in range(40):
        child = cross(tree, poplar, seed)
        for name in ("BA", "IL", "HK", "LS", "IO"):
            low, high = sorted((tree.constants[name], poplar.constants[name]))
            assert low * 0.8 - 1 <= child.constants[name] <= high * 1.2 + 1, (seed, name)
    taken = [cross(tree, poplar, s).from_father for s in range(40)]
    assert any("p1" in t for t in taken) and any("p1" not in t for t in taken)  # a coin per production
    angles = {round(cross(tree, poplar, s).constants["BA"]) for s in range(40)}
    assert len(angles) > 10 and any(26 < a < 48 for a in angles)  # mixed values, not one parent's


@pytest.mark.parametrize("seed", range(6))
def test_every_cross_grows(parents, seed):
    child = cross(*parents, seed)
    world = grow(World(child.system, rules(), seed=seed), 2)
    sapling = len(World(child.system, rules(), seed=seed).tree.lstring)
    assert world.sim.state.alive and len(world.tree.lstring) > sapling + 30


def test_a_child_resembles_both_parents(parents):
    # (height: the pioneer poplar's free growth makes it the taller parent by far, 1.67 m against 1.02 at day 6)
    heights = [measure(grow(World(system, rules(), seed=3), 6))["height"] for system in parents]
    child = measure(grow(World(cross(*parents, 3).system, rules(), seed=3), 6))["height"]
    assert min(heights) < child < max(heights)


def test_lineage_survives_a_save_and_hostile_entries_are_dropped(parents, tmp_path):
    garden = Garden([World(parents[0], rules(), seed=1)])
    garden.plant(parents[1], rules(), now=1.7e9)
    child = garden.breed(garden.worlds[0], garden.worlds[1], 5, rules(), now=1.7e9 + 60)
    assert child.lineage.generation == 1 and set(child.lineage.parents) == {w.lineage.id for w in garden.worlds[:2]}
    path = tmp_path / "g.arbor"
    write_garden(SavedGarden(garden.worlds, 2, 1.7e9, [], garden.family), path)
    saved = read_garden(path, rules())
    assert [w.lineage for w in saved.worlds] == [w.lineage for w in garden.worlds]
    assert saved.family.members == garden.family.members and saved.dropped == 0
    text = path.read_text()
    head, _, tail = text.rpartition(f'id = "{child.lineage.id}"')  # the tree's own record (the last)
    text = head + 'id = "../../etc/passwd"' + tail  # a hostile tree record
    text = text.replace("family = [\n", "family = [\n"
                        '{id = "0123456789abcdef", parents = ["0123456789abcdef"], generation = 1, seed = 1, '
                        'planted = 1.0, species = "x"},\n'
                        '{id = "aaaaaaaaaaaaaaaa", parents = [], generation = -4, seed = 1, planted = 1.0, '
                        'species = "x"},\n'
                        '{id = "bbbbbbbbbbbbbbbb", parents = [], generation = 1, seed = 1, planted = nan, '
                        'species = "x"},\n'
                        '{id = "cccccccccccccccc", parents = [], generation = 1, seed = 1, planted = 1.0, '
                        'species = "<script>"},\n', 1)
    path.write_text(text)
    again = read_garden(path, rules())
    assert again.dropped == 5
    assert again.worlds[2].lineage.parents == ()  # an untrusted record is replaced, never trusted
    assert all(re.fullmatch(r"[0-9a-f]{16}", m) for m in again.family.members)


def test_family_rows_cut_impossible_links():
    a = new_lineage(1, 0.0, "game_tree")
    b = new_lineage(2, 0.0, "game_tree", (a,))
    rows = [a.to_row(), b.to_row(), {**a.to_row(), "id": "dddddddddddddddd", "parents": [b.id], "generation": 0}]
    family, dropped = Family.from_rows(rows)
    assert dropped == 1 and family.get("dddddddddddddddd").parents == ()  # a parent younger than its child
    assert family.ancestors(b) == [a]
    assert lineage_from_row({**a.to_row(), "parents": [a.id, b.id, "eeeeeeeeeeeeeeee"]}) is None  # three parents


def test_arbor_breed_and_lineage_on_the_command_line(parents, tmp_path, capsys):
    from arbor.game.cli import main

    for name, system in zip(("a", "b"), parents, strict=True):
        world = World(system, rules(), seed=4)
        world.lineage = new_lineage(4, 1.7e9, name)
        write_garden(SavedGarden([world], 0, 1.7e9, lsystem_name=f"{name}.lsys"), tmp_path / f"{name}.arbor")
    for out in ("c1", "c2"):
        assert main(["breed", str(tmp_path / "a.arbor"), str(tmp_path / "b.arbor"), "--seed", "9",
                     "--out", str(tmp_path / f"{out}.arbor")]) == 0
    one, two = (read_garden(tmp_path / f"{o}.arbor", rules()).worlds[0] for o in ("c1", "c2"))
    assert one.system.source == two.system.source  # the same seed, the same child
    assert main(["lineage", str(tmp_path / "c1.arbor")]) == 0
    out = capsys.readouterr().out
    assert "generation 1" in out and out.count("generation 0") == 2 and " a, " in out and " b, " in out
    assert main(["breed", str(tmp_path / "nothere.arbor"), str(tmp_path / "b.arbor")]) == 1


def test_roots_grow_on_water_and_spare_it():
    wet = grow(World(load_lsystem(ASSETS / "lsystems" / "game_tree.lsys"), rules(), seed=2), 3)
    dry = World(load_lsystem(ASSETS / "lsystems" / "game_tree.lsys"), rules(), seed=2)
    dry.sim.state.water_meter = 0.15
    for _ in range(500):
        dry.step(0.5)
    assert wet.roots.length() > 2.0 and dry.roots.length() == 0.0
    assert wet.roots.bounds()[0][1] < -1.0  # below the ground
    drains = []
    for share in (0.0, 1.0):
        world = copy.deepcopy(wet)
        world.sim.root_share = share
        world.sim.state.water_meter = 0.8
        world.sim.state.watering = False
        before = world.sim.state.water_meter
        world.sim.step(1.0)
        drains.append(before - world.sim.state.water_meter)
    assert drains[1] == pytest.approx(drains[0] * (1 - wet.rules.roots.drain_relief))


def test_obstacle_gaps_match_a_plain_loop():
    rng = np.random.default_rng(3)
    obstacles = Obstacles(rng.uniform(-5, 5, (300, 3)), rng.uniform(-5, 5, (300, 3)), rng.uniform(0.05, 0.5, 300))
    points = rng.uniform(-6, 6, (40, 3))
    gap, away = obstacles.gaps(points, margin=100.0)
    for k, p in enumerate(points):
        best = np.inf
        for a, b, r in zip(obstacles.start, obstacles.end, obstacles.radius, strict=True):
            t = np.clip(np.dot(p - a, b - a) / max(np.dot(b - a, b - a), 1e-12), 0, 1)
            best = min(best, np.linalg.norm(p - (a + t * (b - a))) - r)
        assert gap[k] == pytest.approx(best, abs=1e-9)
    assert np.allclose(np.linalg.norm(away, axis=1), 1.0)


def test_shoots_grow_around_a_rock_not_into_it():
    inside = []
    rock = (0.0, 8.0, 0.0, 2.0)
    for with_rock in (False, True):
        world = World(load_lsystem(ASSETS / "lsystems" / "game_tree.lsys"), rules(), seed=3)
        world.apply(Action.ORBIT_HEIGHT, 0.9)
        garden = Garden([world])
        garden.rocks = [rock] if with_rock else []
        grow(world, 10, garden)  # (a sapling paid by its sugar: tall enough to pass the rock by day 10)
        segs = world.tree.geometry(world.clocks()).turtle.segments
        gap, _ = rocks([rock]).gaps(np.concatenate([segs.end, (segs.start + segs.end) / 2]), 100.0)
        inside.append(int((gap < -0.05).sum()))
        if with_rock:
            assert float(segs.end[:, 1].max()) > 8.0  # it grew past the rock, around it
    assert inside[0] > 10 and inside[1] == 0
