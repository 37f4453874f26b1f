"""The educators' lab: several trees from one seed, each under its own regime, grown in lock-step.

An experiment file (TOML, read strictly by engine/life/experiment/schema.py) names the trees and their
regimes: the sun (orbit height or day length in hours, noon elevation in degrees, or a place and date:
latitude and day of the year; speed), a watering
schedule (keep the water meter between two levels, water on a timetable, or never), a pruning
schedule (every so many game days: back to a height in metres, and/or the lowest share of the
branches cut) and rule overrides
(any number in rules.toml, e.g. ``"water.drain_rate" = 0.01``). Every tree starts from the same seed,
each with a lineage of its own; with ``spacing`` (metres) the trees stand in a row on one plot and
shade each other (competition). The run samples every ``sample_every`` seconds; meters and wilt are
the mean, minimum and maximum since the last sample (docs/columns.md lists every column and its unit).
Same file -> identical numbers (the worlds are deterministic).
"""

from __future__ import annotations

import copy
import csv
import difflib
import hashlib
import math
from dataclasses import dataclass, field, replace
from pathlib import Path

from arbor.engine.base.assets import assets_dir
from arbor.engine.base.errors import ExperimentError, LSysError
from arbor.engine.base.reader import read_user_toml
from arbor.engine.base.units import METRE
from arbor.engine.life.experiment import schema
from arbor.engine.life.experiment.measure import METRICS, Meters, crown_shape, measure
from arbor.engine.life.experiment.schema import Reader
from arbor.engine.life.lineage.lineage import new_lineage, species_of
from arbor.engine.life.rules.rules import Rules, check_rules, load_rules, set_rule
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.commands import Prune
from arbor.engine.life.world.world import World, step_together
from arbor.engine.lsystem.lsys import LSystem, load_lsystem

MAX_TREES = 6
__all__ = ["METRICS", "Experiment", "Lab", "Pruning", "Regime", "Watering", "crown_shape", "load_experiment", "measure",
           "save_stem"]


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
class Pruning:
    """A pruning schedule: every ``every_days`` game days, head the tree back to ``keep_height`` m and/or
    cut the ``lowest`` share of its trunk's branches (engine/life/world/prune.py)."""

    every_days: float = 7.0
    keep_height: float | None = None
    lowest: float = 0.0

    def apply(self, world: World) -> int:
        """Prune ``world`` now; the branches cut."""
        return world.apply(Prune(self.keep_height, self.lowest))


@dataclass
class Regime:
    """One tree's conditions."""

    name: str
    orbit_height: float | None = None  # orbit radii
    sun_speed: float | None = None  # rad per s
    day_length: float | None = None  # hours of daylight (sets the orbit height)
    sun_elevation: float | None = None  # degrees at noon (sets the rule sun.side)
    latitude: float | None = None  # degrees north: with day_of_year, sets the day length and the noon elevation
    day_of_year: int | None = None
    watering: Watering = field(default_factory=Watering)
    rules: dict[str, float | bool] = field(default_factory=dict)
    prune: Pruning | None = None  # (None: never pruned)


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
    pace: str = "demo"  # experiments keep the tamagotchi thesis's numbers unless they ask for another pace
    seasons: bool = True  # false: an endless summer, to study light or water alone
    spacing: float | None = None  # m between trees sharing one plot (None: each tree alone)
    notes: list[str] = field(default_factory=list)  # what the reader noticed (an old key name)


