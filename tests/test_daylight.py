"""The plant model's dose and response: the length clock runs on the light the leaves caught (remembered over a
day), a leaf lives the same game time whatever the light, a branch's shade is counted in sugar, and a
shade-tolerant leader slows in weak light more than its branches."""

import numpy as np
import pytest

from arbor.engine.life.form.interpret import INTERNODE, Clocks
from arbor.engine.life.keep.save_check import sim_state
from arbor.engine.life.plant.carbon import CarbonBudget, Economy
from arbor.engine.life.plant.growth import GrowingTree
from arbor.engine.life.plant.sim import SimState, Simulation
from arbor.engine.life.rules.rules import Rules, load_rules
from arbor.engine.life.rules.schema import find_rule
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.derive import Deriver
from arbor.engine.lsystem.lstring import parse_lstring
from arbor.engine.lsystem.lsys import load_lsystem

DAY = 2 * np.pi / find_rule("sun.speed").default  # seconds of a simulated day at the default sun speed


@pytest.fixture(scope="module")
def system(lsys_dir):
    return load_lsystem(lsys_dir / "game_tree.lsys")


def test_the_remembered_daylight_follows_the_light_caught_over_a_day_and_sets_the_length_clock():
    sim = Simulation(Rules())
    sim.rules.seasons.enabled = False
    g = sim.rules.growth
    assert sim.state.daylight == g.daylight_full and sim.light_growth() == 1.0  # a sapling starts at the norm
    steady = g.daylight_full + 0.1
    for _ in range(round(DAY)):  # a day at a steady light above the norm
        sim.remember_light(steady, 1.0)
    assert steady - 0.4 * (steady - g.daylight_full) < sim.state.daylight < steady  # most of the way in a day
    sim.state.sun_cycle.rate = sim.state.water_cycle.rate = 1.0  # (both meters have earned growth)
    sim.state.sun_cycle.earned = sim.state.water_cycle.earned = 1
    for share, growth in ((0.5, 0.5), (1.0, 1.0), (1.25, 1.25), (0.99 / g.daylight_full, g.daylight_most)):
        sim.state.daylight = share * g.daylight_full
        assert sim.light_growth() == pytest.approx(growth)
        assert sim.growth_speeds()[0] == pytest.approx(g.length_rate * growth)


def test_a_higher_sun_grows_the_length_clock_in_graded_steps(system):
    """Orbit heights -0.3, 0 and 0.35 (kept watered, three days): each step up adds length time (the sweep's
    steps over 30 days: benchmarks.dose). A sapling's few leaves, all lit, soon reach daylight_most in a
    higher sun: its top speed."""
    grown = []
    for orbit in (-0.3, 0.0, 0.35):
        rules = load_rules("assets/rules.toml", pace="demo")
        rules.seasons.enabled = False
        world = World(system, rules, seed=3)
        world.apply(Action.ORBIT_HEIGHT, orbit)
        start = world.sim.state.length_time
        for _ in range(round(3 * DAY / 0.5)):
            world.apply(Action.WATER, float(world.sim.state.water_meter < 0.6))
            world.step(0.5)
        grown.append(world.sim.state.length_time - start)
    assert grown[0] < grown[1] < grown[2] and grown[2] > 1.3 * grown[0], grown


def test_a_leaf_lives_the_same_game_time_whatever_the_light(system):
    """LG (how fast T runs for the light caught) stretches a leaf's life in T: at LG 1.5 a leaf 70 T old
    still lives (LLIFE 60 x 1.5), at LG 1 it withers."""
    leaf = parse_lstring("L(0,1,0)")
    extern = {"T": 70.0, "G": 70.0, "DT": 0.0, "R": 1.0, "B": 0.0, "WL": 1.0, "C": 1.0, "SF": 1.0, "AF": 0.0,
              "SP": 0.0, "SL": 0.0}
    short, _ = Deriver(system, seed=1).step(leaf, {**extern, "LG": 1.0})
    long, _ = Deriver(system, seed=1).step(leaf, {**extern, "LG": 1.5})
    assert short.params[2] == 70.0 and long.params[2] == 0.0  # (the third parameter: withering since)


