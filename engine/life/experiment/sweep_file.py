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
    key = "orbit_height"       # orbit_height, sun_speed, watering.every, watering.below, species,
    levels = [-0.4, 0.0, 0.35, 0.7, 1.0]   # or any "section.key" of rules.toml
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

from arbor.engine.base.errors import ExperimentError, SweepError
from arbor.engine.life.experiment.lab import flag_value, number_value, pace_value, parse_regime
from arbor.engine.life.experiment.sweep import (
    MAX_FACTORS,
    MAX_LEVELS,
    MAX_RUNS,
    MAX_SEEDS,
    REGIME_KEYS,
    RESPONSES,
    Factor,
    Sweep,
)
from arbor.engine.life.rules.rules import Rules, set_rule

MAX_SAMPLES = 2000  # per run
WEEK = 7 * 24 * 3600.0


def load_sweep(path: str | Path, lsystem_dir: Path) -> Sweep:
    """Read and check a sweep file; species must be .lsys files in ``lsystem_dir``. Every problem is a
    SweepError (also those found by the lab's readers of the parts a sweep shares with an experiment)."""
    try:
        return _load_sweep(Path(path), lsystem_dir)
    except ExperimentError as exc:
        raise SweepError(exc.message, exc.file, exc.line, exc.col) from None


def _load_sweep(path: Path, lsystem_dir: Path) -> Sweep:
    file = str(path)
    try:
        source = path.read_text(encoding="utf-8")
        data = tomllib.loads(source)
    except (OSError, UnicodeDecodeError) as exc:
        raise SweepError(f"cannot read: {exc}", file) from None
    except tomllib.TOMLDecodeError as exc:
        raise SweepError(f"not valid TOML: {exc}", file) from None
    duration = number_value(data, "duration", file, positive=True)
    if duration > WEEK:
        raise SweepError("'duration' is at most a week of game time", file)
    every = number_value(data, "sample_every", file, 60.0, positive=True)
    if duration / every > MAX_SAMPLES:
        raise SweepError(f"'sample_every' gives more than {MAX_SAMPLES} samples per run: take a larger one", file)
    base = data.get("base", {})
    if not isinstance(base, dict):
        raise SweepError("[base] must be a table (watering, orbit_height, sun_speed, rules)", file)
    species = _species(data.get("species", "game_tree.lsys"), lsystem_dir, f"{file} species")
    sweep = Sweep(title=str(data.get("title", path.stem)), factors=_factors(data, lsystem_dir, file),
                  seeds=_seeds(data.get("seeds", 10), file), duration=duration, sample_every=every,
                  responses=_responses(data.get("responses", list(RESPONSES)), file),
                  base=parse_regime({"name": "base", **base}, 0, f"{file} [base]"), species=species,
                  pace=pace_value(data, file), seasons=flag_value(data, "seasons", file), file=file, source=source)
    total = len(sweep.seeds) * math.prod(len(f.levels) for f in sweep.factors)
    if total > MAX_RUNS:
        raise SweepError(f"{total} runs is more than {MAX_RUNS}: use fewer levels or seeds", file)
    return sweep


def _factors(data: dict, lsystem_dir: Path, file: str) -> list[Factor]:
    tables = data.get("factor", [])
    if not isinstance(tables, list) or not 1 <= len(tables) <= MAX_FACTORS:
        raise SweepError(f"a sweep needs 1 or {MAX_FACTORS} [[factor]] tables", file)
    factors = []
    for i, t in enumerate(tables):
        where = f"{file} [[factor]] #{i + 1}"
        if not isinstance(t, dict) or not isinstance(t.get("key"), str):
            raise SweepError("every [[factor]] needs a key (what it varies)", where)
        key, levels = t["key"], t.get("levels")
        if not isinstance(levels, list) or not 1 <= len(levels) <= MAX_LEVELS:
            raise SweepError(f"'levels' must be a list of 1 to {MAX_LEVELS} values", where)
        if key == "species":
            levels = [_species(v, lsystem_dir, where) for v in levels]
        else:
            levels = [number_value({"levels": v}, "levels", where) for v in levels]
            if key not in REGIME_KEYS:
                probe = Rules()
                for level in levels:
                    set_rule(probe, key, level, where, SweepError)  # a known rule, every level in its range
        if len(set(levels)) != len(levels):
            raise SweepError("'levels' must not repeat a value", where)
        factors.append(Factor(str(t.get("name", key)), key, tuple(levels)))
    if len({f.key for f in factors}) != len(factors):
        raise SweepError("two factors vary the same thing", file)
    names = [f.name for f in factors]
    if len(set(names)) != len(names) or set(names) & {"run", "seed", "time_s", "response", *RESPONSES}:
        raise SweepError("each factor needs its own name (not run, seed, time_s, response or a response's)", file)
    return factors


def _species(name, lsystem_dir: Path, where: str) -> str:
    if not isinstance(name, str) or not name.endswith(".lsys") or "/" in name or "\\" in name or name.startswith("."):
        raise SweepError("a species is the file name of an .lsys in assets/lsystems, e.g. \"game_poplar.lsys\"", where)
    if not (lsystem_dir / name).is_file():
        raise SweepError(f"no species {name!r} in assets/lsystems", where)
    return name


def _seeds(value, file: str) -> list[int]:
    if isinstance(value, int) and not isinstance(value, bool):
        if not 1 <= value <= MAX_SEEDS:
            raise SweepError(f"'seeds' must be 1 to {MAX_SEEDS} (how many) or a list of seeds", file)
        return list(range(1, value + 1))
    if (not isinstance(value, list) or not 1 <= len(value) <= MAX_SEEDS
            or not all(isinstance(s, int) and not isinstance(s, bool) and 0 <= s < 2**32 for s in value)):
        raise SweepError(f"'seeds' must be a count or a list of 1 to {MAX_SEEDS} whole numbers from 0", file)
    if len(set(value)) != len(value):
        raise SweepError("'seeds' must not repeat a seed", file)
    return list(value)


def _responses(value, file: str) -> tuple[str, ...]:
    if not isinstance(value, list) or not value or not all(isinstance(v, str) for v in value):
        raise SweepError(f"'responses' must be a list of names from {', '.join(RESPONSES)}", file)
    unknown = [v for v in value if v not in RESPONSES]
    if unknown:
        raise SweepError(f"unknown response {unknown[0]!r}; choose from {', '.join(RESPONSES)}", file)
    return tuple(dict.fromkeys(value))
