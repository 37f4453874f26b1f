"""The game's sun: its sliders (the orbit's height: the day length; its side: the noon elevation) give the real
sun's daily light, its strength follows its elevation, and shade dims it without shortening the day."""

import math

import pytest

from arbor.engine.life.experiment.measure import place_day_par
from arbor.engine.life.experiment.schema import day_length_height, elevation_side
from arbor.engine.life.plant import solar
from arbor.engine.life.plant.sim import Simulation
from arbor.engine.life.rules.rules import Rules

MIDSUMMER = 172


def test_the_game_s_sun_sliders_give_the_real_sun_s_daily_light():
    rules = Rules().sun
    for lat in (0, 30, 60):
        assert place_day_par(lat, MIDSUMMER) == pytest.approx(solar.daily_par(lat, MIDSUMMER, rules), rel=0.15)


def test_shade_dims_the_sun_and_keeps_the_day_length():
    rules = Rules()
    rules.seasons.enabled = False
    sim = Simulation(rules)
    shaded_rules = Rules()
    shaded_rules.seasons.enabled = False
    shaded_rules.sun.shade = 0.6
    shaded = Simulation(shaded_rules)
    lit = dark = 0.0
    up = up_shaded = 0
    for k in range(1000):
        sim.state.sun_angle = shaded.state.sun_angle = 2 * math.pi * k / 1000
        lit += sim.sunshine()
        dark += shaded.sunshine()
        up += sim.sunshine() > 0
        up_shaded += shaded.sunshine() > 0
    assert dark == pytest.approx(0.4 * lit) and up == up_shaded > 0


def test_a_low_noon_sun_is_weaker_than_a_high_one_for_the_same_day_length():
    """Lesson 1's claim: at one noon elevation the noon sun is as strong whatever the day length; a lower noon
    sun is weaker."""
    strengths = {}
    for hours, elevation in ((6, 60), (18, 60), (14, 30)):
        rules = Rules()
        rules.seasons.enabled = False
        rules.sun.side = elevation_side(elevation, day_length_height(hours))
        sim = Simulation(rules)
        sim.set_orbit_height(day_length_height(hours))
        sim.state.sun_angle = math.pi / 2
        strengths[hours, elevation] = sim.sunshine()
    assert strengths[6, 60] == pytest.approx(strengths[18, 60])
    assert strengths[14, 30] < 0.7 * strengths[18, 60]
