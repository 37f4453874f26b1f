"""Every game rule in one file (assets/rules.toml), read strictly, with named paces.

A pace scales time: the same rules run at seed 003's demonstration pace (a day of the sun in about
two minutes, growth earned after 20 s above half) or at a home pace (a day of the sun in a day, meters
that last about a day, seasons of a week). Times are multiplied by the pace's time scale and rates
divided by it, so the 20 s / 40 s rules keep their shape; a pace may also override single rules.
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from arbor.engine.base.config import fill_dataclass
from arbor.engine.base.errors import LSysError


@dataclass
class LightRules:
    """How light is measured (assets/rules.toml [light])."""

    cell: float = 0.9  # side of a shadow cell across the sun's rays, scene units (about a leaf)
    extinction: float = 0.55  # Beer-Lambert coefficient per leaf area per cell area
    sky: float = 0.3  # share of the light that comes from the open sky above rather than the sun disc
    interval: float = 6.0  # seconds of game time between two light measurements (scaled by the pace)
    memory: float = 12.0  # physiological time over which buds and leaves remember their light


@dataclass
class GrowthRules:
    """When a meter earns growth, and how fast the tree's two clocks run."""

    threshold: float = 0.5
    hold_time: float = 20.0
    deadline: float = 40.0
    penalty_time: float = 40.0
    length_rate: float = 0.06
    girth_rate: float = 0.1
    rewrite_step: float = 1.0
    sapling_age: float = 12.0


@dataclass
class SunRules:
    """The sun's orbit (slider defaults and ranges) and how it fills the sun meter."""

    orbit_height: float = 0.35
    orbit_height_min: float = -1.0
    orbit_height_max: float = 1.0
    speed: float = 0.05
    speed_min: float = 0.005
    speed_max: float = 0.5
    fill_rate: float = 0.04
    drain_rate: float = 0.006
    side: float = 0.45  # how far to one side (+z, "south") the sun's path lies, in orbit radii


@dataclass
class WaterRules:
    """How the water meter drains, fills and drowns the roots."""

    drain_rate: float = 0.004
    sun_drain_rate: float = 0.008
    fill_rate: float = 0.12
    drown_level: float = 0.95
    drown_time: float = 30.0
    leaf_min: float = 0.45  # leaf vigour (size, and how long leaves stay) with an empty water meter
    drought_level: float = 0.35  # below this, drought makes shaded branches die faster


@dataclass
class HealthRules:
    """Neglect, wilting and death."""

    neglect_level: float = 0.15
    wilt_rate: float = 0.02
    recover_rate: float = 0.01
    death_time: float = 120.0


@dataclass
class ReplantRules:
    """The sapling button's meter refill range."""

    meter_min: float = 0.25
    meter_max: float = 1.0


@dataclass
class WindRules:
    """The wind that sways the tree (it never changes the L-string): strength 0 is still air."""

    strength: float = 0.35  # sway at the outermost twigs, as a share of the tree's height x 0.1
    direction: float = 60.0  # degrees from +x toward +z the wind blows to
    gusts: float = 0.5  # how much the strength rises and falls (0 steady .. 1 from calm to twice)


@dataclass
class SeasonRules:
    """A year of seasons: spring flush and blossoms, summer growth, autumn colours and leaf fall,
    winter rest. The year is counted in days of the sun (turns of its orbit)."""

    enabled: bool = True  # false: an endless summer (experiments that study light or water alone)
    year_days: float = 28.0  # days of the sun in a year (a season is a quarter of it)
    start: float = 0.05  # where in the year a new garden starts (0 = first day of spring)
    sun_swing: float = 0.25  # the sun stands this much higher in summer and lower in winter (orbit radii)
    spring_growth: float = 1.2  # growth clocks x this in spring ...
    summer_growth: float = 1.0
    autumn_growth: float = 0.5
    winter_growth: float = 0.0  # ... winter rest: no growth
    winter_water: float = 0.3  # the water meter drains this much as fast in winter (no leaves)
    flush: float = 3.0  # buds wake this many times as eagerly in spring
    leaf_fall: float = 0.08  # per unit of physiological time in autumn: chance a leaf starts to fall
    mature_age: float = 80.0  # physiological age from which a healthy tree blossoms in spring


@dataclass
class WeatherRules:
    """Rain showers that fill the water meter (one chance a day, by season) and how the wind changes."""

    spring_rain: float = 0.5  # chance of a shower on a spring day
    summer_rain: float = 0.3
    autumn_rain: float = 0.45
    winter_rain: float = 0.2
    shower: float = 0.08  # how long a shower lasts, as a share of the day
    rain_fill: float = 0.02  # water meter per second while it rains (at the demo pace)
    rain_wind: float = 2.0  # wind x this during a shower


