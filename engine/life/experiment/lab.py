"""The educators' lab: several trees from one seed, each under its own regime, grown in lock-step.

An experiment file (TOML) names the trees and their regimes: sun orbit height and speed, a watering
schedule (keep the water meter between two levels, water on a timetable, or never) and rule
overrides (any number in rules.toml, e.g. ``"water.drain_rate" = 0.01``). Every tree starts from the
same seed; the run samples height, trunk girth, module and leaf counts and both meters at fixed
intervals. Same file -> identical numbers (the worlds are deterministic).
"""

from __future__ import annotations

import copy
import csv
import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from arbor.engine.base.errors import ExperimentError
from arbor.engine.life.rules.rules import Rules, check_rules, set_rule
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import LSystem, load_lsystem

METRICS = ("height", "width", "offset", "girth", "modules", "leaves", "density", "shed", "roots", "sun", "water",
           "wilt", "alive", "fruit")
MAX_TREES = 6


@dataclass
class Watering:
    """Keep water between ``below`` (start) and ``until`` (stop); or on a timetable; or never."""

    below: float | None = None
    until: float = 0.7
    every: float | None = None  # seconds between waterings on a timetable
    seconds: float = 5.0  # how long each timetable watering lasts

    def wants_water(self, time: float, meter: float, watering: bool) -> bool:
        """Whether the can is held at ``time`` given the meter and whether it is held now."""
        if self.every:
            return (time % self.every) < self.seconds
        if self.below is None:
            return False
        return meter < self.until if watering else meter < self.below


@dataclass
class Regime:
    """One tree's conditions."""

    name: str
    orbit_height: float | None = None
    sun_speed: float | None = None
    watering: Watering = field(default_factory=Watering)
    rules: dict[str, float | bool] = field(default_factory=dict)


@dataclass
class Experiment:
    """A whole lab experiment."""

    title: str
    seed: int
    duration: float
    sample_every: float
    regimes: list[Regime]
    lsystem: Path
    dt: float = 0.5
    file: str = "<experiment>"
    pace: str = "demo"  # experiments keep seed 003's numbers unless they ask for another pace
    seasons: bool = True  # false: an endless summer, to study light or water alone


def number_value(data: dict, key: str, file: str, default=None, positive: bool = False) -> float:
    """``data[key]`` as a finite number (``default`` when missing); an error naming the key otherwise."""
    value = data.get(key, default)
    if value is None or isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise ExperimentError(f"'{key}' must be a number", file)
    if positive and value <= 0:
        raise ExperimentError(f"'{key}' must be above 0", file)
    return float(value)


def load_experiment(path: str | Path, lsystem_dir: Path) -> Experiment:
    """Read and check an experiment file; problems are errors naming the file and the key."""
    path = Path(path)
    file = str(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError) as exc:
        raise ExperimentError(f"cannot read: {exc}", file) from None
    except tomllib.TOMLDecodeError as exc:
        raise ExperimentError(f"not valid TOML: {exc}", file) from None
    trees = data.get("tree", [])
    if not isinstance(trees, list) or not 1 <= len(trees) <= MAX_TREES:
        raise ExperimentError(f"an experiment needs 1 to {MAX_TREES} [[tree]] tables", file)
    regimes = [parse_regime(t, i, file) for i, t in enumerate(trees)]
    duration = number_value(data, "duration", file, positive=True)
    if duration > 7 * 24 * 3600:
        raise ExperimentError("'duration' is at most a week of game time", file)
    lsys_name = str(data.get("lsystem", "game_tree.lsys"))
    if "/" in lsys_name or "\\" in lsys_name or lsys_name.startswith("."):
        raise ExperimentError("'lsystem' must be a file name in assets/lsystems", file)
    return Experiment(
        title=str(data.get("title", path.stem)),
        seed=int(number_value(data, "seed", file, 0)),
        duration=duration,
        sample_every=number_value(data, "sample_every", file, 30.0, positive=True),
        regimes=regimes,
        lsystem=lsystem_dir / lsys_name,
        file=file,
        pace=pace_value(data, file),
        seasons=flag_value(data, "seasons", file),
    )


def flag_value(data: dict, key: str, file: str) -> bool:
    """``data[key]`` as true or false (true when missing)."""
    value = data.get(key, True)
    if not isinstance(value, bool):
        raise ExperimentError(f"'{key}' must be true or false", file)
    return value


def pace_value(data: dict, file: str) -> str:
    """The pace a file asks for (default demo)."""
    pace = data.get("pace", "demo")
    if not isinstance(pace, str) or not pace.isidentifier():
        raise ExperimentError("'pace' must be the name of a pace in rules.toml (demo or home)", file)
    return pace


def parse_regime(t: dict, i: int, file: str) -> Regime:
    """One tree's regime from its table (sun, watering, rule overrides), checked."""
    where = f"{file} [[tree]] #{i + 1}"
    if not isinstance(t, dict) or "name" not in t:
        raise ExperimentError("every [[tree]] needs a name", where)
    water = t.get("watering", "never")
    if water == "never":
        watering = Watering()
    elif isinstance(water, dict):
        watering = Watering(
            below=number_value(water, "below", where) if "below" in water else None,
            until=number_value(water, "until", where, 0.7),
            every=number_value(water, "every", where, positive=True) if "every" in water else None,
            seconds=number_value(water, "seconds", where, 5.0, positive=True),
        )
    else:
        raise ExperimentError("'watering' is \"never\" or a table like { below = 0.5, until = 0.7 }", where)
    rules = t.get("rules", {})
    if not isinstance(rules, dict):
        raise ExperimentError("'rules' must be a table of \"section.key\" = number", where)
    probe = Rules()
    for key, value in rules.items():
        set_rule(probe, key, value, where, ExperimentError)  # a known rule, within its range
    return Regime(
        name=str(t["name"]),
        orbit_height=number_value(t, "orbit_height", where) if "orbit_height" in t else None,
        sun_speed=number_value(t, "sun_speed", where, positive=True) if "sun_speed" in t else None,
        watering=watering,
        rules=dict(rules),
    )


