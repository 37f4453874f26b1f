"""The carbon budget under the game: sugar from the light the leaves catch, limited by water, spent on upkeep
and growth; a tree that cannot pay its upkeep, or stands bare in summer, starves and dies."""

import math

import numpy as np
import pytest

from arbor.engine.life.plant.carbon import CarbonBudget, canopy, full_ppfd, stomata
from arbor.engine.life.plant.photosynthesis import real_seconds
from arbor.engine.life.rules.rules import Rules, load_rules
from arbor.engine.life.rules.schema import find_rule
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import load_lsystem

DAY = 2 * np.pi / find_rule("sun.speed").default  # seconds of a simulated day at the default sun speed


@pytest.fixture(scope="module")
def system(lsys_dir):
    return load_lsystem(lsys_dir / "game_tree.lsys")


def lived(system, days: float, orbit: float | None = None, below: float = 0.55, until: float = 0.75,
          seed: int = 3) -> World:
    """A world in an endless summer, watered between ``below`` and ``until`` (both 1: the can always held)."""
    rules = load_rules("assets/rules.toml", pace="demo")
    rules.seasons.enabled = False
    world = World(system, rules, seed=seed)
    if orbit is not None:
        world.apply(Action.ORBIT_HEIGHT, orbit)
    world.sim.state.sun_meter = world.sim.state.water_meter = 0.9
    for _ in range(round(days * DAY / 0.5)):
        s = world.sim.state
        world.apply(Action.WATER, float(s.water_meter < until if s.watering else s.water_meter < below))
        world.step(0.5)
    return world


def nrh(ppfd: float, amax: float, phi: float, theta: float) -> float:
    """The non-rectangular hyperbola, written out here (Thornley 1976): the smaller root of
    theta A² - (phi I + Amax) A + phi I Amax = 0."""
    b = phi * ppfd + amax
    return (b - math.sqrt(b * b - 4 * theta * phi * ppfd * amax)) / (2 * theta)


def test_sugar_follows_each_leaf_s_light_response_and_closes_smoothly_with_the_soil():
    rules = Rules()
    area = np.full(10, 100.0)  # ten leaves of 1 m² (100 scene units² each)
    fixed = {}
    for light in (0.005, 0.01, 0.2, 0.8):
        budget = CarbonBudget(pool=1.0)
        budget.live(rules, 10.0, 1.0, 1.0, 1.0, canopy(area, np.full(10, light), np.zeros(0), np.zeros(0)))
        fixed[light] = budget.fixed
    c, ppfd = rules.carbon, full_ppfd(rules)
    expected = nrh(0.8 * ppfd, c.amax, c.quantum_efficiency, c.curvature) * 30.03e-6 * real_seconds(rules) * 10 * 10
    assert fixed[0.8] == pytest.approx(expected, rel=1e-6)
    assert fixed[0.01] == pytest.approx(2 * fixed[0.005], rel=0.03)  # dim light: in proportion (slope phi)
    assert fixed[0.8] < 2 * fixed[0.2]  # bright light: it saturates toward Amax
    lit = canopy(area, np.full(10, 0.8), np.zeros(0), np.zeros(0))
    dry = CarbonBudget(pool=1.0)
    dry.live(rules, 10.0, 1.0, stomata(0.1, 1.0, rules), 1.0, lit)
    assert dry.fixed == pytest.approx(stomata(0.1, 1.0, rules) * fixed[0.8])
    opened = [stomata(w, 1.0, rules) for w in np.linspace(0.0, 1.0, 101)]
    assert opened[0] == 0.0 and opened[-1] == pytest.approx(1.0) and np.all(np.diff(opened) > 0)
    assert np.max(np.abs(np.diff(opened, 2))) < 0.01  # no threshold: the slope changes gradually
    assert 0.25 < stomata(0.1, 1.0, rules) < 0.5 < 0.8 < stomata(0.5, 1.0, rules)
    assert stomata(0.9, 0.0, rules) == 0.0 and stomata(0.9, 0.5, rules) == pytest.approx(0.5 * stomata(0.9, 1.0, rules))