@dataclass
class TimeAwayRules:
    """What happens while the player is away."""

    cap_days: float = 14.0  # real days of absence that are lived at most
    fast_light: float = 4.0  # light readings a day while catching up (fewer than in play: it must be quick)


@dataclass
class RootRules:
    """Roots (engine/life/roots.py): how fast they grow on water and how much they spare it."""

    growth_rate: float = 0.06  # root time per second with a full water meter
    step: float = 0.5  # root time between two rewrites of the roots' L-string
    drain_relief: float = 0.35  # a full root system drains the water meter this much more slowly
    full_length: float = 150.0  # scene units of roots that count as a full root system


@dataclass
class Rules:
    """All game rules, one section per table of rules.toml."""

    growth: GrowthRules = field(default_factory=GrowthRules)
    sun: SunRules = field(default_factory=SunRules)
    water: WaterRules = field(default_factory=WaterRules)
    health: HealthRules = field(default_factory=HealthRules)
    replant: ReplantRules = field(default_factory=ReplantRules)
    light: LightRules = field(default_factory=LightRules)
    wind: WindRules = field(default_factory=WindRules)
    seasons: SeasonRules = field(default_factory=SeasonRules)
    weather: WeatherRules = field(default_factory=WeatherRules)
    away: TimeAwayRules = field(default_factory=TimeAwayRules)
    roots: RootRules = field(default_factory=RootRules)
    pace: str = "demo"  # the pace these rules are at
    time_scale: float = 1.0  # real seconds per second of the demo pace


# Fields that are times (multiplied by a pace's time scale) and rates per second (divided by it).
# The watering can's fill rate is neither: a player holds the can for seconds at any pace.
TIMES = ("growth.hold_time", "growth.deadline", "growth.penalty_time", "water.drown_time", "health.death_time",
         "light.interval")
RATES = ("growth.length_rate", "growth.girth_rate", "sun.speed", "sun.speed_min", "sun.speed_max", "sun.fill_rate",
         "sun.drain_rate", "water.drain_rate", "water.sun_drain_rate", "health.wilt_rate", "health.recover_rate",
         "weather.rain_fill", "roots.growth_rate")
SECTIONS = ("growth", "sun", "water", "health", "replant", "light", "wind", "seasons", "weather", "away", "roots")