def regime_rules(base: Rules, regime: Regime) -> Rules:
    """The base rules with the regime's overrides, each within its range and the sliders' ranges the right
    way round (an override is at the pace's own scale, like a pace's overrides in rules.toml)."""
    rules = copy.deepcopy(base)
    for key, value in regime.rules.items():
        set_rule(rules, key, value, regime.name, ExperimentError)
    check_rules(rules, regime.name, ExperimentError)
    return rules


@dataclass
class Series:
    """One tree's sampled time series."""

    name: str
    time: list[float] = field(default_factory=list)
    values: dict[str, list[float]] = field(default_factory=lambda: {m: [] for m in METRICS})


class Lab:
    """Runs the trees of an experiment in lock-step and records their time series."""

    def __init__(self, experiment: Experiment, base_rules: Rules, system: LSystem | None = None) -> None:
        self.experiment = experiment
        base_rules = copy.deepcopy(base_rules)
        base_rules.seasons.enabled = experiment.seasons
        self.system = system or load_lsystem(experiment.lsystem)
        self.worlds: list[World] = []
        for regime in experiment.regimes:
            world = World(self.system, regime_rules(base_rules, regime), seed=experiment.seed)
            if regime.orbit_height is not None:
                world.apply(Action.ORBIT_HEIGHT, regime.orbit_height)
            if regime.sun_speed is not None:
                world.apply(Action.SUN_SPEED, regime.sun_speed)
            self.worlds.append(world)
        self.series = [Series(r.name) for r in experiment.regimes]
        self.time = 0.0
        self._next_sample = 0.0

    def step(self) -> None:
        """Advance every tree by one time step, watering each by its schedule; sample when due."""
        dt = self.experiment.dt
        if self.time >= self._next_sample - 1e-9:
            self.sample()
            self._next_sample += self.experiment.sample_every
        for world, regime in zip(self.worlds, self.experiment.regimes, strict=True):
            s = world.sim.state
            wanted = regime.watering.wants_water(s.time, s.water_meter, s.watering)
            if wanted != s.watering:
                world.apply(Action.WATER, float(wanted))
            world.step(dt)
        self.time += dt

    def run(self, until: float | None = None) -> None:
        """Step until ``until`` (default: the experiment's duration), then take a last sample."""
        end = self.experiment.duration if until is None else until
        while self.time < end - 1e-9:
            self.step()
        if self.time >= self._next_sample - 1e-9:
            self.sample()
            self._next_sample += self.experiment.sample_every

    def sample(self) -> None:
        """Record every tree's measurements now."""
        for world, series in zip(self.worlds, self.series, strict=True):
            series.time.append(self.time)
            for key, value in measure(world).items():
                series.values[key].append(value)

    def write_csv(self, path: str | Path) -> None:
        """The time series of every tree as one CSV table (long format: one row per tree and time)."""
        with open(path, "w", newline="", encoding="utf-8") as fh:
            writer = csv.writer(fh)
            writer.writerow(["time_s", "tree", *METRICS])
            for series in self.series:
                for i, t in enumerate(series.time):
                    writer.writerow([f"{t:g}", series.name, *(f"{series.values[m][i]:.6g}" for m in METRICS)])


def measure(world: World) -> dict[str, float]:
    """Height, crown width, crown offset toward the sun's side, trunk girth (diameter at the base),
    modules, leaf clusters on the tree and per unit of the crown's box (each side at least 0.5),
    branches shed, root length, meters, wilt, alive (1 or 0) and fruit."""
    geometry = world.tree.geometry(world.clocks())
    segs, leaves = geometry.turtle.segments, geometry.turtle.leaves
    shape = crown_shape(segs, leaves)
    girth = float(2 * segs.radius[0]) if len(segs) else 0.0
    big = leaves.size > 0.05 * leaves.size.max() if len(leaves) else np.zeros(0, bool)
    on_tree = len(np.unique(leaves.module[big]))
    box = np.ptp(leaves.position[big], axis=0) if big.any() else np.zeros(3)
    density = on_tree / float(np.prod(np.maximum(box, 0.5)))  # leaf clusters per unit of crown box
    side = np.array([0.0, 0.0, 1.0]) if world.rules.sun.side >= 0 else np.array([0.0, 0.0, -1.0])
    s = world.sim.state
    return {"height": shape["height"], "width": shape["width"], "offset": float(shape["centroid"] @ side),
            "girth": girth, "modules": float(len(world.tree.lstring)), "leaves": float(on_tree), "density": density,
            "shed": float(world.tree.shed_total), "roots": world.roots.length(), "sun": s.sun_meter,
            "water": s.water_meter, "wilt": s.wilt, "alive": float(s.alive),
            "fruit": float(world.tree.lstring.count("O"))}


def crown_shape(segs, leaves) -> dict:
    """Height (top of the wood), crown width (largest horizontal extent of the leaves) and the leaves'
    centroid relative to the trunk's base (x, 0, z)."""
    height = float(segs.end[:, 1].max()) if len(segs) else 0.0
    if len(leaves) == 0:
        return {"height": height, "width": 0.0, "centroid": np.zeros(3)}
    base = segs.start[0] if len(segs) else np.zeros(3)
    flat = leaves.position[:, [0, 2]]
    width = float(np.ptp(flat, axis=0).max())
    centroid = leaves.position.mean(axis=0) - base
    centroid[1] = 0.0
    return {"height": height, "width": width, "centroid": centroid}