def load_experiment(path: str | Path, lsystem_dir: Path) -> Experiment:
    """Read and check an experiment file against the schema (engine/life/experiment/schema.py): every
    problem is one ExperimentError naming the file, the key's line and column, and the fix."""
    file = str(path)
    text, data = read_user_toml(path, ExperimentError)
    reader = Reader(file, text, ExperimentError)
    reader.table(data, schema.EXPERIMENT, (), "the experiment")
    trees = reader.value(data, "tree", schema.EXPERIMENT["tree"], (), [])
    if not 1 <= len(trees) <= MAX_TREES:
        raise reader.fail(f"an experiment needs 1 to {MAX_TREES} [[tree]] tables (it has {len(trees)})", ())
    regimes = [parse_regime(reader, t, ("tree", i), schema.TREE) for i, t in enumerate(trees)]
    names = [r.name for r in regimes]
    for i, name in enumerate(names):
        if name in names[:i]:
            raise reader.fail(f"two trees are named {name!r}: give each tree its own name", ("tree", i, "name"),
                              value=True)
    stems = [save_stem(name) for name in names]
    for i, stem in enumerate(stems):
        if stem in stems[:i]:
            raise reader.fail(f"trees {names[stems.index(stem)]!r} and {names[i]!r} would both be saved as "
                              f"{stem}.arbor: give each tree a name of its own", ("tree", i, "name"), value=True)
    spacing = reader.value(data, "spacing", schema.EXPERIMENT["spacing"], (), 0.0) or None
    if spacing is not None:
        check_shared_sun(reader, regimes, trees)
    get = lambda key, default: reader.value(data, key, schema.EXPERIMENT[key], (), default)  # noqa: E731
    pace = pace_value(reader, data)
    calendars = {calendar(pace, r) for r in regimes}
    reader.calendar = calendars.pop() if len(calendars) == 1 else None  # (trees with other days: s only)
    return Experiment(
        title=str(get("title", path.stem)), seed=get("seed", 0), duration=reader.value(
            data, "duration", schema.EXPERIMENT["duration"], ()), sample_every=get("sample_every", 30.0),
        regimes=regimes, lsystem=lsystem_dir / species_name(reader, data, "lab", lsystem_dir), file=file,
        pace=pace, seasons=get("seasons", True), spacing=spacing, notes=reader.notes)


def calendar(pace: str, regime: Regime) -> tuple[float, float] | None:
    """(s of game time a game day lasts, game days a year) for a tree of ``regime`` at ``pace``: what a
    file's "14 days" or "30 years" mean (None when rules.toml has no such pace or an override is out of
    range: their own errors say so)."""
    try:
        rules = load_rules(assets_dir() / "rules.toml", pace)
        for key, value in regime.rules.items():
            set_rule(rules, key, value, "rules")
    except LSysError:  # (an override out of range: the lab's own check names it at its line)
        return None
    speed = regime.sun_speed or rules.sun.speed
    return 2 * math.pi / speed, rules.seasons.year_days


def save_stem(name: str) -> str:
    """The file name (without .arbor) a lab tree is saved under: its name's letters and digits in lower case,
    anything else an underscore ('Full sun' -> full_sun)."""
    return "".join(c if c.isalnum() else "_" for c in name).strip("_").lower() or "tree"


def species_name(reader: Reader, data: dict, kind: str, lsystem_dir: Path | None = None) -> str:
    """The species file name (key ``species``; a lab's old ``lsystem`` is read with a note), checked (and,
    given ``lsystem_dir``, a file there)."""
    key = "species"
    if kind == "lab" and "lsystem" in data:
        if "species" in data:
            raise reader.fail("give 'species' only ('lsystem' is its old name)", ("lsystem",))
        key = "lsystem"
        reader.notes.append(f"{reader.file}:{':'.join(map(str, reader.locator.find(('lsystem',))))}: note: "
                            "'lsystem' is now called 'species' (read as species)")
    name = reader.value(data, key, schema.COMMON["species"], (), "game_tree.lsys")
    if not name.endswith(".lsys") or "/" in name or "\\" in name or name.startswith("."):
        raise reader.fail(f"'{key}' must be a file name in assets/lsystems, e.g. \"game_poplar.lsys\"", (key,),
                          value=True)
    if lsystem_dir is not None:
        check_species(reader, name, lsystem_dir, (key,))
    return name


def check_species(reader: Reader, name: str, lsystem_dir: Path, path: tuple, item: int | None = None) -> None:
    """``name`` is an .lsys file in ``lsystem_dir``; else an error at the value naming the ones there are."""
    if (lsystem_dir / name).is_file():
        return
    there = sorted(p.name for p in lsystem_dir.glob("*.lsys"))
    close = difflib.get_close_matches(name, there, n=1, cutoff=0.75)
    fix = f"did you mean {close[0]!r}? " if close else ""
    raise reader.fail(f"no species {name!r} in assets/lsystems ({fix}the species are: {', '.join(there)})", path,
                      value=True, item=item)


