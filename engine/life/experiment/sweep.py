"""Sweeps: one or two factors x many seeds, each run a headless one-tree lab experiment.

A sweep file (TOML) names the factors (sun orbit height or speed, a watering interval or threshold,
a pruning schedule's interval, height or share, the species, or any number in rules.toml) with their
levels, the seeds, the simulated duration and the responses to record. Every run is independent and
reproducible from its seed and levels alone: a :class:`Task` carries the L-system source and the
rules, so a run needs no files and can go to another process or another machine.
"""

from __future__ import annotations

import copy
import itertools
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from arbor.engine.life.experiment import schema
from arbor.engine.life.experiment.lab import METRICS, Experiment, Lab, Pruning, Regime
from arbor.engine.life.keep.save import save_text
from arbor.engine.life.rules.rules import Rules
from arbor.engine.lsystem.lsys import parse_lsystem

RESPONSES = tuple(m for m in METRICS if m != "day_of_death")  # (no number for a tree still alive)
SUN_KEYS = tuple(schema.SUN)  # the sun's keys of a lab tree, a sweep's [base] and its factors
REGIME_KEYS = (*SUN_KEYS, "watering.every", "watering.below",
               "prune.every_days", "prune.keep_height", "prune.lowest")
MAX_FACTORS, MAX_LEVELS, MAX_SEEDS, MAX_RUNS = 2, 24, 500, 5000


@dataclass(frozen=True)
class Factor:
    """One thing the sweep varies: a name for the plots, what it sets, and its levels."""

    name: str
    key: str  # a REGIME_KEYS entry, "species", or "section.key" of rules.toml
    levels: tuple


@dataclass(frozen=True)
class Stop:
    """When a run ends before the sweep's duration: its tree dies (``dies``), or a response crosses a value
    (``response`` reaches ``above`` or more, or falls to ``below`` or less, checked at each sample)."""

    dies: bool = False
    response: str | None = None
    above: float | None = None
    below: float | None = None

    def crossed(self, values: dict[str, list[float]]) -> str | None:
        """Why to stop after the last sample of ``values`` (a lab series' values), or None to go on."""
        if self.response is None:
            return None
        value = values[self.response][-1]
        if self.above is not None and value >= self.above:
            return f"{self.response} >= {self.above:g}"
        if self.below is not None and value <= self.below:
            return f"{self.response} <= {self.below:g}"
        return None


STOP_COLUMNS = ("stop", "stop_time_s")  # in the tidy table when a sweep has a [stop] table


@dataclass
class Sweep:
    """A whole sweep (see module docstring)."""

    title: str
    factors: list[Factor]
    seeds: list[int]
    duration: float
    sample_every: float
    responses: tuple[str, ...]
    base: Regime
    species: str = "game_tree.lsys"
    pace: str = "demo"
    seasons: bool = True
    file: str = "<sweep>"
    source: str = ""  # the file's text: finished runs are reused only by the very same sweep
    stop: Stop | None = None  # (None: every run goes the whole duration)


@dataclass(frozen=True)
class Run:
    """One run: its number, the level of each factor and the seed."""

    index: int
    levels: tuple
    seed: int

    @property
    def name(self) -> str:
        """A file-safe name, stable for a given sweep."""
        return f"run{self.index:05d}"

    def tree_name(self, sweep: Sweep) -> str:
        """The kept tree's file name: each factor's key and level, and the seed
        (``orbit_height=0.5_seed03.arbor``), so a tree can be found without the tables."""
        parts = [f"{f.key}={cell(level).removesuffix('.lsys')}" for f, level in zip(sweep.factors, self.levels,
                                                                                      strict=True)]
        name = "_".join([*parts, f"seed{self.seed:02d}"])
        return "".join(c if c.isalnum() or c in "._=-" else "_" for c in name) + ".arbor"


@dataclass
class Task:
    """Everything one run needs, with no paths: it can be pickled to a worker anywhere."""

    sweep: Sweep
    run: Run
    rules: Rules
    sources: dict[str, str]  # species file name -> .lsys text
    keep_tree: bool = False


@dataclass
class Outcome:
    """What a run sends back: sampled rows, why and when it stopped ("end": at the sweep's duration;
    "died"; "height >= 2.5") and, for kept runs, the final tree as save text."""

    run: Run
    rows: list[dict[str, float]] = field(default_factory=list)
    tree: str | None = None
    stop: str = "end"
    stop_time: float = 0.0


# What makes two sweep files the same experiment: (field, the sweep file's key); seeds and the title may
# differ between a class's folders (arbor compare), not between a file and the builder's copy of it.
EXPERIMENT = (("factors", "factor"), ("seeds", "seeds"), ("duration", "duration"), ("sample_every", "sample_every"),
              ("responses", "responses"), ("base", "base"), ("species", "species"), ("pace", "pace"),
              ("seasons", "seasons"), ("stop", "stop"))


def differences(sweep: Sweep, other: Sweep, *, seeds: bool = True, within: float = 0.0) -> list[str]:
    """The sweep file's keys in which ``other`` runs another experiment than ``sweep`` ([] for the same one):
    seeds counted unless ``seeds`` is False; the length and sampling equal within the share ``within``."""
    out = []
    for name, key in EXPERIMENT:
        a, b = getattr(sweep, name), getattr(other, name)
        if key == "seeds" and not seeds:
            continue
        if abs(a - b) > within * abs(a) if key in ("duration", "sample_every") else a != b:
            out.append(key)
    return out


