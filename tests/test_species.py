"""The two species differ as real ones do: the pioneer poplar (high Amax and dark respiration, free growth)
outgrows the shade-tolerant game tree in full sun and loses more in shade (Walters, Kruger & Reich 1993; the
traits are the species' .lsys AMAX, QE, RDS and P)."""

import numpy as np
import pytest

from arbor.engine.life.experiment.measure import measure
from arbor.engine.life.plant.photosynthesis import gross, leaf_traits
from arbor.engine.life.rules.rules import Rules, load_rules
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import load_lsystem

DAY = 2 * np.pi / 0.05


@pytest.fixture(scope="module")
def species(lsys_dir):
    return {name: load_lsystem(lsys_dir / f"{name}.lsys") for name in ("game_tree", "game_poplar")}


def grown(system, shade: float, days: float = 7, seed: int = 3, shape: bool = False):
    """Above-ground biomass (kg) after ``days`` of an endless summer, watered, under the default sun with
    ``shade`` of it removed (``shape``: the crown's width over its height instead)."""
    rules = load_rules("assets/rules.toml", pace="demo")
    rules.seasons.enabled = False
    rules.sun.shade = shade
    world = World(system, rules, seed=seed)
    world.apply(Action.ORBIT_HEIGHT, 0.35)
    world.sim.state.sun_meter = world.sim.state.water_meter = 0.9
    for _ in range(round(days * DAY / 0.5)):
        s = world.sim.state
        world.apply(Action.WATER, float(s.water_meter < 0.75 if s.watering else s.water_meter < 0.55))
        world.step(0.5)
    m = measure(world)
    return m["width"] / m["height"] if shape else m["biomass"]


def test_the_leaves_of_a_pioneer_earn_more_in_sun_and_less_in_deep_shade(species):
    rules = Rules()
    tree, poplar = (leaf_traits(species[n].constants, rules) for n in ("game_tree", "game_poplar"))
    assert gross(2000.0, poplar) - poplar.dark > 1.5 * (gross(2000.0, tree) - tree.dark)  # full sun
    assert gross(20.0, poplar) - poplar.dark < gross(20.0, tree) - tree.dark  # deep shade: 1 % of full sun
    assert tree.dark / tree.quantum < poplar.dark / poplar.quantum  # the tolerant leaf's lower compensation point


def test_the_poplar_outgrows_the_game_tree_in_sun_and_loses_more_in_shade(species):
    mass = {(name, shade): grown(species[name], shade) for name in species for shade in (0.0, 0.75)}
    assert mass["game_poplar", 0.0] > mass["game_tree", 0.0], mass  # the pioneer ahead in full sun
    keeps = {name: mass[name, 0.75] / mass[name, 0.0] for name in species}
    assert keeps["game_poplar"] < 0.6 * keeps["game_tree"], (keeps, mass)  # and much further behind in shade


def test_the_poplar_bears_waterlogged_soil_longer(species):
    """FLOOD: a maple's seedlings die in 1-4 weeks of waterlogging, many poplars' live months (Kozlowski 1997)."""
    from benchmarks.validate import drowned_days

    tree, poplar = drowned_days(species["game_tree"], 8), drowned_days(species["game_poplar"], 8)
    assert 7 <= tree <= 28 and poplar > 1.8 * tree, (tree, poplar)


def test_a_flood_tolerant_species_drowns_later_everywhere_drowning_counts():
    """The poplar's FLOOD (x drown_time) holds wherever drowned roots matter: growth, stomata, the status
    and the guardian ask one Simulation.drowned() (growth and stomata used the bare drown_time)."""
    from pathlib import Path

    from arbor.engine.life.rules.rules import Rules
    from arbor.engine.life.world.world import World
    from arbor.engine.lsystem.lsys import load_lsystem

    lsys = Path(__file__).resolve().parent.parent / "assets" / "lsystems"
    rules = Rules()
    worlds = {name: World(load_lsystem(lsys / f"{name}.lsys"), rules, seed=1) for name in ("game_tree", "game_poplar")}
    for world in worlds.values():
        s = world.sim.state
        s.drowning = 2 * rules.water.drown_time  # waterlogged twice as long as a maple bears
        s.sun_cycle.rate = s.water_cycle.rate = 1.0  # (growth earned: only the roots decide)
        s.sun_cycle.earned = s.water_cycle.earned = 1
    tolerant, intolerant = worlds["game_poplar"].sim, worlds["game_tree"].sim
    assert tolerant.flood_tolerance > 2 and not tolerant.drowned() and intolerant.drowned()
    assert 0 < intolerant.growth_speeds()[0] < 0.3 * tolerant.growth_speeds()[0]  # the dose harms graded
    assert intolerant.uptake() < 0.3 * tolerant.uptake()


def test_the_tolerant_crown_flattens_in_shade(species):
    """Under 75 % shade the shade-tolerant game tree spreads a flatter crown, as shade-tolerant saplings do (Canham
    1988, Growth and canopy architecture of shade-tolerant trees: response to canopy gaps): its thinner shade leaves
    (carbon.shade_lma) keep its side shoots paid for (with sun leaves' cost everywhere it grows taller for its
    width in shade)."""
    sun, shade = (grown(species["game_tree"], s, shape=True) for s in (0.0, 0.75))
    assert shade > 1.05 * sun, (sun, shade)