def pace_value(reader: Reader, data: dict) -> str:
    """The pace a file asks for (default demo)."""
    pace = reader.value(data, "pace", schema.COMMON["pace"], (), "demo")
    if not pace.isidentifier():
        raise reader.fail("'pace' must be the name of a pace in rules.toml (demo or home)", ("pace",), value=True)
    return pace


def check_shared_sun(reader: Reader, regimes: list[Regime], tables: list[dict]) -> None:
    """Trees on one plot share one sun: their sun keys must agree."""
    keys = tuple(schema.SUN)
    first = [getattr(regimes[0], k) for k in keys]
    for i, regime in enumerate(regimes[1:], 1):
        for key, want in zip(keys, first, strict=True):
            if getattr(regime, key) != want:
                raise reader.fail(f"trees on one plot (spacing) share the sun: give every tree the same {key!r}",
                                  ("tree", i, key) if key in tables[i] else ("tree", i))


def parse_watering(reader: Reader, water, path: tuple) -> Watering:
    """A watering schedule: "never", keep the meter between ``below`` and ``until``, or a timetable."""
    if water == "never":
        return Watering()
    if not isinstance(water, dict):
        raise reader.fail("'watering' is \"never\" or a table like { below = 0.5, until = 0.7 }", path)
    reader.table(water, schema.WATERING, path, "'watering'")
    get = lambda key, default: reader.value(water, key, schema.WATERING[key], path, default)  # noqa: E731
    watering = Watering(below=get("below", -1.0), until=get("until", 0.7), every=get("every", 0.0) or None,
                        seconds=get("seconds", 5.0))
    watering.below = None if "below" not in water else watering.below
    if watering.below is not None and watering.every is not None:
        raise reader.fail("give 'below' (keep the meter up) or 'every' (a timetable), not both", (*path, "every"))
    if watering.below is not None and not watering.below < watering.until:
        raise reader.fail(f"'below' ({watering.below:g}) must be under 'until' ({watering.until:g}): watering "
                          "starts below one and stops at the other", (*path, "below"), value=True)
    if watering.every is not None and watering.seconds >= watering.every:
        raise reader.fail(f"'seconds' ({watering.seconds:g}) must be shorter than 'every' ({watering.every:g})",
                          (*path, "seconds"), value=True)
    return watering


def parse_pruning(reader: Reader, prune, path: tuple) -> Pruning | None:
    """A pruning schedule: { every_days = 7, keep_height = 2.5 } and/or lowest = a share of the branches."""
    if prune is None:
        return None
    reader.table(prune, schema.PRUNE, path, "'prune'")
    get = lambda key, default: reader.value(prune, key, schema.PRUNE[key], path, default)  # noqa: E731
    pruning = Pruning(get("every_days", 7.0), get("keep_height", 0.0) or None, get("lowest", 0.0))
    if pruning.keep_height is None and not pruning.lowest > 0:
        raise reader.fail("'prune' cuts nothing: give 'keep_height' (m) and/or 'lowest' (a share above 0)", path)
    return pruning


def parse_regime(reader: Reader, t, path: tuple, keys: dict, factors: tuple[str, ...] = ()) -> Regime:
    """One tree's regime from its table (sun, watering, rule overrides), checked against ``keys``; a sweep's
    base gives its ``factors`` (their keys), which may complete a place and date."""
    reader.table(t, keys, path, f"[[{path[0]}]] #{path[1] + 1}" if len(path) > 1 else f"[{path[0]}]")
    name = reader.value(t, "name", schema.TREE["name"], path) if "name" in keys else "base"
    if not name.strip():
        raise reader.fail("a tree's 'name' must not be empty", (*path, "name"), value=True)
    watering = parse_watering(reader, t.get("watering", "never"), (*path, "watering"))
    rules = reader.value(t, "rules", schema.TREE["rules"], path, {})
    probe = Rules()
    for key, value in rules.items():  # a known rule, within its range
        reader.rule(key, (*path, "rules", key))
        set_rule(probe, key, value, reader.file, reader.error, at=reader.locator.value((*path, "rules", key)))
    sun = {key: reader.value(t, key, schema.SUN[key], path, 0.0) if key in t else None for key in schema.SUN}
    if sun["orbit_height"] is not None and sun["day_length"] is not None:
        raise reader.fail("give 'orbit_height' or 'day_length', not both (the day length sets the orbit's height)",
                          (*path, "day_length"))
    if sun["sun_elevation"] is not None and "sun.side" in rules:
        raise reader.fail("give 'sun_elevation' or the rule \"sun.side\", not both", (*path, "sun_elevation"))
    place = [key for key in ("latitude", "day_of_year") if sun[key] is not None]
    if place or {"latitude", "day_of_year"} & set(factors):
        check_place(reader, sun, path, place, rules, factors)
    prune = parse_pruning(reader, reader.value(t, "prune", schema.TREE["prune"], path) if "prune" in t else None,
                          (*path, "prune"))
    return Regime(name=name, watering=watering, rules=dict(rules), prune=prune, **sun)


