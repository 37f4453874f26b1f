"""A leaf's photosynthesis: the non-rectangular hyperbola of its light response, in real units, and the game's
declared time scale that turns real rates into the game's.

Gross assimilation A (µmol CO2 per m² of leaf per s) at a photon flux I (µmol per m² per s) is the smaller root
of ``theta A² - (phi I + Amax) A + phi I Amax = 0`` (Thornley 1976, "Mathematical Models in Plant Physiology";
the form used by Ögren & Evans 1993 and most canopy models): it rises with slope ``phi`` (the quantum
efficiency) in dim light and bends toward ``Amax`` (light-saturated assimilation) in bright light, more sharply
the larger the curvature ``theta``. Dark respiration is a share of Amax (Reich et al. 1998, "Relationships of
leaf dark respiration to leaf nitrogen, specific leaf area and leaf life-span"). A species gives its own Amax,
phi and respiration share as the .lsys defines AMAX, QE and RDS (the game tree and the poplar cite theirs);
the rules' [carbon] table gives the defaults.

**The time scale.** A game year of ``seasons.year_days`` game days stands for ``seasons.real_year`` real days
(engine/life/rules/schema.py): a game day is a representative day of about 13 real days of a growing year, at
every pace. So a rate per real second becomes a rate per game second by :func:`real_seconds` (real seconds a
game second stands for: 8,966 at the demo pace, 13 at the home pace).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from arbor.engine.life.rules.rules import Rules, species_trait

CH2O = 30.03e-6  # g of sugar (CH2O) per µmol of CO2 fixed
DAY = 86400.0  # s in a real day


def real_days(rules: Rules) -> float:
    """Real days of a tree's growing year a game day stands for (the declared time scale)."""
    return rules.seasons.real_year / rules.seasons.year_days


def real_seconds(rules: Rules) -> float:
    """Real seconds a game second stands for: a game day (a turn of the sun at the rules' speed) stands for
    :func:`real_days` real days."""
    game_day = 2 * math.pi / rules.sun.speed
    return real_days(rules) * DAY / game_day


@dataclass(frozen=True)
class LeafTraits:
    """A species' leaves: light-saturated gross assimilation ``amax`` and dark respiration ``dark`` (µmol CO2
    per m² per s), quantum efficiency ``quantum`` (mol CO2 per mol of photons) and curvature ``curvature``."""

    amax: float
    quantum: float
    curvature: float
    dark: float


def leaf_traits(constants: dict[str, float], rules: Rules) -> LeafTraits:
    """A species' leaf traits: its .lsys AMAX, QE and RDS (dark respiration as a share of AMAX), else the rules'."""
    c = rules.carbon
    amax = species_trait(constants, "AMAX", "carbon.amax", c.amax)
    return LeafTraits(amax, species_trait(constants, "QE", "carbon.quantum_efficiency", c.quantum_efficiency),
                      c.curvature, amax * species_trait(constants, "RDS", "carbon.dark_share", c.dark_share))


def gross(ppfd: np.ndarray | float, traits: LeafTraits) -> np.ndarray:
    """Gross assimilation (µmol CO2 per m² per s) at photon flux ``ppfd`` (µmol per m² per s): the
    non-rectangular hyperbola."""
    q = traits.quantum * np.maximum(np.asarray(ppfd, float), 0.0)
    s = q + traits.amax
    theta = traits.curvature
    if theta <= 1e-9:  # the rectangular hyperbola
        return q * traits.amax / np.maximum(s, 1e-12)
    return (s - np.sqrt(np.maximum(s * s - 4.0 * theta * q * traits.amax, 0.0))) / (2.0 * theta)


def grams(umol: np.ndarray | float, rules: Rules) -> np.ndarray | float:
    """A real rate in µmol CO2 per m² per s as the game's: g of sugar per m² per game second."""
    return umol * CH2O * real_seconds(rules)