def runs(sweep: Sweep) -> list[Run]:
    """Every run of the sweep: each combination of levels, each seed, in a fixed order."""
    combos = itertools.product(*(f.levels for f in sweep.factors))
    return [Run(i, levels, seed) for i, (levels, seed) in
            enumerate(itertools.product(list(combos), sweep.seeds))]


def execute(task: Task) -> Outcome:
    """Grow one run's tree headless and sample its responses (the worker's function)."""
    sweep, run = task.sweep, task.run
    lab, species = lab_for(task)
    why = grow(lab, sweep.duration, sweep.stop)
    series, world = lab.series[0], lab.worlds[0]
    rows = [{"time_s": t, **{m: series.values[m][i] for m in sweep.responses}} for i, t in enumerate(series.time)]
    return Outcome(run, rows, save_text(world, species) if task.keep_tree else None, why, series.time[-1])


def lab_for(task: Task) -> tuple[Lab, str]:
    """The one-tree lab of a run, at time 0, and its species (the file name of its .lsys source)."""
    sweep, run = task.sweep, task.run
    regime, species = copy.deepcopy(sweep.base), sweep.species  # (the lab copies the rules itself)
    for factor, level in zip(sweep.factors, run.levels, strict=True):
        if factor.key == "species":
            species = level
        elif factor.key in REGIME_KEYS:
            _set_regime(regime, factor.key, float(level))
        else:
            regime.rules[factor.key] = float(level)
    system = parse_lsystem(task.sources[species], species)
    experiment = Experiment(sweep.title, run.seed, sweep.duration, sweep.sample_every, [regime],
                            Path(species), pace=sweep.pace, seasons=sweep.seasons)
    return Lab(experiment, task.rules, system), species


def grow(lab: Lab, duration: float, stop: Stop | None = None) -> str:
    """Step a one-tree ``lab`` to ``duration`` or until ``stop`` says so; the last sample is taken when it
    stops (at the full duration, the step its tree died, or the sample that crossed the value; the first
    sample, at time 0, is never a crossing). Returns why it stopped: "end", "died" or the crossing
    ("height >= 2.5")."""
    series = lab.series[0]
    while stop is not None and lab.time < duration - 1e-9:
        samples = len(series.time)
        lab.step()
        why = stop.crossed(series.values) if len(series.time) > samples and series.time[-1] > 0 else None
        if why:
            return why
        if stop.dies and not lab.worlds[0].sim.state.alive:
            lab.sample()
            return "died"
    lab.run(duration)
    if series.time[-1] < duration - 1e-6:
        lab.sample()  # every run ends with a sample at the full duration: the dose-response reads it
    return (stop.crossed(series.values) if stop is not None else None) or "end"


def _set_regime(regime: Regime, key: str, value: float) -> None:
    if key in SUN_KEYS:
        setattr(regime, key, value)
        if key == "orbit_height":
            regime.day_length = None
        elif key == "day_length":
            regime.orbit_height = None
    elif key == "watering.every":
        regime.watering = replace(regime.watering, every=value, below=None)
    elif key == "watering.below":
        regime.watering = replace(regime.watering, below=value, every=None)
    else:  # prune.every_days, prune.keep_height, prune.lowest (on the base's schedule, or a weekly one)
        regime.prune = replace(regime.prune or Pruning(), **{key.removeprefix("prune."): value})


STATS = ("n", "mean", "sd", "p10", "median", "p90")


def final_values(table: list[dict[str, str]], sweep: Sweep) -> dict[tuple, dict[str, np.ndarray]]:
    """Each run's last sample, grouped by levels: {levels: {response: values over seeds}} (tidy rows in)."""
    last: dict[str, dict[str, str]] = {}
    for row in table:
        last[row["run"]] = row  # rows come in time order within a run
    lookup = [{cell(level): level for level in f.levels} for f in sweep.factors]
    groups: dict[tuple, dict[str, list[float]]] = {
        levels: {r: [] for r in sweep.responses} for levels in itertools.product(*(f.levels for f in sweep.factors))}
    for row in last.values():
        levels = tuple(names[row[f.name]] for names, f in zip(lookup, sweep.factors, strict=True))
        for r in sweep.responses:
            groups[levels][r].append(float(row[r]))
    return {k: {r: np.array(v) for r, v in g.items()} for k, g in groups.items() if len(g[sweep.responses[0]])}


def by_run(rows: list[dict[str, str]]) -> dict[str, list[dict[str, str]]]:
    """The tidy rows of each run (by its name), in order."""
    runs: dict[str, list[dict[str, str]]] = {}
    for row in rows:
        runs.setdefault(row["run"], []).append(row)
    return runs


def cell(value) -> str:
    """How a level or a value is written in the CSVs (text as is, numbers to 10 digits)."""
    return value if isinstance(value, str) else f"{float(value):.10g}"


def summarize(finals: dict[tuple, dict[str, np.ndarray]]) -> list[tuple[tuple, str, tuple[float, ...]]]:
    """(levels, response, (n, mean, sd, p10, median, p90)) of the final values, levels in sweep order."""
    out = []
    for levels, group in finals.items():
        for response, v in group.items():
            p10, p50, p90 = np.percentile(v, [10, 50, 90])
            sd = float(v.std(ddof=1)) if len(v) > 1 else 0.0
            out.append((levels, response, (float(len(v)), float(v.mean()), sd, float(p10), float(p50), float(p90))))
    return out
