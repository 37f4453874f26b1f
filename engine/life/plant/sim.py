"""The sun and water simulation of the tamagotchi game (the tamagotchi thesis, sections 2.3-2.4).

A sun orbits the tree on a vertical circle whose centre height and speed the player sets; the sun
meter fills while it shines on the leaves (as fast as they catch it: a shaded crown fills it more slowly)
and drains at night. The water meter drains (faster in strong sun) and
fills while the watering can is held. The tree grows only after both meters have stayed above half for 20 s;
a cycle that takes longer than 40 s earns less, the longer the less: the sun's cycle the length growth, the
water's the girth growth (the thesis, 2.3.1-2.3.2). The light the leaves caught over the last day sets the
length-growth rate (the thesis had the sun meter's level), water the girth-growth rate. The water meter is
the soil's water as a bucket (engine/life/plant/soil.py): the roots take it up as far as the stomata let it
go (so a drying soil dries ever more slowly), water above field capacity drains away, and waterlogged soil
loses its oxygen, a dose the roots take graded. Neglect (or drowning) wilts the tree; long full wilt kills it.
All constants come from assets/rules.toml (see :func:`load_rules`).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field

import numpy as np

from arbor.engine.life.plant import seasons, soil, solar
from arbor.engine.life.plant.seasons import Season, raining, season_at
from arbor.engine.life.rules.rules import GrowthRules, Rules, clamp_orbit, load_rules
from arbor.engine.life.rules.schema import find_rule

__all__ = ["GrowthCycle", "Rules", "SimState", "Simulation", "load_rules"]


@dataclass
class GrowthCycle:
    """Seed 003's rule for one meter: earn growth by staying above half for ``hold_time``."""

    cycle: float = 0.0  # seconds since growth was last earned
    above: float = 0.0  # seconds above the threshold during this cycle
    rate: float = 0.0  # growth factor 0..1; 0 until the first cycle completes
    earned: int = 0

    def update(self, meter: float, dt: float, rules: GrowthRules) -> None:
        """Advance by ``dt`` seconds with the meter at ``meter``."""
        self.cycle += dt
        if meter > rules.threshold:
            self.above += dt
        late = max(0.0, self.cycle - rules.deadline)
        factor = math.exp(-late / rules.penalty_time)
        if self.above >= rules.hold_time:
            self.rate = factor
            self.earned += 1
            self.cycle = self.above = 0.0
        elif late > 0:
            self.rate = min(self.rate, factor)


@dataclass
class SimState:
    """Everything the simulation needs to continue exactly where it was (saved in save files)."""

    time: float = 0.0
    sun_angle: float = 0.25  # mid-morning
    orbit_height: float = find_rule("sun.orbit_height").default
    sun_speed: float = find_rule("sun.speed").default
    sun_meter: float = 0.6
    water_meter: float = 0.6
    watering: bool = False
    length_time: float = 0.0  # physiological time T: drives new internodes and elongation
    girth_time: float = 0.0  # girth time G: drives thickening
    wilt: float = 0.0
    drowning: float = 0.0  # the roots' dose of want of oxygen (s of full anoxia; engine/life/plant/soil.py)
    dead_for: float = 0.0
    alive: bool = True
    sun_turns: float = 0.0  # days of the sun so far (turns of its orbit): the calendar of the seasons
    weather_seed: int = 0  # which days it rains (see engine/life/plant/seasons.py)
    root_time: float = 0.0  # the roots' clock: runs on water (engine/life/plant/roots.py)
    root_vigour: float = 1.0  # how fast the carbon pool lets the roots grow (set by its World; 0 .. carbon.root_most)
    # the light the leaves fixed sugar with, remembered (0..1 of fully lit, open leaves); a sapling's is the norm
    daylight: float = find_rule("growth.daylight_full").default
    oxygen: float = 1.0  # the soil air's oxygen, 0..1 of a drained soil's (waterlogging uses it up)
    sun_cycle: GrowthCycle = field(default_factory=GrowthCycle)
    water_cycle: GrowthCycle = field(default_factory=GrowthCycle)

    def to_dict(self) -> dict:
        """Plain data (numbers and booleans) for save files."""
        return asdict(self)


