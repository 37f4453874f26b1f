"""Paces, seasons, rain, blossoms, fruit, seeds, the journal and time away (engine, headless)."""

import copy
import math
from pathlib import Path

import numpy as np
import pytest

from arbor.engine.life.form.shoot_units import bud_count, leaf_count, node_count
from arbor.engine.life.keep.away import away_seconds, live_away, tree_height
from arbor.engine.life.keep.save import SavedGarden, read_garden, write_garden
from arbor.engine.life.plant import seasons
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.rules.schema import find_rule
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.garden import Garden
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import load_lsystem

ASSETS = Path(__file__).resolve().parent.parent / "assets"
RULES = ASSETS / "rules.toml"


def careful(world: World, until_turns: float, snaps: dict | None = None, every: float = 0.25) -> None:
    """Water like a careful player until the sun has turned ``until_turns`` times, noting the string
    every ``every`` days in ``snaps`` (turns -> (season, L, K, O, V, length time, shed, I))."""
    s = world.sim.state
    next_snap = s.sun_turns
    while s.sun_turns < until_turns:
        world.apply(Action.WATER, float(s.water_meter < 0.75 if s.watering else s.water_meter < 0.55))
        world.step(0.5)
        if snaps is not None and s.sun_turns >= next_snap:
            ls = world.tree.lstring
            snaps[round(s.sun_turns, 2)] = (world.sim.season().name, leaf_count(ls), ls.count("K"), ls.count("O"),
                                            bud_count(ls), s.length_time, world.tree.shed_total, node_count(ls))
            next_snap += every


@pytest.fixture(scope="module")
def year():
    """One tree through more than a year at the demo pace (about 5 s): the world and its diary."""
    world = World(load_lsystem(ASSETS / "lsystems" / "game_tree.lsys"), load_rules(RULES, pace="demo"), seed=3)
    world.sim.state.sun_meter = world.sim.state.water_meter = 0.9
    snaps: dict = {}
    careful(world, 32.0, snaps)
    return world, snaps


def test_paces_scale_times_and_rates_but_keep_the_rules_shape():
    demo, home = load_rules(RULES, pace="demo"), load_rules(RULES, pace="home")
    assert (demo.growth.hold_time, demo.growth.deadline) == (find_rule("growth.hold_time").default,
                                                             find_rule("growth.deadline").default)  # as declared
    k = home.time_scale
    assert 500 < k < 1000
    assert home.growth.hold_time == pytest.approx(20.0 * k) and home.growth.deadline == pytest.approx(40.0 * k)
    assert home.water.drain_rate == pytest.approx(demo.water.drain_rate / k)
    assert home.water.fill_rate == demo.water.fill_rate  # the watering can fills as fast at every pace
    day = 2 * math.pi / home.sun.speed
    assert 0.9 * 86400 < day < 1.1 * 86400  # a day of the sun lasts a day at home
    full_to_empty = 1.0 / (home.water.drain_rate + home.water.sun_drain_rate)
    assert full_to_empty > 0.5 * 86400  # a full water meter lasts most of a day even in full sun


def test_a_year_has_its_seasons_in_order(year):
    _, snaps = year
    names = [v[0] for v in snaps.values()]
    order = [n for i, n in enumerate(names) if i == 0 or n != names[i - 1]]
    assert order[:5] == ["spring", "summer", "autumn", "winter", "spring"]


def test_winter_is_bare_and_still_and_sheds_nothing(year):
    _, snaps = year
    winter = [v for v in snaps.values() if v[0] == "winter"]
    winter = winter[: int(len(winter) * 0.85)]  # (buds break in the last days of winter)
    assert len(winter) > 10
    assert all(v[1] == 0 for v in winter)  # no leaves
    assert max(v[5] for v in winter) - min(v[5] for v in winter) < 0.5  # (almost) no growth
    assert winter[-1][6] == winter[0][6]  # no branch shed all winter
    assert winter[0][4] > 100  # leaf buds wait for spring


def test_autumn_drops_leaves_and_spring_opens_them_again(year):
    _, snaps = year
    summer = max(v[1] for v in snaps.values() if v[0] == "summer")
    late_autumn = [v for v in snaps.values() if v[0] == "autumn"][-1]
    assert late_autumn[1] < 0.8 * summer
    spring2 = [v for t, v in snaps.items() if v[0] == "spring" and t > 20]
    assert max(v[1] for v in spring2) > 0.8 * summer  # the crown is green again
    assert spring2[-1][4] == 0  # every leaf bud opened
    winter = [v for v in snaps.values() if v[0] == "winter"]
    wood = [v[7] for v in winter + spring2[:8]]
    assert min(wood) > 0.9 * winter[0][7]  # a bare crown does not starve before its leaves are out