def check_place(reader: Reader, sun: dict, path: tuple, given: list[str], rules: dict,
                factors: tuple[str, ...] = ()) -> None:
    """A place and date (latitude, day_of_year) come together (one of them may be a sweep's factor), set the
    sun alone, and give a noon sun no lower than Arbor's lowest."""
    if len(given) == 1 and ("day_of_year" if given[0] == "latitude" else "latitude") not in factors:
        other = "day_of_year" if given[0] == "latitude" else "latitude"
        raise reader.fail(f"give '{other}' with '{given[0]}' (a place and a date set the sun together)",
                          (*path, given[0]))
    for key in ("orbit_height", "day_length", "sun_elevation"):
        if sun[key] is not None:
            raise reader.fail(f"give 'latitude' and 'day_of_year' or {key!r}, not both (the place and date set "
                              "the day length and the noon sun)", (*path, key))
    if "sun.side" in rules:
        raise reader.fail("give 'latitude' or the rule \"sun.side\", not both", (*path, "rules", "sun.side"))
    if sun["latitude"] is not None and sun["day_of_year"] is not None:  # (a sweep checks its levels itself)
        check_noon(reader, sun["latitude"], sun["day_of_year"], (*path, "latitude"))


def check_noon(reader: Reader, latitude: float, day_of_year: float, path: tuple, item: int | None = None) -> None:
    """The noon sun at this place and date stands at least schema.LOWEST_SUN degrees high (an error at the
    value of ``path``, its ``item``-th element for a list of levels)."""
    _, noon = schema.latitude_sun(latitude, day_of_year)
    if noon < schema.LOWEST_SUN:
        raise reader.fail(f"at latitude {latitude:g} on day {day_of_year:g} the noon sun stands {noon:.1f} degrees "
                          f"high, below Arbor's lowest ({schema.LOWEST_SUN:g}): choose a date nearer midsummer or a "
                          "latitude nearer the equator", path, value=True, item=item)


def sun_of(regime: Regime) -> tuple[float | None, float | None]:
    """The regime's (day length in hours, noon elevation in degrees): its own, or its place and date's."""
    if regime.latitude is not None and regime.day_of_year is not None:
        return schema.latitude_sun(regime.latitude, regime.day_of_year)
    return regime.day_length, regime.sun_elevation


def regime_rules(base: Rules, regime: Regime, file: str = "<experiment>") -> Rules:
    """The base rules with the regime's overrides, each within its range and the sliders' ranges the right
    way round (an override is at the pace's own scale, like a pace's overrides in rules.toml); a problem
    names the experiment ``file`` and the tree."""
    rules = copy.deepcopy(base)
    try:
        for key, value in regime.rules.items():
            set_rule(rules, key, value, file, ExperimentError)
        elevation = sun_of(regime)[1]
        if elevation is not None:
            rules.sun.side = schema.elevation_side(elevation, orbit_height(regime, rules))
        check_rules(rules, file, ExperimentError)
    except ExperimentError as err:
        raise ExperimentError(f"tree {regime.name!r}: {err.message}", err.file, err.line, err.col) from None
    return rules


def orbit_height(regime: Regime, rules: Rules) -> float:
    """The orbit height a regime asks for: its own, the one its day length (or place and date) gives, or the
    rules'."""
    if regime.orbit_height is not None:
        return regime.orbit_height
    hours = sun_of(regime)[0]
    if hours is not None:
        return schema.day_length_height(hours)
    return rules.sun.orbit_height


