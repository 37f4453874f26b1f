"""The sun from solar geometry: elevation from latitude, date and hour, a clear-sky atmosphere, PAR; checked
against references computed here independently (the top-of-atmosphere daily insolation, FAO-56's clear-sky
radiation), and the game's orbit against the real sun's day."""

import math

import numpy as np
import pytest

from arbor.engine.life.plant import solar
from arbor.engine.life.rules.rules import Rules

MIDSUMMER = 172


def top_of_atmosphere(latitude: float, day: int, constant: float = 1361.0) -> float:
    """Daily insolation at the top of the atmosphere (MJ per m²), closed form (Allen et al. 1998, FAO-56 eq. 21;
    Liou 2002): the sunset hour angle from the sunrise equation, the Earth-Sun distance, Spencer-free."""
    dec = 0.409 * math.sin(2 * math.pi * day / 365 - 1.39)  # FAO-56 eq. 24 (not Cooper's, used by the model)
    phi = math.radians(latitude)
    sunset = math.acos(max(-1.0, min(1.0, -math.tan(phi) * math.tan(dec))))
    distance = 1 + 0.033 * math.cos(2 * math.pi * day / 365)
    return 86400 / math.pi * constant * 1e-6 * distance * (sunset * math.sin(phi) * math.sin(dec)
                                                           + math.cos(phi) * math.cos(dec) * math.sin(sunset))


def test_the_elevation_follows_latitude_date_and_hour():
    assert math.degrees(solar.elevation(0.0, 80, 12.0)) == pytest.approx(90.0, abs=0.5)  # equinox noon, equator
    assert math.degrees(solar.elevation(52.0, MIDSUMMER, 12.0)) == pytest.approx(90 - 52 + 23.45, abs=0.1)
    assert math.degrees(solar.elevation(52.0, 355, 12.0)) == pytest.approx(90 - 52 - 23.45, abs=0.1)
    assert solar.elevation(52.0, MIDSUMMER, 0.0) < 0  # midnight
    morning, noon = solar.elevation(30.0, MIDSUMMER, np.array([8.0, 12.0]))
    assert 0 < morning < noon and solar.elevation(30.0, MIDSUMMER, 16.0) == pytest.approx(morning)


def test_the_clear_sky_weakens_a_low_sun():
    rules = Rules().sun
    assert float(solar.air_mass(math.pi / 2)) == pytest.approx(1.0, abs=1e-3)
    assert float(solar.air_mass(math.radians(30))) == pytest.approx(2.0, abs=0.01)  # ~1/sin(30°)
    assert 35 < float(solar.air_mass(0.0001)) < 40  # Kasten & Young's horizon
    assert 950 < float(solar.global_irradiance(math.pi / 2, rules)) < 1100  # a clear noon near the zenith
    strength = [solar.strength(math.radians(d), rules) for d in (5, 15, 30, 60, 90)]
    assert strength == sorted(strength) and strength[-1] == 1.0 and strength[0] < 0.05
    assert strength[2] < 0.5 * strength[3] * 1.1  # the beam through twice the air on a slant: less than half
    assert 2000 < solar.full_par(rules) * rules.par_photons < 2500  # full sun, µmol per m² per s


def test_daily_light_against_latitude_at_midsummer_is_within_15_percent_of_the_references():
    """FAO-56's clear-sky radiation (0.75 x the top of the atmosphere's, Allen et al. 1998 eq. 37) at 0, 30 and
    60 N, and the rise from the equator to 60 N against the top of the atmosphere's (1.24x)."""
    rules = Rules().sun
    model = {lat: solar.daily_global(lat, MIDSUMMER, rules) for lat in (0, 30, 60)}
    toa = {lat: top_of_atmosphere(lat, MIDSUMMER) for lat in (0, 30, 60)}
    for lat in (0, 30, 60):
        assert model[lat] == pytest.approx(0.75 * toa[lat], rel=0.15), (lat, model[lat], toa[lat])
    assert model[60] / model[0] == pytest.approx(toa[60] / toa[0], rel=0.15)
    assert solar.daily_par(30, MIDSUMMER, rules) == pytest.approx(rules.par_share * model[30])
