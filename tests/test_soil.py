"""Water as a gradient (issue 43; engine/life/plant/soil.py): the soil bucket drains above field capacity, the
roots take up less as it dries (so it dries ever more slowly), waterlogging harms by an oxygen dose that heals,
a flood-intolerant seedling lives 1-4 weeks of waterlogging on the declared time scale and a tolerant one
months, wilting grows with the dryness, and seed 003's late cycles cut the sun's length growth and the
water's girth growth."""

from __future__ import annotations

import math
from itertools import pairwise

import pytest

from arbor.engine.life.keep.save_check import sim_state
from arbor.engine.life.plant import soil
from arbor.engine.life.plant.photosynthesis import real_days
from arbor.engine.life.plant.sim import Simulation
from arbor.engine.life.rules.rules import Rules


def sim_at(water: float, orbit: float = 1.0, **rules_set) -> Simulation:
    """A sim at noon with the water meter at ``water`` (an endless summer; showers wet nothing)."""
    rules = Rules()
    rules.seasons.enabled = False
    rules.weather.rain_fill = 0.0
    for key, value in rules_set.items():
        section, name = key.split("__")
        setattr(getattr(rules, section), name, value)
    sim = Simulation(rules)
    sim.state.sun_angle, sim.state.orbit_height, sim.state.water_meter = math.pi / 2, orbit, water
    return sim


def loss(sim: Simulation, seconds: float = 1.0, dt: float = 0.05) -> float:
    """Water meter lost over ``seconds``."""
    before = sim.state.water_meter
    for _ in range(round(seconds / dt)):
        sim.step(dt)
    return before - sim.state.water_meter


def test_water_above_field_capacity_drains_away_and_stops_there():
    night = {"orbit": -1.0}  # (no sun: the roots' uptake is small beside drainage)
    wet, moist = sim_at(1.0, **night), sim_at(0.75, **night)
    rules = wet.rules
    assert loss(sim_at(1.0, **night)) > 3 * loss(sim_at(0.75, **night))  # the excess drains, moist soil holds
    loss(wet, 30.0)
    assert wet.state.water_meter < rules.water.field_capacity  # the excess has drained away within 30 s
    assert soil.drainage(0.9, rules) == pytest.approx(rules.water.drainage * 0.1) and soil.drainage(0.7, rules) == 0
    loss(moist, 30.0)
    assert moist.state.water_meter > 0.6  # below field capacity only the roots take water


def test_a_drying_soil_dries_ever_more_slowly_with_no_step():
    rates = [loss(sim_at(w), 0.5) for w in (0.7, 0.5, 0.3, 0.2, 0.1, 0.05)]
    assert all(a > b > 0 for a, b in pairwise(rates))  # the roots take up what stomata let go
    assert rates[-1] < 0.3 * rates[0]
    dry = sim_at(0.5)
    loss(dry, 300.0)  # five minutes of noon sun and nobody waters
    assert 0.0 < dry.state.water_meter < 0.1  # it falls ever more slowly: never to nothing at once


def test_the_oxygen_dose_harms_graded_and_heals():
    rules = Rules()
    doses = [0.0, 5.0, 15.0, 30.0, 60.0, 120.0]
    health = [soil.root_health(d, 1.0, rules) for d in doses]
    assert health[0] == 1.0 and health[3] == pytest.approx(0.5) and all(a > b for a, b in pairwise(health))
    assert soil.root_health(30.0, 4.0, rules) > 0.9  # a tolerant species' roots bear the same dose
    flooded = sim_at(1.0)
    for _ in range(200):  # 20 s with the can held: the soil's oxygen runs out
        flooded.state.watering = True
        flooded.step(0.1)
    assert flooded.state.oxygen < 0.2 and 0 < flooded.state.drowning < rules.water.drown_time
    flooded.state.watering = False
    taken = flooded.state.drowning
    loss(flooded, 4 * rules.water.repair_time, dt=0.1)  # drained: air comes back and the roots heal
    assert flooded.state.oxygen > 0.9 and flooded.state.drowning < 0.2 * taken


def lived_flooded(tolerance: float, rules: Rules) -> float:
    """Real days (the declared time scale) a tree of flood tolerance ``tolerance`` lives in waterlogged soil."""
    sim = Simulation(rules)
    sim.flood_tolerance = tolerance
    day = 2 * math.pi / rules.sun.speed
    t, dt = 0.0, day / 400
    while sim.state.alive and t < 100 * day:
        sim.state.water_meter = 1.0
        sim.step(dt)
        t += dt
    return t / day * real_days(rules)


def test_flood_intolerant_seedlings_live_weeks_tolerant_ones_months():
    """Kozlowski 1997, Responses of woody plants to flooding and salinity: flood-intolerant seedlings die in
    1-4 weeks of waterlogging, tolerant ones live months (FLOOD 1 the maple's, 4 the poplar's, 8 the willow's)."""
    rules = Rules()
    rules.seasons.enabled = False
    assert 7 <= lived_flooded(1.0, rules) <= 28
    assert 30 <= lived_flooded(4.0, rules) <= 180 and 60 <= lived_flooded(8.0, rules) <= 180


def test_wilting_grows_with_the_dryness():
    wilts = []
    for water in (0.14, 0.1, 0.05, 0.0):
        sim = sim_at(water)
        for _ in range(100):
            sim.state.water_meter = water
            sim.step(0.1)
        wilts.append(sim.state.wilt)
    assert 0 < wilts[0] < wilts[1] < wilts[2] < wilts[3]
    assert wilts[3] == pytest.approx(10 * sim.rules.health.wilt_rate, rel=0.05)


def test_late_cycles_cut_the_sun_s_length_and_the_water_s_girth_growth():
    """Seed 003 (2.3.1-2.3.2): the tree grows once both meters earned; a late sun cycle reduces the length
    growth, a late water cycle the girth growth."""
    sim = sim_at(0.9)
    assert sim.growth_speeds() == (0.0, 0.0)  # nothing earned yet
    s = sim.state
    s.sun_cycle.earned = s.water_cycle.earned = 1
    s.sun_cycle.rate = s.water_cycle.rate = 1.0
    length, girth = sim.growth_speeds()
    s.water_cycle.rate = 0.25
    assert sim.growth_speeds() == pytest.approx((length, 0.25 * girth))
    s.water_cycle.rate, s.sun_cycle.rate = 1.0, 0.5
    assert sim.growth_speeds() == pytest.approx((0.5 * length, girth))


def test_a_save_from_before_the_soil_s_oxygen_loads():
    sim = sim_at(1.0)
    for _ in range(100):
        sim.state.watering = True
        sim.step(0.1)
    data = sim.state.to_dict()
    assert sim_state(data) == sim.state and data["oxygen"] < 1.0
    del data["oxygen"]
    assert sim_state(data).oxygen == 1.0