def test_a_mature_tree_blossoms_in_spring_and_sets_fruit(year):
    world, snaps = year
    first_year = [v for t, v in snaps.items() if t < 20]
    assert all(v[2] == 0 and v[3] == 0 for v in first_year)  # a young tree does not flower
    spring2 = [v for t, v in snaps.items() if v[0] == "spring" and t > 20]
    assert max(v[2] for v in spring2) > 5  # blossoms (K modules from the tree's own rules)
    assert max(v[3] for v in spring2) > 5  # fruit
    first_k = min(t for t, v in snaps.items() if v[2] > 0)
    first_o = min(t for t, v in snaps.items() if v[3] > 0)
    assert first_o > first_k  # blossoms come first
    kinds = {k for _, k, _ in world.journal.entries}
    assert {"branch", "flower", "fruit", "season", "height"} <= kinds


def test_ripe_fruit_can_be_picked_and_its_seed_sown(year):
    world, _ = year
    world = copy.deepcopy(world)
    garden = Garden([world])
    ls = world.tree.lstring
    fruit = np.flatnonzero(ls.sym == ord("O"))
    born = ls.params[ls.offsets[fruit]]
    ripe = fruit[world.sim.state.length_time - born >= world.tree.geometry_constants["RIPEN"]]
    green = fruit[world.sim.state.length_time - born < world.tree.geometry_constants["RIPEN"]]
    assert len(ripe) and len(green)
    assert garden.harvest(world, int(green[0])) is None  # not ripe yet
    assert garden.harvest(world, int(np.flatnonzero(ls.sym == ord("I"))[0])) is None  # not a fruit
    seed = garden.harvest(world, int(ripe[0]))
    assert seed is not None and seed.parent_seed == world.seed and garden.seeds == [seed]
    assert world.tree.lstring.count("O") == len(fruit) - 1
    assert world.journal.has("harvest", 1.0)
    child = garden.plant_seed(world.rules, world.system)
    assert child is garden.world and not garden.seeds
    assert child.lineage.parents == (world.lineage.id,) and child.lineage.generation == 1  # alone: self-pollinated
    assert [p.key for p in child.system.productions] == [p.key for p in world.system.productions]
    assert child.sim.state.sun_turns == world.sim.state.sun_turns  # one calendar for the garden


