"""The sun's strength from solar geometry through a clear-sky atmosphere, in W/m² and MJ/m² a day of PAR.

- **Elevation** from latitude, day of the year and hour: the declination by Cooper's formula (Cooper 1969,
  "The absorption of radiation in solar stills"), the hour angle 15° an hour from solar noon, and
  sin(elevation) = sin(lat) sin(decl) + cos(lat) cos(decl) cos(hour angle).
- **Air mass** by Kasten & Young (1989, "Revised optical air mass tables and approximation formula").
- **Clear sky**: the direct beam through the air mass by Meinel & Meinel's transmittance (1976, "Applied
  Solar Energy": ``S0 x 0.7^(AM^0.678)``), plus diffuse light from the sky as a share of the beam (the same
  source's rule of thumb, a tenth), both on a horizontal surface: the global irradiance.
- **PAR**: a share of the global irradiance (McCree 1972, "Test of current definitions of photosynthetically
  active radiation against leaf photosynthesis data": 0.45-0.50), as photons 4.57 µmol per J.

The game's sun (an orbit the player's sliders set) shines with the strength of its elevation
(:func:`strength`): a low sun is weak, a high one strong, whatever the hours of the day. Every constant is a
rule of the schema's [sun] table (engine/life/rules/schema.py) with its source.
"""

from __future__ import annotations

import math

import numpy as np

from arbor.engine.life.rules.rules import SunRules

MJ = 1e-6  # MJ per J


def declination(day_of_year: float | np.ndarray) -> float | np.ndarray:
    """The sun's declination (radians) on ``day_of_year`` (1 = 1 January): Cooper's formula,
    23.45° x sin(2 pi (284 + day) / 365)."""
    return np.radians(23.45) * np.sin(2 * np.pi * (284 + np.asarray(day_of_year, float)) / 365.0)


def elevation(latitude: float, day_of_year: float, hour: float | np.ndarray) -> float | np.ndarray:
    """The sun's elevation above the horizon (radians; negative at night) at ``latitude`` (degrees north)
    on ``day_of_year`` at ``hour`` of solar time (12 = noon)."""
    lat, dec = math.radians(latitude), declination(day_of_year)
    angle = np.radians(15.0 * (np.asarray(hour, float) - 12.0))
    return np.arcsin(np.clip(np.sin(lat) * np.sin(dec) + np.cos(lat) * np.cos(dec) * np.cos(angle), -1.0, 1.0))


def _air_mass(elev):
    """Kasten & Young 1989's formula for an elevation above the horizon (radians; floats or an array)."""
    return 1.0 / (np.sin(elev) + 0.50572 * (np.degrees(elev) + 6.07995) ** -1.6364)


def air_mass(elev: float | np.ndarray) -> np.ndarray:
    """Relative optical air mass at elevation ``elev`` (radians; 1 at the zenith, about 38 at the horizon):
    Kasten & Young 1989. Infinite below the horizon."""
    e = np.asarray(elev, float)
    return np.where(e > 0, _air_mass(np.maximum(e, 0.0)), np.inf)


def global_irradiance(elev: float | np.ndarray, rules: SunRules) -> np.ndarray:
    """Clear-sky global irradiance on a horizontal surface (W/m²) at elevation ``elev`` (radians): the
    Meinel beam (``solar_constant x transmittance^(AM^transmittance_power)``) on the horizontal, plus the
    sky's diffuse light (``diffuse`` x that); 0 with the sun below the horizon."""
    e = np.asarray(elev, float)
    with np.errstate(over="ignore", invalid="ignore"):
        beam = rules.solar_constant * rules.transmittance ** (air_mass(e) ** rules.transmittance_power)
    horizontal = np.where(e > 0, beam * np.sin(np.maximum(e, 0.0)), 0.0)
    return horizontal * (1.0 + rules.diffuse)


def par_watts(elev: float | np.ndarray, rules: SunRules) -> np.ndarray:
    """Clear-sky PAR on a horizontal surface (W/m²) at elevation ``elev`` (radians)."""
    return global_irradiance(elev, rules) * rules.par_share


def full_par(rules: SunRules) -> float:
    """PAR (W/m²) with the sun at the zenith under a clear sky: the game's sun strength 1."""
    return float(par_watts(math.pi / 2, rules))


def strength(elev: float, rules: SunRules) -> float:
    """The sun's strength 0..1 at elevation ``elev`` (radians): its clear-sky PAR against the zenith sun's,
    with the share ``shade`` removed (a shade cloth or a canopy above: it dims the sun, it does not shorten
    the day). In plain floats: the simulation asks at every step."""
    if not elev > 0:
        return 0.0
    mass, zenith = _air_mass(elev), _air_mass(math.pi / 2)
    power, t = rules.transmittance_power, rules.transmittance
    return t ** (mass ** power - zenith ** power) * math.sin(elev) * (1.0 - rules.shade)


def daily_par(latitude: float, day_of_year: float, rules: SunRules, steps: int = 1440) -> float:
    """Clear-sky PAR over one day (MJ per m²) at ``latitude`` on ``day_of_year``: the irradiance integrated
    over ``steps`` moments of the day (midpoints)."""
    hours = (np.arange(steps) + 0.5) * 24.0 / steps
    watts = par_watts(elevation(latitude, day_of_year, hours), rules)
    return float(watts.sum() * 86400.0 / steps * MJ)


def daily_global(latitude: float, day_of_year: float, rules: SunRules, steps: int = 1440) -> float:
    """Clear-sky global irradiation over one day (MJ per m²), as :func:`daily_par` for all wavelengths."""
    hours = (np.arange(steps) + 0.5) * 24.0 / steps
    watts = global_irradiance(elevation(latitude, day_of_year, hours), rules)
    return float(watts.sum() * 86400.0 / steps * MJ)
