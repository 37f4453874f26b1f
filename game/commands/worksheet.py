"""`arbor worksheet LESSON --out sheet.html` (or .pdf): a printable worksheet for one of the lessons.

The sheet holds the lesson's question, a box for the class's prediction, the setup (read from the lesson's
own file: what varies, its levels and unit, the seeds, how long, what every tree shares), an empty chart
with the lesson's axes and units to sketch on, and the discussion questions; then, on a page of its own,
the answer key, drawn from a real run of the lesson (fewer seeds than the lesson's own, at its full
length: ``--seeds``), so it cannot disagree with the model: the chart filled in, the means per level (or
per tree) and what they show, in sentences made from the numbers. The words (question, prediction,
discussion) are in assets/worksheets/LESSON.toml; the sweep's runs are kept in a folder beside the sheet
(LESSON_runs/), so a second sheet of the same lesson does not run them again.
"""

from __future__ import annotations

import csv
import io
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from arbor.engine.base.errors import LSysError, SettingsError
from arbor.engine.base.reader import read_user_toml
from arbor.engine.life.experiment.measure import UNITS
from arbor.engine.life.experiment.sweep import Sweep, cell, final_values
from arbor.engine.life.experiment.sweep_file import load_sweep
from arbor.game import report
from arbor.game.errors import UserError
from arbor.game.paths import ASSETS

SHEETS = ASSETS / "worksheets"
KEY_SEEDS = 3  # seeds of the answer key's run (a lesson's own has 6-8)


@dataclass
class Sheet:
    """A lesson's worksheet words (assets/worksheets/NAME.toml)."""

    name: str
    lesson: Path  # the lesson's experiment or sweep file
    question: str
    predict: str
    response: str  # the chart's response
    key: list[str]  # the responses of the answer key's table
    discuss: list[str]


@dataclass
class Chart:
    """An empty chart's axes: the x axis (a factor's levels, or game days), the y axis, one line per tree."""

    title: str
    x_label: str
    y_label: str
    x_ticks: list[float]
    x_names: list[str] | None = None  # tick labels for named levels (species)
    lines: list[str] | None = None  # trees of a lab lesson: a line each to sketch
    y_top: float | None = None


@dataclass
class Answer:
    """The answer key: the filled chart's data, a table, sentences made from the numbers, and the run."""

    header: list[str]
    rows: list[list[str]]
    sentences: list[str]
    run: str  # what was run ("3 seeds of the lesson's 8, the full 20 game days")
    points: dict  # chart data: {label: (x values, y values, per-x lists of every run's values or None)}


def lessons() -> list[str]:
    """The lessons that have a worksheet."""
    return sorted(p.stem for p in SHEETS.glob("*.toml"))


def load_sheet(name: str) -> Sheet:
    """The worksheet ``name`` (light, water, competition, pruning); a name that has none is one line listing
    the ones there are."""
    if name not in lessons():
        raise UserError(f"no worksheet {name!r}: the lessons with one are {', '.join(lessons())}")
    path = SHEETS / f"{name}.toml"
    _, data = read_user_toml(path, SettingsError)
    return Sheet(name, ASSETS / "experiments" / data["lesson"], data["question"], data["predict"], data["response"],
                 list(data["key"]), list(data["discuss"]))


def _unit(response: str) -> str:
    unit = UNITS.get(response, "")
    return f" {unit}" if unit and unit not in ("count", "1 or 0", "0..1") else ""


def _num(value: float) -> str:
    """A number for a table or a sentence: three significant digits, whole above a thousand (8,810, not 8.81e+03)."""
    return f"{value:,.0f}" if abs(value) >= 1000 else f"{value:.3g}"


def trend(name: str, unit: str, levels: list[str], means: list[float]) -> str:
    """One sentence saying how ``means`` (over ``levels``) go: rising, falling, or highest at one level."""
    first, last = means[0], means[-1]
    steps = np.diff(means)
    if len(means) > 1 and np.all(steps > 0):
        times = f" ({last / first:.1f} times as much)" if first > 0 else ""
        return f"{name} rises at every step: from {_num(first)}{unit} at {levels[0]} to {_num(last)}{unit} at " \
               f"{levels[-1]}{times}."
    if len(means) > 1 and np.all(steps < 0):
        return f"{name} falls at every step: from {_num(first)}{unit} at {levels[0]} to {_num(last)}{unit} at " \
               f"{levels[-1]}."
    hi, lo = int(np.argmax(means)), int(np.argmin(means))
    return f"{name} is highest at {levels[hi]} ({_num(means[hi])}{unit}) and lowest at {levels[lo]} " \
           f"({_num(means[lo])}{unit})."