def test_rain_showers_fill_the_water_meter():
    rules = load_rules(RULES, pace="demo")
    world = World(load_lsystem(ASSETS / "lsystems" / "game_tree.lsys"), rules, seed=3)
    rainy = [t / 100 for t in range(2800) if seasons.raining(t / 100, world.sim.state.weather_seed, rules)]
    assert 0.02 < len(rainy) / 2800 < 0.1  # a shower on some days, not all the time
    s = world.sim.state
    s.sun_turns = rainy[len(rainy) // 2]
    s.water_meter = 0.3
    world.step(0.5)
    assert world.sim.raining() and s.water_meter > 0.3


def test_time_away_is_capped_and_ignores_clocks_that_cannot_be_read():
    assert away_seconds(1000.0, 400.0, 14) == 600.0
    assert away_seconds(100 * 86400.0, 0.0, 14) == 14 * 86400.0
    for saved_at in (2000.0, float("nan"), 1e308, float("inf")):
        assert away_seconds(1000.0, saved_at, 14) == 0.0


def test_a_well_kept_tree_lives_three_days_away_at_home_and_grows():
    rules = load_rules(RULES, pace="home")
    world = World(load_lsystem(ASSETS / "lsystems" / "game_tree.lsys"), rules, seed=3)
    garden = Garden([world])
    world.sim.state.water_meter = 0.9
    for _ in range(48 * 60):  # two days of watering every evening and morning
        world.apply(Action.WATER, float(world.sim.state.water_meter < 0.6))
        garden.step(60.0)
    world.apply(Action.WATER, 0.0)
    before = tree_height(world)
    summary = live_away(garden, 3 * 86400.0)
    assert world.sim.state.alive and summary.grown > 0 and not summary.died
    assert tree_height(world) > before
    assert 2.5 < summary.days < 3.5


def test_journal_and_seeds_survive_a_save(tmp_path, year):
    world, _ = year
    garden = Garden([copy.deepcopy(world)])
    ls = garden.world.tree.lstring
    fruit = np.flatnonzero(ls.sym == ord("O"))
    born = ls.params[ls.offsets[fruit]]
    ripe = fruit[garden.world.sim.state.length_time - born >= garden.world.tree.geometry_constants["RIPEN"]]
    garden.harvest(garden.world, int(ripe[0]))
    path = tmp_path / "g.arbor"
    write_garden(SavedGarden(garden.worlds, 0, 1000.0, garden.seeds), path)
    saved = read_garden(path, world.rules)
    worlds, saved_at = saved.worlds, saved.saved_at
    assert saved_at == 1000.0
    assert worlds[0].journal.entries == garden.world.journal.entries
    assert saved.seeds == garden.seeds


@pytest.mark.parametrize("species", ["game_tree", "game_poplar"])
def test_with_seasons_a_leaf_lives_out_its_season_and_in_an_endless_summer_it_ages_out(species):
    from arbor.engine.lsystem.derive import Deriver
    from arbor.engine.lsystem.lstring import parse_lstring

    system = load_lsystem(Path("assets/lsystems") / f"{species}.lsys")
    old = parse_lstring("".join("[L(0,1,0)]" for _ in range(50)))  # leaves 200 T old, past LLIFE
    summer = {"T": 200.0, "G": 0.0, "DT": 0.5, "R": 1.0, "B": 0.0, "WL": 1.0, "SF": 1.0, "AF": 0.0, "SP": 0.0,
              "C": 1.0}
    falling = []
    for seasons_run in (1.0, 0.0):
        ls, _ = Deriver(system, seed=2).step(old, {**summer, "SL": seasons_run, "LG": 1.0})
        leaf = np.flatnonzero(ls.sym == ord("L"))
        falling.append(int(np.count_nonzero(ls.params[ls.offsets[leaf] + 2] > 0)))
    assert falling == [0, 50]  # a summer leaf stays till autumn; without seasons every old leaf falls


def test_the_gardener_sees_ripe_fruit_come_and_go_as_the_tree_changes(year):
    """The gardener keeps the fruit's births between rewrites; a pick (a new L-string) and the clock moving
    on are seen at once: its count is ripe_fruit's at every turn."""
    from arbor.engine.life.world.guardian import Gardener, Guardian, ripe_fruit

    world, _ = year
    world = copy.deepcopy(world)
    garden, gardener = Garden([world]), Gardener(Guardian(world.rules))
    ls, s = world.tree.lstring, world.sim.state
    ripe = gardener._ripe(world)
    assert ripe == ripe_fruit(world) > 0 and ls.count("O") > ripe  # (green fruit too)
    while ripe:  # every ripe one picked, one at a time
        fruit = np.flatnonzero(world.tree.lstring.sym == ord("O"))
        assert any(garden.harvest(world, int(k)) is not None for k in fruit)  # (the first ripe one)
        assert gardener._ripe(world) == ripe_fruit(world) == ripe - 1
        ripe -= 1
    s.length_time += 1000.0  # the clock moves on: the green ones ripen on the same L-string
    assert gardener._ripe(world) == ripe_fruit(world) == world.tree.lstring.count("O")


def test_a_birthday_keeps_the_trees_height_and_crown_width_through_a_save(year, tmp_path):
    """Each winter survived, the journal keeps how tall and wide the tree begins its year (its wood and
    leaves, in m); a save keeps them, and sizes a hostile file made up are dropped."""
    from arbor.engine.life.keep.save import SavedGarden, read_garden, write_garden
    from arbor.engine.life.plant.journal import Journal, crown_size

    world, _ = year
    years = [v for _, k, v in world.journal.entries if k == "season"]
    assert years and sorted(world.journal.sizes) == years
    height, width = world.journal.sizes[years[0]]
    now_height, now_width = crown_size(world)
    assert 0.05 < height <= now_height + 1e-6 and 0.05 < width <= 1.5 * now_width  # (a tree grows on after it)
    path = tmp_path / "garden.arbor"
    write_garden(SavedGarden.of(Garden([world]), "game_tree.lsys"), path)
    assert read_garden(path, world.rules).world.journal.sizes == world.journal.sizes
    journal = Journal(entries=[(0.0, "season", 1.0)])
    bad = [[1, 2.0], [2, 1.0, 1.0], [1, -1.0, 1.0], [1, 1.0, float("inf")], [1, True, 1.0], "x", [1, 3.0, 2.5]]
    assert journal.read_sizes(bad) == 6 and journal.sizes == {1.0: (3.0, 2.5)}


def test_the_journal_page_tells_a_birthday_with_the_trees_size():
    from arbor.game.screens.coach import describe

    assert describe("season", 3.0, (3.14, 2.58)) == "lived through winter 3: 3.1 m tall, its crown 2.6 m wide"
    assert describe("season", 3.0) == "lived through winter 3"
