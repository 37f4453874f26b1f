"""The sun and water simulation of the tamagotchi game (seed 003, sections 2.3-2.4).

A sun orbits the tree on a vertical circle whose centre height and speed the player sets; the sun
meter fills while it shines and drains at night. The water meter drains (faster in strong sun) and
fills while the watering can is held. A meter earns growth only after staying above half for 20 s;
a cycle that takes longer than 40 s earns less, the longer the less. Sun sets the length-growth rate,
water the girth-growth rate. Neglect (or drowning) wilts the tree; long full wilt kills it.
All constants come from assets/rules.toml (see :func:`load_rules`).
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import asdict, dataclass, field, fields
from pathlib import Path

import numpy as np

from engine.base.config import fill_dataclass
from engine.base.errors import LSysError
from engine.life.light import LightRules


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
class Rules:
    """All game rules, one section per table of rules.toml."""

    growth: GrowthRules = field(default_factory=GrowthRules)
    sun: SunRules = field(default_factory=SunRules)
    water: WaterRules = field(default_factory=WaterRules)
    health: HealthRules = field(default_factory=HealthRules)
    replant: ReplantRules = field(default_factory=ReplantRules)
    light: LightRules = field(default_factory=LightRules)
    wind: WindRules = field(default_factory=WindRules)


def load_rules(path: str | Path) -> Rules:
    """Read rules.toml; unknown tables/keys or non-numbers are errors naming the file and key."""
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except tomllib.TOMLDecodeError as exc:
        raise LSysError(f"not valid TOML: {exc}", str(path)) from None
    rules = Rules()
    for table, values in data.items():
        if table not in {f.name for f in fields(Rules)} or not isinstance(values, dict):
            raise LSysError(f"unknown table [{table}]", str(path))
        fill_dataclass(getattr(rules, table), values, str(path), f"key in [{table}]")
    check_rules(rules, str(path))
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
    orbit_height: float = 0.35
    sun_speed: float = 0.05
    sun_meter: float = 0.6
    water_meter: float = 0.6
    watering: bool = False
    length_time: float = 0.0  # physiological time T: drives new internodes and elongation
    girth_time: float = 0.0  # girth time G: drives thickening
    wilt: float = 0.0
    drowning: float = 0.0
    dead_for: float = 0.0
    alive: bool = True
    sun_cycle: GrowthCycle = field(default_factory=GrowthCycle)
    water_cycle: GrowthCycle = field(default_factory=GrowthCycle)

    def to_dict(self) -> dict:
        """Plain data (numbers and booleans) for save files."""
        return asdict(self)

    @classmethod
    def from_dict(cls, data: dict) -> SimState:
        """Inverse of :meth:`to_dict`; raises ValueError on missing or mistyped fields."""
        values = dict(data)
        values["sun_cycle"] = GrowthCycle(**values.get("sun_cycle", {}))
        values["water_cycle"] = GrowthCycle(**values.get("water_cycle", {}))
        state = cls(**values)
        for f in fields(state):
            if f.name.endswith("_cycle"):
                continue
            value = getattr(state, f.name)
            if not isinstance(value, int | float) or not math.isfinite(float(value)):
                raise ValueError(f"{f.name} must be a finite number")
        return state


class Simulation:
    """Steps the meters, the growth clocks and the tree's health with a fixed time step."""

    def __init__(self, rules: Rules | None = None, state: SimState | None = None) -> None:
        self.rules = rules or Rules()
        if state is None:
            state = SimState(orbit_height=self.rules.sun.orbit_height, sun_speed=self.rules.sun.speed)
        self.state = state

    def sun_height(self) -> float:
        """Height of the sun above the horizon in orbit radii (negative at night)."""
        return self.state.orbit_height + math.sin(self.state.sun_angle)

    def sunshine(self) -> float:
        """How strongly the sun shines on the tree, 0 (night) to 1 (high noon)."""
        return min(max(self.sun_height(), 0.0), 1.0)

    def sun_direction(self) -> np.ndarray:
        """Unit vector from the tree towards the sun (for lighting, shadows and drawing the sun)."""
        s = self.state
        v = np.array([math.cos(s.sun_angle), self.sun_height(), self.rules.sun.side])
        return v / np.linalg.norm(v)

    def set_orbit_height(self, value: float) -> None:
        """Slider: height of the orbit centre, clamped to the rules' range."""
        r = self.rules.sun
        self.state.orbit_height = min(max(value, r.orbit_height_min), r.orbit_height_max)

    def set_sun_speed(self, value: float) -> None:
        """Slider: the sun's angular speed, clamped to the rules' range."""
        r = self.rules.sun
        self.state.sun_speed = min(max(value, r.speed_min), r.speed_max)

    def replant(self, rng: np.random.Generator) -> None:
        """The sapling button: a new tree; meters refilled to a random level in the rules' range."""
        r = self.rules.replant
        old = self.state
        self.state = SimState(
            sun_angle=old.sun_angle, orbit_height=old.orbit_height, sun_speed=old.sun_speed,
            sun_meter=float(rng.uniform(r.meter_min, r.meter_max)),
            water_meter=float(rng.uniform(r.meter_min, r.meter_max)),
        )

    def growth_speeds(self) -> tuple[float, float]:
        """(length clock, girth clock) speeds right now.

        Seed 003: the tree can grow only when BOTH meters have been above half for 20 s; a cycle that
        takes longer than 40 s earns less. So both clocks run at the rules' rate x what each meter earned
        (0 before its first 20 s above half, less after late cycles) x health (1 - wilt), and sun sets
        the length-growth rate (x the sun meter's level), water the girth-growth rate (x its level).
        """
        s, g = self.state, self.rules.growth
        if not s.alive:
            return 0.0, 0.0
        gate = s.sun_cycle.rate * s.water_cycle.rate * (1.0 - s.wilt)
        return g.length_rate * s.sun_meter * gate, g.girth_rate * s.water_meter * gate

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
        """0..1: how well the tree is doing; decides how many dormant buds may wake."""
        s = self.state
        return s.sun_cycle.rate * s.water_cycle.rate * (1.0 - s.wilt) if s.alive else 0.0

    def step(self, dt: float) -> None:
        """Advance the simulation by ``dt`` seconds of game time."""
        s, rules = self.state, self.rules
        s.time += dt
        s.sun_angle = (s.sun_angle + s.sun_speed * dt) % (2 * math.pi)
        shine = self.sunshine()
        if shine > 0:
            s.sun_meter += rules.sun.fill_rate * shine * dt
        else:
            s.sun_meter -= rules.sun.drain_rate * dt
        w = rules.water
        s.water_meter -= (w.drain_rate + w.sun_drain_rate * shine) * dt
        if s.watering:
            s.water_meter += w.fill_rate * dt
        s.sun_meter = min(max(s.sun_meter, 0.0), 1.0)
        s.water_meter = min(max(s.water_meter, 0.0), 1.0)
        s.sun_cycle.update(s.sun_meter, dt, rules.growth)
        s.water_cycle.update(s.water_meter, dt, rules.growth)
        self._health(dt)
        length, girth = self.growth_speeds()
        s.length_time += length * dt
        s.girth_time += girth * dt

    def _health(self, dt: float) -> None:
        s, h, w = self.state, self.rules.health, self.rules.water
        s.drowning = s.drowning + dt if s.water_meter > w.drown_level else 0.0
        neglected = min(s.sun_meter, s.water_meter) < h.neglect_level
        if not s.alive:
            return
        if neglected or s.drowning > w.drown_time:
            s.wilt = min(1.0, s.wilt + h.wilt_rate * dt)
        else:
            s.wilt = max(0.0, s.wilt - h.recover_rate * dt)
        s.dead_for = s.dead_for + dt if s.wilt >= 1.0 else 0.0
        if s.dead_for > h.death_time:
            s.alive = False

    def status(self) -> str:
        """A short word for the HUD that says what is true: dead, wilting, drowning, thirsty, needs_light,
        growing, resting (night) or starting (both meters fine; growth is earned after 20 s)."""
        s, threshold = self.state, self.rules.growth.threshold
        if not s.alive:
            return "dead"
        if s.wilt > 0.5:
            return "wilting"
        if s.drowning > self.rules.water.drown_time:
            return "drowning"
        if s.water_meter <= threshold:
            return "thirsty"
        if s.sun_meter <= threshold:
            return "needs_light"
        if self.growth_speeds()[0] > 0:
            return "growing" if self.sunshine() > 0 else "resting"
        return "starting"