def sweep_setup(sweep: Sweep, seeds: int, day: float) -> list[str]:
    """The setup of a sweep lesson in words, from its file."""
    from arbor.game.render.figures import axis_label

    factor = sweep.factors[0]
    levels = ", ".join(cell(v).removesuffix(".lsys") for v in factor.levels)
    base = sweep.base
    shared = []
    if base.day_length is not None:
        shared.append(f"{base.day_length:g} hours of daylight")
    if base.sun_elevation is not None:
        shared.append(f"the noon sun {base.sun_elevation:g} degrees high")
    if base.watering.below is not None:
        shared.append(f"watered whenever the water meter falls below {base.watering.below:g} (until "
                      f"{base.watering.until:g})")
    elif base.watering.every is not None:
        shared.append(f"a {base.watering.seconds:g} s drink every {base.watering.every:g} s")
    if base.prune is not None:
        shared.append(f"pruned every {base.prune.every_days:g} game days")
    return [f"What changes: {axis_label(factor)}, at {levels}.",
            f"Every level grows {seeds} seed{'' if seeds == 1 else 's'} (the same seeds at each level) for "
            f"{sweep.duration / day:.0f} game days "
            f"({sweep.duration:g} s of game time).",
            *([f"Every tree has {', '.join(shared)}."] if shared else []),
            f"What is measured: {', '.join(sweep.responses)} (docs/columns.md)."]


def run_sweep_key(sweep: Sweep, folder: Path, workers: int | None, echo=report.say) -> list[dict]:
    """The lesson's runs by the sweep command (kept in ``folder``: a second sheet does not run them again);
    the tidy rows."""
    from arbor.game.commands.sweep import RESUME, run_sweep

    try:
        status = run_sweep(sweep, folder, workers, plots=False, echo=echo, keep="none")
    except LSysError:
        raise UserError(f"{folder} holds the runs of another answer key (other --seeds, or the lesson changed): "
                        "delete that folder, or write the sheet under another name") from None
    if status:
        raise UserError(f"the answer key's runs did not all end (said above); {RESUME}")
    return list(csv.DictReader(io.StringIO((folder / "tidy.csv").read_text(encoding="utf-8"))))


def sweep_answer(sheet: Sheet, sweep: Sweep, rows: list[dict], seeds_of_lesson: int, day: float) -> Answer:
    """The answer key of a sweep lesson: the means per level of the key's responses and what they show."""
    from arbor.game.render.figures import TITLES, axis_label, factor_unit

    finals = final_values(rows, sweep)
    factor = sweep.factors[0]
    unit = factor_unit(factor)
    unit = unit if not set(unit) & set(" ,.") else ""  # (h, s, m: after each level; not "share, 0..1")
    names = [f"{cell(v).removesuffix('.lsys')}{' ' + unit if unit else ''}" for v in factor.levels]
    header = [axis_label(factor), *(f"{r} ({UNITS.get(r, '')})" for r in sheet.key)]
    table, sentences = [], []
    means = {r: [float(finals[(v,)][r].mean()) for v in factor.levels] for r in sheet.key}
    for k, name in enumerate(names):
        table.append([name, *(_num(means[r][k]) for r in sheet.key)])
    for r in sheet.key:
        sentences.append(trend(TITLES.get(r, r), _unit(r), names, means[r]))
    x = [float(v) if not isinstance(v, str) else k for k, v in enumerate(factor.levels)] \
        if any(isinstance(v, str) for v in factor.levels) else [float(v) for v in factor.levels]
    points = {"mean": (x, means[sheet.response], [list(finals[(v,)][sheet.response]) for v in factor.levels])}
    run = (f"{len(sweep.seeds)} seed{'' if len(sweep.seeds) == 1 else 's'} (the lesson's file has {seeds_of_lesson}), "
           f"the full {sweep.duration / day:.0f} game days")
    return Answer(header, table, sentences, run, points)


def lab_answer(sheet: Sheet, lab, day: float) -> Answer:
    """The answer key of a lab lesson: each tree's values at the end and what they show."""
    from arbor.game.render.figures import TITLES

    names = [s.name for s in lab.series]
    header = ["tree", *(f"{r} ({UNITS.get(r, '')}, last day)" for r in sheet.key)]
    last = {r: [float(s.values[r][-1]) for s in lab.series] for r in sheet.key}
    table = [[n, *(_num(last[r][k]) for r in sheet.key)] for k, n in enumerate(names)]
    sentences = []
    for r in sheet.key:
        v = last[r]
        lo, hi = int(np.argmin(v)), int(np.argmax(v))
        others = ", ".join(f"{names[k]} {_num(v[k])}" for k in range(len(v)) if k != lo)
        sentences.append(f"{TITLES.get(r, r)} on the last day: lowest for {names[lo]} ({_num(v[lo])}{_unit(r)}; "
                         f"{others}), highest for {names[hi]}.")
    points = {s.name: (list(np.asarray(s.day, float)), list(np.asarray(s.values[sheet.response], float)), None)
              for s in lab.series}
    run = f"the lesson as written: {len(names)} trees, {lab.experiment.duration / day:.0f} game days"
    return Answer(header, table, sentences, run, points)