def sun_angle_at(seconds_after_midnight: float) -> float:
    """The sun's angle on its orbit at this time of a day (noon at noon): at the home pace, a day of
    the sun lasts a day, so a garden started with it keeps the player's day and night."""
    return (-math.pi / 2 + 2 * math.pi * seconds_after_midnight / 86400.0) % (2 * math.pi)


class Simulation:
    """Steps the meters, the growth clocks and the tree's health with a fixed time step."""

    def __init__(self, rules: Rules | None = None, state: SimState | None = None) -> None:
        self.rules = rules or Rules()
        if state is None:
            state = SimState(orbit_height=self.rules.sun.orbit_height, sun_speed=self.rules.sun.speed,
                             daylight=self.rules.growth.daylight_full)
        self.state = state
        self.root_share = 0.0  # how much of a full root system the tree has (set by its World)
        self.starving = 0.0  # s the tree's carbon pool has been empty with upkeep unpaid (set by its World)
        self.leaf_light = 1.0  # the share of the sun its leaves catch (0..1, set by its World at each step)
        self.flood_tolerance = self.rules.water.flood_tolerance  # its species' (set by its World when planted)

    def season(self) -> Season:
        """The season now (spring, summer, autumn, winter)."""
        return season_at(self.state.sun_turns, self.rules)

    def raining(self) -> bool:
        """Whether a rain shower is falling now."""
        return raining(self.state.sun_turns, self.state.weather_seed, self.rules)

    def season_externs(self, tree_age: float) -> dict[str, float]:
        """What the L-system hears of the season: SF (bud flush), AF (autumn leaf fall per unit of T),
        SP (1 while a mature, healthy tree may blossom in spring), SL (1 while the seasons run: a deciduous
        leaf then lives until autumn's fall, not a fixed span)."""
        turns, rules = self.state.sun_turns, self.rules
        season = self.season()
        bloom = (season.index == 0 and season.progress < rules.seasons.bloom_share
                 and tree_age >= rules.seasons.mature_age)
        healthy = self.resources() > rules.seasons.bloom_health
        return {"SF": seasons.flush(turns, rules), "AF": seasons.leaf_fall(turns, rules),
                "SP": 1.0 if bloom and healthy else 0.0, "SL": 1.0 if rules.seasons.enabled else 0.0}

    def sun_height(self) -> float:
        """Height of the sun above the horizon in orbit radii (negative at night): higher in summer."""
        offset = seasons.sun_offset(self.state.sun_turns, self.rules)
        return self.state.orbit_height + offset + math.sin(self.state.sun_angle)

    def sun_elevation(self) -> float:
        """The sun's elevation above the horizon (radians; negative at night): that of the drawn sun's
        direction, so the orbit's sliders (its height: the day length; its side: the noon elevation) set it."""
        s = self.state
        return math.atan2(self.sun_height(), math.hypot(math.cos(s.sun_angle), self.rules.sun.side))

    def sunshine(self) -> float:
        """How strongly the sun shines on the tree, 0 (night) to 1 (a clear sky's zenith sun): clear-sky PAR
        at the sun's elevation against the zenith's (engine/life/plant/solar.py), less the rules' shade."""
        return solar.strength(self.sun_elevation(), self.rules.sun) if self.sun_height() > 0 else 0.0

    def par(self) -> float:
        """The sun's PAR on a horizontal surface now (W/m²), shade removed."""
        return self.sunshine() * solar.full_par(self.rules.sun)

    def sun_direction(self) -> np.ndarray:
        """Unit vector from the tree towards the sun (for lighting, shadows and drawing the sun)."""
        s = self.state
        v = np.array([math.cos(s.sun_angle), self.sun_height(), self.rules.sun.side])
        return v / np.linalg.norm(v)

    def set_orbit_height(self, value: float) -> None:
        """Slider: height of the orbit centre, clamped to the rules' range (rules.clamp_orbit)."""
        self.state.orbit_height = clamp_orbit(self.rules.sun, value, self.state.sun_speed)[0]

    def set_sun_speed(self, value: float) -> None:
        """Slider: the sun's angular speed, clamped to the rules' range (rules.clamp_orbit)."""
        self.state.sun_speed = clamp_orbit(self.rules.sun, self.state.orbit_height, value)[1]

    def replant(self, rng: np.random.Generator) -> None:
        """The sapling button: a new tree; meters refilled to a random level in the rules' range."""
        r = self.rules.replant
        old = self.state
        self.state = SimState(
            sun_angle=old.sun_angle, orbit_height=old.orbit_height, sun_speed=old.sun_speed,
            sun_meter=float(rng.uniform(r.meter_min, r.meter_max)),
            water_meter=float(rng.uniform(r.meter_min, r.meter_max)),
            sun_turns=old.sun_turns, weather_seed=old.weather_seed,  # the calendar and weather go on
            daylight=self.rules.growth.daylight_full,
        )

    def remember_light(self, caught: float, seconds: float) -> None:
        """Fold ``seconds`` of the light the leaves caught (0..1: sugar fixed per m² of leaf against a fully
        lit, open leaf's; 0 at night) into the tree's remembered daylight (over ``daylight_memory``)."""
        if seconds > 0:
            weight = 1.0 - math.exp(-seconds / self.rules.growth.daylight_memory)
            s = self.state
            s.daylight = min(max(s.daylight + (caught - s.daylight) * weight, 0.0), 1.0)

    def light_growth(self) -> float:
        """How fast the light the leaves caught lets the shoots grow, x length_rate: in proportion to the
        remembered daylight (``daylight_full`` gives 1), at most ``daylight_most``."""
        g = self.rules.growth
        return min(self.state.daylight / g.daylight_full, g.daylight_most)

    def growth_speeds(self) -> tuple[float, float]:
        """(length clock, girth clock) speeds right now.

        The tamagotchi thesis (2.3.1-2.3.2): the tree can grow only once BOTH meters have been above half for
        20 s; a cycle that takes longer than 40 s earns less: the sun's the length growth, the water's the girth
        growth. So the clocks run at the rules' rate x what their meter earned (0 before both first earned) x
        health (1 - wilt) x the roots' health (an oxygen dose, :meth:`root_health`). The shoots grow as fast as
        the light their leaves caught lets them (:meth:`light_growth`: sugar earns the new internodes, and
        stomata closing in a drying soil fix less), the girth as water lets it (x the water meter's level).
        """
        s, g = self.state, self.rules.growth
        if not s.alive or s.sun_cycle.earned == 0 or s.water_cycle.earned == 0:
            return 0.0, 0.0
        gate = (1.0 - s.wilt) * seasons.growth_factor(s.sun_turns, self.rules) * self.root_health()
        return (g.length_rate * self.light_growth() * s.sun_cycle.rate * gate,
                g.girth_rate * s.water_meter * s.water_cycle.rate * gate)

    def root_health(self) -> float:
        """How well the roots take up water after the oxygen dose they took (0..1, smooth; soil.root_health)."""
        return soil.root_health(self.state.drowning, self.flood_tolerance, self.rules)

    def uptake(self) -> float:
        """How freely the roots take up water now (0..1): the stomata's opening at the soil's water times the
        roots' health."""
        return soil.opening(self.state.water_meter, self.rules) * self.root_health()

    def leaf_vigour(self) -> float:
        """How big new leaves grow and how well they stay (rules' leaf_min with no water, 1 when the
        water meter is above half)."""
        w = self.rules.water
        level = min(max(self.state.water_meter / self.rules.growth.threshold, 0.0), 1.0)
        return w.leaf_min + (1.0 - w.leaf_min) * level

    def drought(self) -> float:
        """0 with enough water, rising to 1 as the water meter empties below the drought level."""
        level = self.rules.water.drought_level
        return min(max((level - self.state.water_meter) / level, 0.0), 1.0) if level > 0 else 0.0

    def resources(self) -> float:
        """0..1: how well the tree is doing; decides how many dormant buds may wake: the sun's growth earned,
        the water the roots take up against their uptake at the growth threshold (at most 1; 0 before the water
        meter first earned growth) and health (1 - wilt)."""
        s = self.state
        full = soil.opening(self.rules.growth.threshold, self.rules)
        water = min(self.uptake() / full, 1.0) if s.water_cycle.earned > 0 else 0.0
        return s.sun_cycle.rate * water * (1.0 - s.wilt) if s.alive else 0.0

    def step(self, dt: float) -> None:
        """Advance the simulation by ``dt`` seconds of game time."""
        s, rules = self.state, self.rules
        s.time += dt
        s.sun_angle = (s.sun_angle + s.sun_speed * dt) % (2 * math.pi)
        s.sun_turns += s.sun_speed * dt / (2 * math.pi)
        shine = self.sunshine()
        if shine > 0:  # the meter shows the light the tree catches: a shaded crown fills it more slowly
            s.sun_meter += rules.sun.fill_rate * shine * self.leaf_light * dt
        else:
            s.sun_meter -= rules.sun.drain_rate * dt
        w = rules.water
        need = seasons.water_factor(s.sun_turns, rules)
        relief = 1.0 - rules.roots.drain_relief * self.root_share  # good roots take up water better
        # the roots take up what the stomata let go (less as the soil dries); above field capacity it drains
        s.water_meter -= ((w.drain_rate + w.sun_drain_rate * shine) * need * relief * self.uptake()
                          + soil.drainage(s.water_meter, rules)) * dt
        if s.watering:
            s.water_meter += w.fill_rate * dt
        if self.raining():
            s.water_meter += rules.weather.rain_fill * dt
        s.sun_meter = min(max(s.sun_meter, 0.0), 1.0)
        s.water_meter = min(max(s.water_meter, 0.0), 1.0)
        s.sun_cycle.update(s.sun_meter, dt, rules.growth)
        s.water_cycle.update(s.water_meter, dt, rules.growth)
        self._health(dt)
        length, girth = self.growth_speeds()
        s.length_time += length * dt
        s.girth_time += girth * dt
        if s.alive:
            r = rules.roots
            wet = min(max((s.water_meter - r.dry_level) / max(r.wet_level - r.dry_level, 1e-9), 0.0), 1.0)
            s.root_time += (rules.roots.growth_rate * wet * s.oxygen * self.root_health() * s.root_vigour
                            * seasons.growth_factor(s.sun_turns, rules) * dt)  # none in soil without oxygen

    def _health(self, dt: float) -> None:
        s, h = self.state, self.rules.health
        # waterlogged soil loses its oxygen and the roots take a dose of its want, healed while they have air;
        # resting roots (winter) take none; a dying tree needs a lasting recovery to live
        resting = seasons.growth_factor(s.sun_turns, self.rules) <= 0
        s.oxygen = soil.oxygen_after(s.oxygen, s.water_meter, dt, self.rules)
        s.drowning = soil.dose_after(s.drowning, s.oxygen, dt, self.rules, resting)
        starved = self.starving > self.rules.carbon.starve_time
        neglected = s.sun_meter < h.neglect_level or starved
        thirst = self.thirst()
        if not s.alive:
            return
        drowned = self.drowned()
        if neglected or drowned or thirst > 0:
            pressure = 1.0 if neglected else max(thirst, 1.0 / self.flood_tolerance if drowned else 0.0)
            s.wilt = min(1.0, s.wilt + h.wilt_rate * pressure * dt)
        else:
            s.wilt = max(0.0, s.wilt - h.recover_rate * dt)
        s.dead_for = s.dead_for + dt if s.wilt >= 1.0 else max(s.dead_for - dt, 0.0)
        if s.dead_for > h.death_time:
            s.alive = False

    def thirst(self) -> float:
        """How hard a dry soil wilts the tree (0..1): 0 with the water meter at the neglect level or above,
        rising in proportion as it empties below (1 when it is empty): wilting graded, no step."""
        level = self.rules.health.neglect_level
        return min(max((level - self.state.water_meter) / level, 0.0), 1.0) if level > 0 else 0.0

    def drowned(self) -> bool:
        """Whether the roots have drowned: their oxygen dose past drown_time x the species' flood tolerance
        (uptake halved; a tolerant species' roots bear more), so the tree wilts."""
        return self.state.drowning > self.rules.water.drown_time * self.flood_tolerance

    def settle_left(self) -> float:
        """Seconds until growth is earned if both meters stay above half: the longest of the two meters'
        hold times still to go (0 once both have earned growth). The HUD counts it down."""
        hold = self.rules.growth.hold_time
        left = [hold - c.above for c in (self.state.sun_cycle, self.state.water_cycle) if c.rate == 0]
        return max([0.0, *left])