def test_leaves_and_sapwood_cost_upkeep_by_day_and_by_night():
    rules = Rules()
    small, big = CarbonBudget(pool=50.0), CarbonBudget(pool=50.0)
    leaves = np.full(4, 100.0)  # 4 m² of leaves in the dark; 5 internodes of 0.02 units² x 10 units of sapwood
    small.live(rules, 1.0, 1.0, 1.0, 1.0, canopy(leaves, np.zeros(4), np.full(5, 0.02), np.full(5, 10.0)))
    big.live(rules, 1.0, 1.0, 1.0, 1.0, canopy(leaves, np.zeros(4), np.full(5, 0.08), np.full(5, 10.0)))
    dark = rules.carbon.dark_share * rules.carbon.amax * 30.03e-6 * real_seconds(rules)  # g per m² per s
    upkeep = dark * 4.0 + rules.carbon.wood_respiration * 5 * math.pi * 0.02 * 10 / 1000  # (pipe areas are r²)
    assert small.respired == pytest.approx(upkeep) and big.respired > small.respired
    night = small.pool
    small.live(rules, 10.0, 0.0, 0.0, 1.0)  # night: the last canopy respires on, nothing is fixed
    assert small.pool == pytest.approx(night - 10 * upkeep) and small.fixed == 0.0
    asleep = CarbonBudget(pool=50.0, leaf_area=4.0, sapwood=small.sapwood)
    asleep.live(rules, 10.0, 0.0, 0.0, rules.carbon.dormant)  # winter rest: a share of summer's upkeep
    assert asleep.respired == pytest.approx(rules.carbon.dormant * 10 * upkeep)


def test_shade_builds_less_than_sun_and_starves_nothing_that_is_lit(system):
    sun, shade = lived(system, 8), lived(system, 8, orbit=-0.5)
    assert sun.carbon.fixed > 2.5 * shade.carbon.fixed
    assert sun.carbon.built > 2 * shade.carbon.built
    leaves = [int(np.count_nonzero(w.tree.lstring.sym == ord("L"))) for w in (sun, shade)]
    assert leaves[1] <= 0.7 * leaves[0]
    assert sun.sim.state.alive and shade.sim.state.alive and sun.carbon.starving == 0.0


def test_a_drowned_tree_all_but_stops_growing(system):
    wet = lived(system, 3, below=1.0, until=1.0)  # the can held all the time
    s = wet.sim.state
    assert s.drowning > wet.rules.water.drown_time and s.oxygen < 1e-6  # a large dose of want of oxygen
    length, roots = s.length_time, s.root_time
    for _ in range(round(DAY / 0.5)):
        wet.step(0.5)
    grown = wet.sim.state.length_time - length  # the roots' health (soil.root_health) holds the clocks back
    assert grown < 0.02 * wet.rules.growth.length_rate * DAY and wet.sim.state.root_time - roots < 1e-9


def test_a_tree_kept_in_the_dark_starves_and_dies(system):
    rules = load_rules("assets/rules.toml", pace="demo")
    rules.seasons.enabled = False
    rules.carbon.seed_reserve = 2.0  # (a small reserve: a bigger one keeps a shade leaf's low upkeep longer)
    world = World(system, rules, seed=3)
    world.sim.state.water_meter = 0.7
    world.apply(Action.ORBIT_HEIGHT, -1.0)  # the sun never rises: leaves stay, nothing is fixed
    days = 0.0
    while world.sim.state.alive and days < 6:
        for _ in range(round(DAY / 4 / 0.5)):
            world.sim.state.water_meter = max(world.sim.state.water_meter, 0.6)  # watered: only light is missing
            world.sim.state.sun_meter = max(world.sim.state.sun_meter, 0.6)  # (the meter alone would not kill)
            world.step(0.5)
        days += 0.25
    assert not world.sim.state.alive and days <= 5  # (about 65 real days on 2 g against a shade leaf's low upkeep)
    assert world.carbon.pool == 0.0 and world.carbon.respired > 0


def test_seedlings_differ_within_their_species_ranges_and_keep_their_traits(system, tmp_path):
    from arbor.engine.life.keep.save import SavedGarden, read_garden, write_garden
    from arbor.engine.life.plant.genome import checked, ranges

    rules = load_rules("assets/rules.toml", pace="demo")
    a, b = World(system, rules, seed=1), World(system, rules, seed=2)
    spread = ranges(system)
    assert {"BA", "WAKE", "P", "HK"} <= set(spread) and a.genome.keys() == spread.keys()
    assert a.genome != b.genome and World(system, rules, seed=1).genome == a.genome  # a seed is a genome
    for name, value in a.genome.items():
        assert abs(value / system.constants[name] - 1) <= spread[name] + 1e-12
        assert a.tree.system.constants[name] == pytest.approx(value)  # the tree grows by its own values
    path = tmp_path / "a.arbor"
    write_garden(SavedGarden([a]), path)
    back = read_garden(path, rules).world
    assert back.genome == pytest.approx(a.genome) and back.tree.system.constants["BA"] == pytest.approx(a.genome["BA"])
    hostile = checked(system, {"BA": 1e9, "IL": 5.0, "WAKE": float("nan")})
    assert hostile == {"BA": pytest.approx(system.constants["BA"] * (1 + spread["BA"]))}  # clamped; others dropped