@dataclass
class Series:
    """One tree's sampled time series (``day``: game days, turns of the sun, at each sample)."""

    name: str
    time: list[float] = field(default_factory=list)
    day: list[float] = field(default_factory=list)
    values: dict[str, list[float]] = field(default_factory=lambda: {m: [] for m in METRICS})


class Lab:
    """Runs the trees of an experiment in lock-step and records their time series."""

    def __init__(self, experiment: Experiment, base_rules: Rules, system: LSystem | None = None) -> None:
        self.experiment = experiment
        base_rules = copy.deepcopy(base_rules)
        base_rules.seasons.enabled = experiment.seasons
        self.system = system or load_lsystem(experiment.lsystem)
        self.worlds = [self._world(i, regime, base_rules) for i, regime in enumerate(experiment.regimes)]
        self.meters = [Meters() for _ in self.worlds]
        self.series = [Series(r.name) for r in experiment.regimes]
        self.time = 0.0
        self._next_sample = 0.0
        self._next_prune = [r.prune.every_days if r.prune else math.inf for r in experiment.regimes]

    def _world(self, index: int, regime: Regime, base_rules: Rules) -> World:
        """One tree's world: its rules, its sun, its own lineage and (on a shared plot) its place in the row."""
        rules = regime_rules(base_rules, regime, str(self.experiment.file))
        seed = self.experiment.seed
        lineage = new_lineage(seed, 0.0, species_of(self.system.file))
        ident = hashlib.sha256(f"{lineage.id}|lab|{index}|{regime.name}".encode()).hexdigest()[:16]
        position = (0.0, 0.0)
        if self.experiment.spacing:
            n = len(self.experiment.regimes)
            position = ((index - (n - 1) / 2) * self.experiment.spacing * METRE, 0.0)
        world = World(self.system, rules, seed=seed, position=position,
                      lineage=replace(lineage, id=ident))  # every tree a line of its own
        if regime.orbit_height is not None or sun_of(regime)[0] is not None:
            world.apply(Action.ORBIT_HEIGHT, orbit_height(regime, rules))
        if regime.sun_speed is not None:
            world.apply(Action.SUN_SPEED, regime.sun_speed)
        return world

    def step(self) -> None:
        """Advance every tree by one time step, watering each by its schedule; sample when due. Trees on
        one plot read the light together (each shades the others)."""
        dt = self.experiment.dt
        if self.time >= self._next_sample - 1e-9:
            self.sample()
            self._next_sample += self.experiment.sample_every
        for i, (world, regime) in enumerate(zip(self.worlds, self.experiment.regimes, strict=True)):
            s = world.sim.state
            wanted = regime.watering.wants_water(s.time, s.water_meter, s.watering)
            if wanted != s.watering:
                world.apply(Action.WATER, float(wanted))
            if s.sun_turns >= self._next_prune[i] and regime.prune is not None:
                regime.prune.apply(world)
                self._next_prune[i] += regime.prune.every_days
        plots = [self.worlds] if self.experiment.spacing else [[world] for world in self.worlds]
        for plot in plots:  # (trees on one plot read the light together)
            step_together(plot, dt)
        for world, meters in zip(self.worlds, self.meters, strict=True):
            meters.add(world, dt)
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
        """Record every tree's measurements now (meters and wilt: since the last sample)."""
        for world, series, meters in zip(self.worlds, self.series, self.meters, strict=True):
            series.time.append(self.time)
            series.day.append(world.sim.state.sun_turns)
            for key, value in measure(world, meters).items():
                series.values[key].append(value)
            meters.reset()

    def write_csv(self, path: str | Path) -> None:
        """The time series of every tree as one CSV table (long format: one row per tree and time)."""
        with open(path, "w", newline="", encoding="utf-8") as fh:
            writer = csv.writer(fh)
            writer.writerow(["time_s", "day", "tree", *METRICS])
            for series in self.series:
                for i, t in enumerate(series.time):
                    writer.writerow([f"{t:g}", f"{series.day[i]:.4g}", series.name,
                                     *(f"{series.values[m][i]:.6g}" for m in METRICS)])