def load_rules(path: str | Path, pace: str | None = None) -> Rules:
    """Read rules.toml at ``pace`` (default: the file's ``pace``); unknown tables/keys or non-numbers
    are errors naming the file and key."""
    path = Path(path)
    file = str(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except tomllib.TOMLDecodeError as exc:
        raise LSysError(f"not valid TOML: {exc}", file) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise LSysError(f"cannot read: {exc}", file) from None
    paces = data.pop("paces", {})
    chosen = pace or data.pop("pace", "demo")
    data.pop("pace", None)
    if not isinstance(paces, dict) or not isinstance(chosen, str) or (chosen != "demo" and chosen not in paces):
        raise LSysError(f"unknown pace {chosen!r}: rules.toml names {', '.join(['demo', *paces])}", file)
    rules = Rules()
    for table, values in data.items():
        if table not in SECTIONS or not isinstance(values, dict):
            raise LSysError(f"unknown table [{table}]", file)
        fill_dataclass(getattr(rules, table), values, file, f"key in [{table}]")
    check_rules(rules, file)
    return apply_pace(rules, chosen, paces.get(chosen, {}), file)


def apply_pace(rules: Rules, name: str, pace: dict, file: str = "<rules>") -> Rules:
    """Scale ``rules`` to a pace: times x ``time_scale``, rates / it, then the pace's own overrides
    (``"section.key" = value``, at the pace's own scale)."""
    if not isinstance(pace, dict):
        raise LSysError(f"[paces.{name}] must be a table", file)
    scale = pace.get("time_scale", 1.0)
    if isinstance(scale, bool) or not isinstance(scale, int | float) or not 0.01 <= scale <= 1e5:
        raise LSysError(f"[paces.{name}] time_scale must be a number from 0.01 to 100000", file)
    for key in TIMES:
        section, attr = key.split(".")
        setattr(getattr(rules, section), attr, getattr(getattr(rules, section), attr) * scale)
    for key in RATES:
        section, attr = key.split(".")
        setattr(getattr(rules, section), attr, getattr(getattr(rules, section), attr) / scale)
    for key, value in pace.items():
        if key == "time_scale":
            continue
        section, _, attr = key.partition(".")
        if section not in SECTIONS or not hasattr(getattr(rules, section), attr):
            raise LSysError(f"[paces.{name}]: unknown rule {key!r}", file)
        fill_dataclass(getattr(rules, section), {attr: value}, file, f"key in [paces.{name}]")
    rules.pace, rules.time_scale = name, float(scale)
    return rules


# Physical limits of every rule (section.key -> low, high); anything else is a typo or a misunderstanding.
RULE_RANGES = {
    "growth.threshold": (0.01, 0.99), "growth.hold_time": (0.0, 1e7), "growth.deadline": (0.0, 1e7),
    "growth.penalty_time": (1e-3, 1e7), "growth.length_rate": (0.0, 100.0), "growth.girth_rate": (0.0, 100.0),
    "growth.rewrite_step": (0.01, 100.0), "growth.sapling_age": (0.0, 1000.0),
    "sun.orbit_height": (-1.0, 1.0), "sun.orbit_height_min": (-1.0, 1.0), "sun.orbit_height_max": (-1.0, 1.0),
    "sun.speed": (1e-7, 10.0), "sun.speed_min": (1e-7, 10.0), "sun.speed_max": (1e-7, 10.0),
    "sun.fill_rate": (0.0, 100.0), "sun.drain_rate": (0.0, 100.0), "sun.side": (-10.0, 10.0),
    "water.drain_rate": (0.0, 100.0), "water.sun_drain_rate": (0.0, 100.0), "water.fill_rate": (0.0, 100.0),
    "water.drown_level": (0.0, 1.0), "water.drown_time": (0.0, 1e7), "water.leaf_min": (0.0, 1.0),
    "water.drought_level": (0.0, 1.0),
    "health.neglect_level": (0.0, 1.0), "health.wilt_rate": (0.0, 100.0), "health.recover_rate": (0.0, 100.0),
    "health.death_time": (0.0, 1e8),
    "replant.meter_min": (0.0, 1.0), "replant.meter_max": (0.0, 1.0),
    "light.cell": (0.05, 100.0), "light.extinction": (0.0, 100.0), "light.sky": (0.0, 1.0),
    "light.interval": (0.01, 1e6), "light.memory": (0.01, 1e6),
    "wind.strength": (0.0, 5.0), "wind.direction": (-360.0, 360.0), "wind.gusts": (0.0, 1.0),
    "seasons.year_days": (1.0, 1000.0), "seasons.start": (0.0, 1.0), "seasons.sun_swing": (0.0, 1.0),
    "seasons.spring_growth": (0.0, 10.0), "seasons.summer_growth": (0.0, 10.0), "seasons.autumn_growth": (0.0, 10.0),
    "seasons.winter_growth": (0.0, 10.0), "seasons.winter_water": (0.0, 10.0), "seasons.flush": (0.0, 100.0),
    "seasons.leaf_fall": (0.0, 100.0), "seasons.mature_age": (0.0, 1e6),
    "weather.spring_rain": (0.0, 1.0), "weather.summer_rain": (0.0, 1.0), "weather.autumn_rain": (0.0, 1.0),
    "weather.winter_rain": (0.0, 1.0), "weather.shower": (0.0, 1.0), "weather.rain_fill": (0.0, 100.0),
    "weather.rain_wind": (0.0, 10.0), "away.cap_days": (0.0, 3650.0), "away.fast_light": (0.5, 100.0),
    "roots.growth_rate": (0.0, 100.0), "roots.step": (0.01, 100.0), "roots.drain_relief": (0.0, 0.9),
    "roots.full_length": (1.0, 1e5),
}


def check_rules(rules: Rules, file: str) -> None:
    """Every rule within its physical limits, and every slider range the right way round."""
    for key, (low, high) in RULE_RANGES.items():
        section, name = key.split(".")
        value = getattr(getattr(rules, section), name)
        if not low <= value <= high:
            raise LSysError(f"'{name}' in [{section}] must be from {low:g} to {high:g} (it is {value:g})", file)
    sun = rules.sun
    if not sun.orbit_height_min <= sun.orbit_height <= sun.orbit_height_max:
        raise LSysError("[sun] orbit_height must lie between orbit_height_min and orbit_height_max", file)
    if not sun.speed_min <= sun.speed <= sun.speed_max:
        raise LSysError("[sun] speed must lie between speed_min and speed_max", file)
    if rules.replant.meter_min > rules.replant.meter_max:
        raise LSysError("[replant] meter_min must not be above meter_max", file)