def test_old_straight_bare_wood_is_consolidated_with_its_geometry_girth_and_age(system):
    from arbor.engine.life.form.interpret import Clocks, grow_geometry, reference_constants
    from arbor.engine.life.plant.consolidate import consolidated
    from arbor.engine.lsystem.lstring import parse_lstring

    text = ("I(0,0,0,0,0.02)+(0.3)^(-0.2)/(137.5)I(1,1,0,0,0.018)+(0.2)^(0.1)/(137.5)I(2,2,0,0,0.016)"
            "+(-0.4)^(0.3)/(137.5)I(3,3,0,0,0.015)[+(40)I(3,3,1,0,0.002)[&(62)L(3,1,0)]]"  # a branch: the run ends
            "+(0.1)^(0)/(137.5)I(4,4,0,0,0.01)+(0.1)^(0)/(137.5)I(90,90,0,0,0.002)[&(62)L(90,1,0)]A(0,0,6,1,0,0)")
    ls, now, const = parse_lstring(text), 100.0, reference_constants()
    merged, saved = consolidated(ls, now, const["TAU"])
    # the first piece has no roll of its own to take the others' rolls: the run starts at the second;
    # the branch ends it; the last internode is young
    assert saved == 2 * 4 and len(merged) == len(ls) - saved
    assert "+(0.3)^(-0.2)/(412.5)I(1,1,0,0,0.018,3)[+(40)" in merged.to_text()  # three pieces, their rolls
    assert "I(4,4,0,0,0.01)+(0.1)^(0)/(137.5)I(90,90,0,0,0.002)" in merged.to_text()  # young wood stays
    before = grow_geometry(ls, Clocks(now, now), const).turtle
    after = grow_geometry(merged, Clocks(now, now), const).turtle
    np.testing.assert_allclose(after.leaves.position, before.leaves.position, atol=0.05)  # the tree stands as it did
    assert after.segments.end[:, 1].max() == pytest.approx(before.segments.end[:, 1].max(), abs=0.01)
    assert after.segments.radius[1] == pytest.approx(before.segments.radius[1])  # the run keeps its base's girth
    again, more = consolidated(merged, now, const["TAU"])
    assert more == 0 and again.to_text() == merged.to_text()
    assert parse_lstring(merged.to_text()).to_text() == merged.to_text()  # saves as text like any string


def test_blossoms_and_fruit_are_paid_for_and_set_only_as_far_as_the_pool_pays(system):
    from arbor.engine.life.plant.carbon import built_cost
    from arbor.engine.lsystem.derive import Deriver
    from arbor.engine.lsystem.lstring import parse_lstring

    rules, const = Rules(), {**system.constants, "IL": 1.0, "IO": 0.75, "TIP": 0.012, "LS": 1.2}
    plain = built_cost(parse_lstring("I(5,0,0,0,0)L(5,1,0)"), 5.0, const, rules)
    flowering = built_cost(parse_lstring("I(5,0,0,0,0)L(5,1,0)K(5)K(5)O(5)K(4)"), 5.0, const, rules)
    assert flowering - plain == pytest.approx(2 * rules.carbon.blossom_cost + rules.carbon.fruit_cost)
    blossoms = parse_lstring("".join(f"[K({t})]" for t in range(200)))
    externs = {"T": 400.0, "G": 0.0, "DT": 1.0, "R": 1.0, "B": 0.0, "WL": 1.0, "SF": 1.0, "AF": 0.0, "SP": 1.0,
               "SL": 0.0, "LG": 1.0}
    fruit = []
    for pays in (1.0, 0.0):  # what the pool pays for: everything, nothing
        ls, _ = Deriver(system, seed=1).step(blossoms, {**externs, "C": pays})
        fruit.append(ls.count("O"))
    assert fruit[0] > 80 and fruit[1] == 0  # SET = 0.6 of 200 blossoms in full; none from an empty pool