def grown_tree(system) -> GrowingTree:
    tree = GrowingTree(system, seed=1)
    for k in range(1, 41):
        clocks = Clocks(float(k), float(k))
        scene = tree.light_scene(clocks)
        tree.sense(scene, np.ones(len(scene.queries)), clocks, 1.0, np.array([0.0, 1.0, 0.0]), 4.0)
        tree.rewrite(float(k), float(k), resources=1.0)
    return tree


def test_a_branch_s_shade_is_counted_in_sugar_so_a_weak_day_s_light_counts_less(system):
    """The same share of the sky on every leaf: in a strong day's light (remembered daylight 1.5 x the norm)
    few internodes count shade; in a weak one (0.1 x) the same light is deep shade for many more."""
    counted = []
    for daylight in (1.5, 0.1):
        tree = grown_tree(system)
        clocks = Clocks(41.0, 41.0)
        scene = tree.light_scene(clocks)
        economy = Economy(CarbonBudget(pool=1e6), Rules(), 6.0, 1.0, daylight=daylight)
        tree.sense(scene, np.full(len(scene.queries), 0.6), clocks, 1.0, np.array([0.0, 1.0, 0.0]), 4.0,
                   economy=economy)
        ls = tree.lstring
        grown = np.flatnonzero((ls.sym == INTERNODE) & (ls.nparams >= 5))
        counted.append(int(np.count_nonzero(ls.params[ls.offsets[grown] + 3] > 0)))
    strong, weak = counted
    assert weak > 2 * strong + 5, counted


def test_a_shade_tolerant_leader_slows_in_weak_light_more_than_its_branches(system):
    """The game tree's AD: at LG 0.5 the leader's progress is 0.5^(AD-1) of its branches' (C^AD x LG^(AD-1))."""
    apices = parse_lstring("A(0,0,0,1,0,0)A(0,1,0,1,0,0)")
    extern = {"T": 1.0, "G": 1.0, "DT": 0.1, "R": 1.0, "B": 0.0, "WL": 1.0, "C": 1.0, "SF": 1.0, "AF": 0.0,
              "SP": 0.0, "SL": 0.0}
    full, _ = Deriver(system, seed=1).step(apices, {**extern, "LG": 1.0})
    weak, _ = Deriver(system, seed=1).step(apices, {**extern, "LG": 0.5})
    leader, branch = (weak.params[weak.offsets[i]] / full.params[full.offsets[i]] for i in (0, 1))
    assert system.constants["AD"] > 1  # (shade-tolerant: its leader slows more than its branches)
    assert leader == pytest.approx(0.5 ** (system.constants["AD"] - 1) * branch) and branch == pytest.approx(1.0)


def test_the_remembered_daylight_is_saved_and_an_older_save_starts_at_the_norm():
    state = SimState(daylight=0.37).to_dict()
    assert sim_state(state).daylight == 0.37
    del state["daylight"]
    assert sim_state(state).daylight == Rules().growth.daylight_full


def test_the_sun_meter_shows_the_light_the_leaves_catch(system):
    """Under the same sun a crown whose leaves catch a third of it fills its sun meter a third as fast; a
    world hands its tree's leaf light to the meter at every step."""
    filled = []
    for light in (1.0, 1 / 3):
        sim = Simulation(Rules())
        sim.state.sun_angle, sim.state.sun_meter = 0.5, 0.1
        sim.leaf_light = light
        sim.step(5.0)
        filled.append(sim.state.sun_meter - 0.1)
    assert filled[1] == pytest.approx(filled[0] / 3) and filled[0] > 0
    world = World(system, load_rules("assets/rules.toml", pace="demo"), seed=1)
    world.tree.mean_light = 0.4
    world.step(0.5)
    assert world.sim.leaf_light == 0.4
