"""Reading sweep files (TOML) strictly: every problem is one error naming the file and the key.

Example (assets/experiments/sweep_sun_height.toml)::

    title = "How high the sun climbs"
    duration = 1800            # simulated seconds at the pace below
    sample_every = 60
    seeds = 20                 # seeds 1..20, or a list of seeds
    responses = ["height", "girth", "width", "leaves", "alive"]

    [base]                     # what every run shares: like a lab [[tree]] without a name
    watering = { below = 0.5, until = 0.7 }

    [[factor]]
    name = "Sun orbit height"
    key = "orbit_height"       # orbit_height, sun_speed, day_length, sun_elevation, latitude, day_of_year,
    levels = [-0.4, 0.0, 0.35, 0.7, 1.0]   # watering.every, watering.below, prune.every_days,
                                           # prune.keep_height, prune.lowest, species, or any "section.key"
                                           # of rules.toml
"""

from __future__ import annotations

import math
from pathlib import Path

from arbor.engine.base.errors import SweepError
from arbor.engine.base.reader import read_user_toml
from arbor.engine.life.experiment import schema
from arbor.engine.life.experiment.lab import (
    calendar,
    check_noon,
    check_species,
    pace_value,
    parse_regime,
    species_name,
)
from arbor.engine.life.experiment.schema import Reader
from arbor.engine.life.experiment.sweep import (
    MAX_FACTORS,
    MAX_LEVELS,
    MAX_RUNS,
    MAX_SEEDS,
    REGIME_KEYS,
    RESPONSES,
    STOP_COLUMNS,
    Factor,
    Stop,
    Sweep,
    cell,
)
from arbor.engine.life.rules.rules import Rules, set_rule

MAX_SAMPLES = 2000  # per run


def load_sweep(path: str | Path, lsystem_dir: Path) -> Sweep:
    """Read and check a sweep file against the schema (engine/life/experiment/schema.py); species must be
    .lsys files in ``lsystem_dir``. Every problem is one SweepError naming the key's line and column."""
    file = str(path)
    source, data = read_user_toml(path, SweepError)
    reader = Reader(file, source, SweepError)
    reader.table(data, schema.SWEEP, (), "the sweep")
    get = lambda key, default=None: reader.value(data, key, schema.SWEEP[key], (), default)  # noqa: E731
    varied = tuple(t["key"] for t in data.get("factor", []) if isinstance(t, dict) and isinstance(t.get("key"), str))
    # (only names: a table or list given as a key is reported by _factors at its line, not a TypeError here)
    base = parse_regime(reader, get("base", {}), ("base",), schema.BASE, factors=varied)
    reader.calendar = calendar(pace_value(reader, data), base)  # (days and years: at the base's sun speed)
    duration, every = get("duration"), get("sample_every", 60.0)
    if duration / every > MAX_SAMPLES:
        raise reader.fail(f"'sample_every' gives more than {MAX_SAMPLES} samples per run: take a larger one",
                          ("sample_every",))
    species = _species_file(reader, species_name(reader, data, "sweep"), lsystem_dir, ("species",))
    factors = _factors(reader, data, lsystem_dir)
    _check_place(reader, base, factors)
    for i, factor in enumerate(factors):
        if factor.key == "prune.every_days" and base.prune is None:
            raise reader.fail("a factor 'prune.every_days' needs what to cut: give [base] a prune = { keep_height = "
                              "2.5 } or { lowest = 0.25 }", ("factor", i, "key"))
    sweep = Sweep(title=str(get("title", path.stem)), factors=factors,
                  seeds=_seeds(reader, data.get("seeds", 10)), duration=duration, sample_every=every,
                  responses=_responses(reader, get("responses", list(RESPONSES))), base=base, species=species,
                  pace=pace_value(reader, data), seasons=get("seasons", True), file=file, source=source,
                  stop=_stop(reader, get("stop", {})) if "stop" in data else None)
    total = len(sweep.seeds) * math.prod(len(f.levels) for f in sweep.factors)
    if total > MAX_RUNS:
        raise reader.fail(f"{total} runs is more than {MAX_RUNS}: use fewer levels or seeds", ("seeds",))
    return sweep


def _factors(reader: Reader, data: dict, lsystem_dir: Path) -> list[Factor]:
    tables = reader.value(data, "factor", schema.SWEEP["factor"], (), [])
    if not 1 <= len(tables) <= MAX_FACTORS:
        raise reader.fail(f"a sweep needs 1 or {MAX_FACTORS} [[factor]] tables (it has {len(tables)})", ())
    factors = [_factor(reader, t, ("factor", i), lsystem_dir) for i, t in enumerate(tables)]
    for i, f in enumerate(factors):
        if f.key in [g.key for g in factors[:i]]:
            raise reader.fail(f"two factors vary {f.key!r}: vary it in one [[factor]] (give it every level)",
                              ("factor", i, "key"), value=True)
        where = ("factor", i, "name") if "name" in tables[i] else ("factor", i, "key")
        if f.name in [g.name for g in factors[:i]]:
            raise reader.fail(f"two factors are named {f.name!r}: give each factor a name of its own", where,
                              value=True)
        if f.name in {"run", "seed", "time_s", "response", *STOP_COLUMNS, *RESPONSES}:
            raise reader.fail(f"a factor cannot be named {f.name!r}: that is a column of the tables already (run, "
                              "seed, time_s, response, stop or a response's)", where, value=True)
    return factors