def test_the_pool_pays_for_all_the_wood_and_leaves_drawn_and_sets_how_fast_the_tree_builds(system):
    """The tree drawn weighs what its pool paid for (every segment's wood at pi r² and the leaves; roots apart),
    and growth is set by the carbon: the pool is spent, not left full (carbon.growth_fill, carbon.growth_cost)."""
    from arbor.engine.life.experiment.measure import measure

    world = lived(system, 5)
    budget, rules = world.carbon, world.rules
    above = (budget.built - budget.roots_built) / 1000.0  # kg of dry mass the pool paid for above ground
    assert 0.85 * above <= measure(world)["biomass"] <= 1.15 * above, (measure(world)["biomass"], above)
    paid = budget.built * rules.carbon.growth_cost + budget.pool + budget.respired
    assert paid == pytest.approx(budget.fixed + rules.carbon.seed_reserve, rel=0.05)  # nothing made, little lost
    assert budget.pool < 0.8 * budget.capacity(rules)  # a full pool would build more


def test_shade_leaves_are_thinner_so_the_same_sugar_buys_more_leaf_in_shade():
    """carbon.shade_lma and carbon.sun_leaf_light (Poorter et al. 2009): a leaf's mass per area falls from a sun
    leaf's in bright light to shade_lma of it in the dark; the new leaves of a shaded tree cost that much less."""
    from arbor.engine.life.plant.carbon import built_cost, leaf_mass
    from arbor.engine.lsystem.lstring import parse_lstring

    rules = Rules()
    c = rules.carbon
    assert leaf_mass(rules, 1.0) == leaf_mass(rules, c.sun_leaf_light) == pytest.approx(c.leaf_mass)
    assert leaf_mass(rules, 0.0) == pytest.approx(c.shade_lma * c.leaf_mass)
    assert leaf_mass(rules, 0.0) < leaf_mass(rules, 0.1) < leaf_mass(rules, 0.3) < leaf_mass(rules, 1.0)
    const = {"IL": 1.0, "IO": 0.75, "TIP": 0.012, "LS": 1.2}
    leaves = parse_lstring("I(5,0,0,0,0)L(5,1,0)L(5,1,0)")
    assert built_cost(leaves, 5.0, const, rules, 0.1) < 0.7 * built_cost(leaves, 5.0, const, rules, 1.0)


def test_only_the_fine_roots_the_leaves_keep_respire_in_full():
    """A tree's roots grow with its wood; the fine roots its leaves keep (carbon.fine_root_leaf g a g of leaf)
    respire at root_respiration, the coarse rest at coarse_root_share of it, so an old tree's roots do not eat
    its sugar (they did: 26 kg of roots respired 2.7 kg a day, three times its leaves, and it starved)."""
    from arbor.engine.life.plant import photosynthesis

    rules = Rules()
    c = rules.carbon
    per_gram = float(photosynthesis.grams(c.root_respiration * 1e-3, rules))
    young = CarbonBudget(roots_built=100.0, leaf_area=4.0)  # fewer roots than the leaves keep: all fine
    assert young.upkeep_rate(rules) - CarbonBudget(leaf_area=4.0).upkeep_rate(rules) == pytest.approx(100 * per_gram)
    old = CarbonBudget(roots_built=26_000.0, leaf_area=29.0)
    fine = c.fine_root_leaf * c.leaf_mass * 29.0
    roots = old.upkeep_rate(rules) - CarbonBudget(leaf_area=29.0).upkeep_rate(rules)
    assert roots == pytest.approx((fine + c.coarse_root_share * (26_000.0 - fine)) * per_gram)
    assert roots < 0.25 * 26_000.0 * per_gram


def test_autumn_and_winter_keep_stores_from_growth_for_the_spring():
    """In autumn and winter growth may not spend the winter_keep more of upkeep the tree keeps for its winter
    and for the spring before its new leaves pay (a 30-year tree starved every spring without it); half of it
    in spring, none in summer."""
    from arbor.engine.life.plant import seasons

    rules = load_rules("assets/rules.toml", pace="demo")
    world = World(load_lsystem("assets/lsystems/game_tree.lsys"), rules, seed=3)
    year, shares = rules.seasons.year_days, {}
    for name, quarter in (("spring", 0.1), ("summer", 0.35), ("autumn", 0.6), ("winter", 0.85)):
        world.sim.state.sun_turns = (quarter - rules.seasons.start) % 1.0 * year
        assert seasons.season_at(world.sim.state.sun_turns, rules).name == name
        world.economy(1.0, 0.0)
        shares[name] = world.carbon.stored / rules.carbon.winter_keep
    assert shares == {"spring": 0.5, "summer": 0.0, "autumn": 1.0, "winter": 1.0}
    budget = CarbonBudget(pool=1000.0, leaf_area=2.0, sapwood=0.001)
    summer = budget.spare(rules)
    budget.stored = rules.carbon.winter_keep
    assert summer - budget.spare(rules) == pytest.approx(rules.carbon.winter_keep * budget.upkeep_rate(rules))