def make_worksheet(name: str, out: Path, seeds: int = KEY_SEEDS, workers: int | None = None,
                   duration: float | None = None, echo=report.say) -> list[Path]:
    """Write the worksheet of lesson ``name`` to ``out`` (.html or .pdf; with a PNG of each page beside a
    PDF: OUT-1.png, ...). ``duration`` (game seconds) shortens the run (tests); the sheet then says so."""
    from arbor.game.commands.sweep import day_seconds
    from arbor.game.render import worksheet as pages
    from arbor.game.render.figures import TITLES, axis_label, y_label

    suffix = out.suffix.lower()
    if suffix not in (".html", ".pdf"):
        raise UserError(f"cannot write a worksheet as {out.suffix or 'a file without a suffix'!r}: use --out "
                        "NAME.html or NAME.pdf")
    if not out.absolute().parent.is_dir():
        raise UserError(f"{out.parent}: no such folder (to write {out.name} in)")
    sheet = load_sheet(name)
    try:
        if "tree" in read_user_toml(sheet.lesson, SettingsError)[1]:  # a lab lesson ([[tree]] tables)
            chart, setup, answer = _lab_parts(sheet, duration)
        else:
            sweep = load_sweep(sheet.lesson, ASSETS / "lsystems")
            lesson_seeds = len(sweep.seeds)
            reduced = replace(sweep, seeds=sweep.seeds[:seeds], duration=duration or sweep.duration,
                              source=f"{sweep.source}\n# worksheet answer key: seeds {sweep.seeds[:seeds]}, "
                                     f"duration {duration or sweep.duration}\n")
            day = day_seconds(sweep)
            rows = run_sweep_key(reduced, out.with_name(f"{out.stem}_runs"), workers, echo)
            answer = sweep_answer(sheet, reduced, rows, lesson_seeds, day)
            if duration:
                answer.run = f"{answer.run} (shortened to {duration / day:.1f} game days)"
            factor = sweep.factors[0]
            numeric = not any(isinstance(v, str) for v in factor.levels)
            chart = Chart(TITLES.get(sheet.response, sheet.response), axis_label(factor), y_label(sheet.response),
                          answer.points["mean"][0], None if numeric else [v.removesuffix(".lsys") for v in
                                                                        factor.levels])
            setup = sweep_setup(sweep, lesson_seeds, day)
    except LSysError as err:
        raise UserError(str(err)) from None
    top = max(max(max(v) if v else 0.0 for v in (p[2] or [p[1]])) for p in answer.points.values())
    chart.y_top = pages.nice_top(top)
    lesson = f"assets/experiments/{sheet.lesson.name}"
    return pages.write(out, sheet, setup, chart, answer, lesson)


def _lab_parts(sheet: Sheet, duration: float | None):
    """The chart, setup and answer of a lab lesson (its trees grown here, in lock-step)."""
    from arbor.engine.life.experiment.lab import Lab, load_experiment, sun_of
    from arbor.engine.life.rules.rules import load_rules
    from arbor.game.render.figures import TITLES, y_label

    experiment = load_experiment(sheet.lesson, ASSETS / "lsystems")
    rules = load_rules(ASSETS / "rules.toml", experiment.pace)
    day = 2 * np.pi / rules.sun.speed
    full = experiment.duration
    if duration:
        experiment = replace(experiment, duration=duration)
    lab = Lab(experiment, rules)
    lab.run()
    regime = experiment.regimes[0]
    hours, elevation = sun_of(regime)
    shared = [f"{hours:g} hours of daylight" if hours is not None else "",
              f"the noon sun {elevation:g} degrees high" if elevation is not None else ""]
    setup = [f"The trees: {', '.join(r.name for r in experiment.regimes)}, from one seed ({experiment.seed}).",
             (f"They stand in a row {experiment.spacing:g} m apart on one plot and shade each other."
              if experiment.spacing else "Each tree stands on a plot of its own."),
             f"They grow {full / day:.0f} game days; "
             + ("every tree is watered alike" if len({repr(r.watering) for r in experiment.regimes}) == 1
                else "each tree is watered as the lesson's file says")
             + (f", with {' and '.join(s for s in shared if s)}." if any(shared) else "."),
             f"What is measured: {', '.join(TITLES.get(r, r).lower() for r in sheet.key)} (docs/columns.md)."]
    label = y_label(sheet.response) + (" per day" if sheet.response == "light_day" else "")
    chart = Chart(TITLES.get(sheet.response, sheet.response), "time (game days)", label,
                  [float(d) for d in range(0, round(full / day) + 1, 5)],
                  lines=[r.name for r in experiment.regimes])
    answer = lab_answer(sheet, lab, day)
    if duration:
        answer.run = f"{answer.run} (shortened to {duration / day:.0f} game days)"
    return chart, setup, answer