def _factor(reader: Reader, t, path: tuple, lsystem_dir: Path) -> Factor:
    reader.table(t, schema.FACTOR, path, f"[[factor]] #{path[1] + 1}")
    key = reader.value(t, "key", schema.FACTOR["key"], path)
    levels = reader.value(t, "levels", schema.FACTOR["levels"], path)
    where = (*path, "levels")
    if not 1 <= len(levels) <= MAX_LEVELS:
        raise reader.fail(f"'levels' must be a list of 1 to {MAX_LEVELS} values", where, value=True)
    if key == "species":
        levels = [_species_file(reader, v, lsystem_dir, where, k) for k, v in enumerate(levels)]
    elif key in REGIME_KEYS:
        levels = [reader.check(v, "levels", schema.FACTOR_KEYS[key], where, k) for k, v in enumerate(levels)]
    else:
        reader.rule(key, (*path, "key"), also=(*REGIME_KEYS, "species"), what="factor key", value=True)
        levels = [reader.check(v, "levels", schema.Key("number", "a level"), where, k) for k, v in enumerate(levels)]
        probe = Rules()
        for k, level in enumerate(levels):  # a known rule, every level in its range
            set_rule(probe, key, level, reader.file, SweepError, at=reader.locator.value(where, k))
    for k, level in enumerate(levels):
        if level in levels[:k]:
            raise reader.fail(f"'levels' must not repeat a value ({cell(level)} is there twice)", where, item=k)
    return Factor(str(t.get("name", key)), key, tuple(levels))


def _check_place(reader: Reader, base, factors: list[Factor]) -> None:
    """A place and date (latitude, day_of_year; each from [base] or a factor) set the sun alone, and every
    combination of their levels gives a noon sun no lower than Arbor's lowest."""
    keys = [f.key for f in factors]
    place = base.latitude is not None or base.day_of_year is not None or {"latitude", "day_of_year"} & set(keys)
    if not place:
        return
    for i, key in enumerate(keys):
        if key in ("orbit_height", "day_length", "sun_elevation"):
            raise reader.fail(f"a factor {key!r} with a place and date (latitude, day_of_year): vary 'latitude' "
                              "or 'day_of_year' instead", ("factor", i, "key"))
        other = {"latitude": "day_of_year", "day_of_year": "latitude"}.get(key)
        if other and other not in keys and getattr(base, other) is None:
            raise reader.fail(f"a factor {key!r} needs {other!r}: give it in [base] or vary it too",
                              ("factor", i, "key"))
    levels = {key: [getattr(base, key)] for key in ("latitude", "day_of_year")}
    where, varied = ("base", "latitude"), ""
    for i, f in enumerate(factors):
        if f.key in levels:
            levels[f.key], where, varied = list(f.levels), ("factor", i, "levels"), f.key
    for a, latitude in enumerate(levels["latitude"]):
        for b, day in enumerate(levels["day_of_year"]):
            check_noon(reader, latitude, day, where, {"latitude": a, "day_of_year": b}.get(varied))


def _species_file(reader: Reader, name, lsystem_dir: Path, path: tuple, item: int | None = None) -> str:
    if not isinstance(name, str) or not name.endswith(".lsys") or "/" in name or "\\" in name or name.startswith("."):
        raise reader.fail("a species is the file name of an .lsys in assets/lsystems, e.g. \"game_poplar.lsys\"",
                          path, value=True, item=item)
    check_species(reader, name, lsystem_dir, path, item)
    return name


def _stop(reader: Reader, table: dict) -> Stop:
    """The [stop] table: ``dies = true`` and/or a ``response`` with ``above`` or ``below``."""
    reader.table(table, schema.STOP, ("stop",), "[stop]")
    get = lambda key: reader.value(table, key, schema.STOP[key], ("stop",), None) if key in table else None  # noqa: E731
    stop = Stop(bool(get("dies")), get("response"), get("above"), get("below"))
    if stop.response is not None:
        reader.known(stop.response, list(RESPONSES), "response", ("stop", "response"),
                     f"choose from {', '.join(RESPONSES)}; docs/columns.md")
        if (stop.above is None) == (stop.below is None):
            raise reader.fail(f"[stop] response {stop.response!r} needs 'above' or 'below' (one of them): the value "
                              "that stops a run", ("stop", "response"))
    elif stop.above is not None or stop.below is not None:
        raise reader.fail("[stop] needs a 'response' for 'above' or 'below' to stop at, e.g. response = \"height\"",
                          ("stop", "above" if stop.above is not None else "below"))
    if not stop.dies and stop.response is None:
        raise reader.fail("[stop] stops nothing: give dies = true and/or a response with 'above' or 'below'",
                          ("stop",))
    return stop


def _seeds(reader: Reader, value) -> list[int]:
    seed = schema.Key("whole", "a seed", "", 0, schema.SEED_MAX)
    if isinstance(value, int) and not isinstance(value, bool):
        if not 1 <= value <= MAX_SEEDS:
            raise reader.fail(f"'seeds' must be 1 to {MAX_SEEDS} (how many) or a list of seeds", ("seeds",),
                              value=True)
        return list(range(1, value + 1))
    if not isinstance(value, list) or not 1 <= len(value) <= MAX_SEEDS:
        raise reader.fail(f"'seeds' must be a count or a list of 1 to {MAX_SEEDS} whole numbers from 0", ("seeds",),
                          value=True)
    seeds = [reader.check(s, "seeds", seed, ("seeds",), k) for k, s in enumerate(value)]
    for k, s in enumerate(seeds):
        if s in seeds[:k]:
            raise reader.fail(f"'seeds' must not repeat a seed ({s} is there twice)", ("seeds",), item=k)
    return seeds


def _responses(reader: Reader, value: list) -> tuple[str, ...]:
    for k, v in enumerate(value):
        reader.known(v, list(RESPONSES), "response", ("responses",),
                     f"choose from {', '.join(RESPONSES)}; docs/columns.md", item=k)
    if not value:
        raise reader.fail("'responses' must name at least one response", ("responses",))
    return tuple(dict.fromkeys(value))
