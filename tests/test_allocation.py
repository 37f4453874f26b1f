"""Allocation by a functional balance (Brouwer 1963): roots in proportion to the crown's water need against what
each root supplies; root:shoot 0.2-0.5 for a watered young tree (Poorter et al. 2012), higher in drought, lower in
shade."""

import numpy as np
import pytest

from arbor.engine.life.experiment.measure import root_shoot
from arbor.engine.life.plant.carbon import CarbonBudget, root_balance, root_demand
from arbor.engine.life.rules.rules import Rules, load_rules
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import load_lsystem

DAY = 2 * np.pi / 0.05


def test_the_balance_rises_with_the_crown_s_need_and_falls_with_the_soil_s_supply():
    rules = Rules()
    assert root_balance(1.0, 1.0, rules) == pytest.approx(1.0)
    assert root_balance(1.0, 0.4, rules) > root_balance(1.0, 0.8, rules) > root_balance(0.5, 0.8, rules)
    assert root_balance(2.0, 0.0, rules) == rules.carbon.root_most
    roots = 100.0 * rules.carbon.root_shoot
    budget = CarbonBudget(built=100.0 + roots, roots_built=roots)  # 100 g of shoot, its roots at the target
    assert root_demand(budget, rules, 1e9, 1.0) == pytest.approx(0.0)  # at the target: nothing wanted
    assert root_demand(budget, rules, 1e9, 2.0) == pytest.approx(roots)  # the target doubled: the gap
    half = rules.carbon.root_catch_up / 2
    assert root_demand(budget, rules, half, 2.0) == pytest.approx(roots / 2)  # closed over root_catch_up


def grown(system, below: float, until: float, shade: float = 0.0, days: float = 6) -> float:
    """Root:shoot after ``days`` of an endless summer, watered between ``below`` and ``until``."""
    rules = load_rules("assets/rules.toml", pace="demo")
    rules.seasons.enabled = False
    rules.sun.shade = shade
    world = World(system, rules, seed=3)
    world.apply(Action.ORBIT_HEIGHT, 0.35)
    world.sim.state.sun_meter, world.sim.state.water_meter = 0.9, until
    for _ in range(round(days * DAY / 0.5)):
        s = world.sim.state
        world.apply(Action.WATER, float(s.water_meter < until if s.watering else s.water_meter < below))
        world.step(0.5)
    assert world.sim.state.alive
    return root_shoot(world.carbon)


def test_root_shoot_is_a_young_tree_s_and_rises_in_drought_and_falls_in_shade(lsys_dir):
    system = load_lsystem(lsys_dir / "game_tree.lsys")
    watered, dry, shaded = grown(system, 0.55, 0.75), grown(system, 0.25, 0.55), grown(system, 0.55, 0.75, 0.75)
    assert 0.2 <= watered <= 0.5, watered
    assert dry > 1.2 * watered and shaded < 0.9 * watered, (dry, watered, shaded)


def test_the_roots_grow_as_fast_as_the_balance_asks_up_to_the_rule_root_most(lsys_dir):
    """A reading pays the roots' due and World.settle lets them grow at the balance's need over supply, capped once,
    by carbon.root_most."""
    rules = load_rules("assets/rules.toml", pace="demo")
    world = World(load_lsystem(lsys_dir / "game_tree.lsys"), rules, seed=3)
    world.carbon.pool, world.carbon.built = 1e6, 10.0  # a full pool and a shoot to balance
    world.sim.state.water_meter, world.sim.state.daylight = 0.02, 1.0  # a dry soil under a bright crown
    world.economy(10.0, 0.0).rest(0.0)  # (a reading at night: upkeep, then the roots' due)
    world.settle(10.0)
    assert world.carbon.roots_built > 0
    assert world.sim.state.root_vigour == pytest.approx(rules.carbon.root_most)
