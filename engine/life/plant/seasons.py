"""Seasons and weather, as functions of how many days of the sun have passed (its orbit's turns).

A year is ``year_days`` turns: spring, summer, autumn, winter, a quarter each. Growth, water need and
the sun's height follow the year smoothly (each season's value is blended into the next over the last
tenth of a season, so nothing jumps at midnight). A shower falls on a day with the season's chance; which
days and when is a hash of the day and the garden's weather seed: the same garden has the same weather
whoever replays it, and no weather state needs saving.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

from arbor.engine.life.rules.rules import Rules

SEASONS = ("spring", "summer", "autumn", "winter")
BLEND = 0.1  # share of a season over which its values blend into the next season's


@dataclass(frozen=True)
class Season:
    """Where in the year a moment lies."""

    name: str
    index: int  # 0 spring .. 3 winter
    progress: float  # 0..1 through this season
    year: int  # whole years passed


def season_at(turns: float, rules: Rules) -> Season:
    """The season ``turns`` days of the sun into the garden's life (always summer without seasons)."""
    if not rules.seasons.enabled:
        return Season("summer", 1, 0.5, 0)
    year = turns / rules.seasons.year_days + rules.seasons.start
    quarter = (year % 1.0) * 4.0
    index = min(int(quarter), 3)
    return Season(SEASONS[index], index, quarter - index, math.floor(year))


def _blended(turns: float, rules: Rules, values: tuple[float, float, float, float]) -> float:
    s = season_at(turns, rules)
    if not rules.seasons.enabled:
        return values[1]  # summer
    here, nxt = values[s.index], values[(s.index + 1) % 4]
    if s.progress < 1.0 - BLEND:
        return here
    t = (s.progress - (1.0 - BLEND)) / BLEND
    return here + (nxt - here) * (0.5 - 0.5 * math.cos(math.pi * t))


def growth_factor(turns: float, rules: Rules) -> float:
    """How fast the growth clocks run in this season (0 in winter rest)."""
    r = rules.seasons
    return _blended(turns, rules, (r.spring_growth, r.summer_growth, r.autumn_growth, r.winter_growth))


def stores(turns: float, rules: Rules) -> float:
    """How much of carbon.winter_keep the tree keeps from growth now: all of it in autumn and winter, half
    in spring (its leaves are still unfolding), none in summer (none without seasons)."""
    return _blended(turns, rules, (0.5, 0.0, 1.0, 1.0)) if rules.seasons.enabled else 0.0


def water_factor(turns: float, rules: Rules) -> float:
    """How fast the water meter drains in this season (leafless in winter: slowly)."""
    return _blended(turns, rules, (1.0, 1.0, 1.0, rules.seasons.winter_water))


def sun_offset(turns: float, rules: Rules) -> float:
    """How much higher (summer) or lower (winter) the sun's orbit stands, in orbit radii."""
    if not rules.seasons.enabled:
        return 0.0
    year = turns / rules.seasons.year_days + rules.seasons.start
    return rules.seasons.sun_swing * math.cos(2 * math.pi * (year - 0.375))  # highest mid-summer


def flush(turns: float, rules: Rules) -> float:
    """Buds' eagerness to wake: the spring flush."""
    return _blended(turns, rules, (rules.seasons.flush, 1.0, 1.0, 1.0))


def leaf_fall(turns: float, rules: Rules) -> float:
    """Per unit of physiological time, the chance a leaf starts to fall (autumn only)."""
    return _blended(turns, rules, (0.0, 0.0, rules.seasons.leaf_fall, 0.0))


def leaf_keep(turns: float, rules: Rules) -> float:
    """Share of the leaves still on the tree (0..1): all of them until mid-autumn (colours first), then fewer and fewer,
    none in winter. The renderer hides leaves by their hash so the crown thins smoothly; the L-string
    drops what is left when winter comes (GrowingTree.drop_leaves)."""
    s = season_at(turns, rules)
    if not rules.seasons.enabled or s.index < 2:
        return 1.0
    if s.index == 3:
        return 0.0
    t = min(max((s.progress - 0.5) / 0.45, 0.0), 1.0)
    return 1.0 - t * t * (3.0 - 2.0 * t)


def evergreen(constants: Mapping[str, float]) -> bool:
    """Whether a tree's .lsys ``constants`` keep its leaves through winter (its EVERGREEN define set)."""
    return constants.get("EVERGREEN", 0.0) >= 0.5


def leafy(turns: float, rules: Rules) -> bool:
    """True while the crown is in full leaf: from a little into spring until the leaves start to fall."""
    s = season_at(turns, rules)
    return not rules.seasons.enabled or (s.index == 0 and s.progress >= 0.25) or s.index == 1 or (
        s.index == 2 and leaf_keep(turns, rules) >= 0.999)


def autumn_colour(turns: float, rules: Rules) -> float:
    """0 green .. 1 full autumn colour: rising through autumn, gone by the next spring."""
    s = season_at(turns, rules)
    if s.index == 2:
        return min(1.0, 0.2 + 1.2 * s.progress)
    if s.index == 1 and s.progress > 0.85:
        return (s.progress - 0.85) / 0.15 * 0.2
    return 1.0 if s.index == 3 else 0.0


def _hash(day: int, seed: int, salt: int) -> float:
    """A number in [0, 1) from a day and a seed (no state: the weather replays exactly)."""
    x = math.sin(day * 12.9898 + (seed % 10007) * 78.233 + salt * 37.719) * 43758.5453
    return x - math.floor(x)


def raining(turns: float, seed: int, rules: Rules) -> bool:
    """Whether a shower is falling now (one chance a day, at a time of day of its own)."""
    day = math.floor(turns)
    w = rules.weather
    chance = (w.spring_rain, w.summer_rain, w.autumn_rain, w.winter_rain)[season_at(turns, rules).index]
    if _hash(day, seed, 1) >= chance:
        return False
    start = 0.1 + 0.7 * _hash(day, seed, 2)
    return start <= turns - day < start + w.shower
