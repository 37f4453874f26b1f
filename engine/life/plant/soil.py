"""The soil's water as a bucket the roots drink from, and the oxygen its air holds (issue 43: water as a gradient).

The water meter is the bucket's fill (0 dry .. 1 saturated). Water above ``water.field_capacity`` drains away
below the roots, a share ``water.drainage`` of the excess each second (gravity drainage: a wetted soil is back at
field capacity within a day or two; Allen, Pereira, Raes & Smith 1998, FAO-56 "Crop evapotranspiration", ch. 8).
The roots take water up as far as the stomata let it go (:func:`opening`: they close smoothly as the soil
dries, no threshold; Jarvis 1976), so a drying soil dries ever more slowly and never falls off a cliff.

A soil above ``water.drown_level`` is waterlogged: its pores are full and the oxygen in them is used up by the
roots and microbes over about ``water.oxygen_time``; once it drains it comes back as fast (Ponnamperuma 1972,
"The chemistry of submerged soils"; Kozlowski 1997, "Responses of woody plants to flooding and salinity"). The
roots take a **dose** of want of oxygen (s of full anoxia, the state's ``drowning``) which they heal over
``water.repair_time`` while they have air; their uptake falls smoothly with the dose, to half at ``drown_time``
x the species' flood tolerance (:func:`root_health`), and past it the tree wilts (Simulation.drowned).
"""

from __future__ import annotations

import math

from arbor.engine.life.rules.rules import Rules

__all__ = ["dose_after", "drainage", "opening", "oxygen_after", "root_health"]


def opening(water: float, rules: Rules) -> float:
    """How far the stomata are open (0..1) at the soil's water ``water`` (the meter, 0..1): ``(1 - exp(-water /
    s)) / (1 - exp(-1 / s))`` with s the rule water.stomata_scale, smooth from 0 to 1 with no threshold."""
    s = rules.water.stomata_scale
    return min(max((1.0 - math.exp(-max(water, 0.0) / s)) / (1.0 - math.exp(-1.0 / s)), 0.0), 1.0)


def drainage(water: float, rules: Rules) -> float:
    """Meter per s draining below the roots: water.drainage x the water above field capacity (0 below it)."""
    w = rules.water
    return w.drainage * max(water - w.field_capacity, 0.0)


def oxygen_after(oxygen: float, water: float, dt: float, rules: Rules) -> float:
    """The soil air's oxygen (0..1 of a drained soil's) ``dt`` s on: toward 0 while the soil is waterlogged
    (above water.drown_level), toward 1 otherwise, over water.oxygen_time (exactly, for any ``dt``)."""
    w = rules.water
    target = 0.0 if water > w.drown_level else 1.0
    return target + (oxygen - target) * math.exp(-dt / max(w.oxygen_time, 1e-9))


def dose_after(dose: float, oxygen: float, dt: float, rules: Rules, resting: bool = False) -> float:
    """The roots' dose of want of oxygen (s of full anoxia) ``dt`` s on: it grows by (1 - oxygen) a second and
    heals over water.repair_time in proportion to the oxygen there is. Resting roots (winter) take no dose."""
    heal = math.exp(-oxygen * dt / max(rules.water.repair_time, 1e-9))
    return max(dose * heal + (0.0 if resting else (1.0 - oxygen) * dt), 0.0)


def root_health(dose: float, tolerance: float, rules: Rules) -> float:
    """How well the roots still take up water (0..1) after an oxygen dose ``dose`` (s): ``1 / (1 + (dose /
    (drown_time x tolerance))²)``, half at the species' drown time, falling smoothly (no threshold)."""
    scale = max(rules.water.drown_time * tolerance, 1e-9)
    return 1.0 / (1.0 + (max(dose, 0.0) / scale) ** 2)
