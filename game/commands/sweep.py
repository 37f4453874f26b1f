"""`arbor sweep SWEEP.toml --out DIR`: every run of a sweep, then a tidy CSV, a summary CSV and figures.

DIR gets: runs/ (one CSV per finished run, kept across Ctrl-C), trees/ (the final trees, as saves the
game opens, named by level and seed: ``orbit_height=0.5_seed03.arbor``; ``--keep all|first|none``:
every seed, each level's first seed (default), none), tidy.csv (one row per run and sample time), summary.csv
(per level and response at the end: n, mean, sd, 10 %, median, 90 %), and dose_response, time_series
and thumbnails as PNG and SVG. docs/columns.md documents every column (unit and meaning).
"""

from __future__ import annotations

import contextlib
import csv
import io
import math
import os
from collections.abc import Callable
from pathlib import Path

import numpy as np

from arbor.engine.base.errors import SweepError
from arbor.engine.base.reader import read_user_text
from arbor.engine.life.experiment.lab import calendar
from arbor.engine.life.experiment.measure import UNITS
from arbor.engine.life.experiment.sweep import (
    STATS,
    Outcome,
    Sweep,
    Task,
    by_run,
    cell,
    final_values,
    runs,
    summarize,
)
from arbor.engine.life.experiment.sweep_file import load_sweep
from arbor.engine.life.keep.save import read_garden
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.lsystem.lsys import MAX_SOURCE_BYTES
from arbor.game import report
from arbor.game.commands.sweep_runs import RunStore, calibrate, outcomes, progress_bar, write_atomic
from arbor.game.paths import ASSETS

MAX_WORKERS = 256
KEEP = ("all", "first", "none")


RESUME = "run the same command to resume"  # what a stopped sweep says (the runs kept are not run again)


def run_sweep(path: Path | Sweep, out: Path, workers: int | None = None, scheduler: str | None = None,
              plots: bool = True, echo: Callable[[str], None] = report.say, keep: str = "first") -> int:
    """Run what is not done yet of the sweep in ``path`` (a sweep file, or a sweep already read) into
    ``out``; write tables and figures when every run is done. ``keep`` says which final trees are saved
    (all, each level's first seed, none). Returns the exit status (0 done, 1 some runs failed, 130 stopped
    by Ctrl-C: at any moment, it says how to resume)."""
    if keep not in KEEP:
        raise ValueError(f"keep must be one of {KEEP}")
    try:
        return _run(path, out, workers, scheduler, plots, echo, keep)
    except KeyboardInterrupt:  # (before the runs, or while the tables and figures are written)
        done = len(list((out / "runs").glob("run*.csv"))) if (out / "runs").is_dir() else 0
        echo(f"stopped: {done} finished run(s) kept in {out / 'runs'}; {RESUME}")
        return 130


def _run(path: Path | Sweep, out: Path, workers: int | None, scheduler: str | None, plots: bool,
         echo: Callable[[str], None], keep: str) -> int:
    sweep = path if isinstance(path, Sweep) else load_sweep(path, ASSETS / "lsystems")
    store = RunStore(out, sweep)
    everything = runs(sweep)
    done = store.done()
    todo = [r for r in everything if r.name not in done]
    workers = min(workers or os.cpu_count() or 1, MAX_WORKERS)
    where = f"the Dask scheduler at {scheduler}" if scheduler else f"{workers} worker process(es)"
    echo(f"{sweep.title}: {len(everything)} runs, {len(everything) - len(todo)} already done, on {where}")
    tasks = _tasks(sweep, todo, keep)
    shown = report.level == report.NORMAL
    estimate = None  # seconds for the whole sweep, calibrated on the first run (a cluster: its size unknown)
    if shown and tasks and not scheduler:
        try:
            estimate = calibrate(tasks[0]) * math.ceil(len(tasks) / min(workers, len(tasks)))
        except KeyboardInterrupt:  # Ctrl-C before any run started: nothing to keep
            echo("stopped before any run started; run the same command again to start it")
            return 130
    bar = progress_bar(len(everything), len(everything) - len(todo), sweep.title, shown=shown, estimate=estimate)
    failed, stopped = [], False
    try:
        with contextlib.closing(outcomes(tasks, workers, scheduler)) as finished:
            for outcome in finished:
                if isinstance(outcome, Outcome):
                    store.keep(outcome)
                    report.detail(f"{outcome.run.name}: seed {outcome.run.seed}, levels {outcome.run.levels}, "
                                  f"{len(outcome.rows)} samples")
                else:
                    failed.append(outcome)
                bar.update()
    except KeyboardInterrupt:
        stopped = True
    finally:
        bar.close()
    if stopped:
        echo(f"stopped: {len(store.done())} of {len(everything)} runs kept in {out / 'runs'}; {RESUME} (the "
             "runs kept are not run again)")
        return 130
    for run, error in failed:
        echo(f"{run.name} (seed {run.seed}, levels {run.levels}) failed: {error.strip().splitlines()[-1]}")
    if failed:
        echo(f"{len(failed)} runs failed; the others are kept. Run the same command again to retry them.")
        return 1
    for written in write_outputs(sweep, store, everything, plots, echo):
        echo(str(written))
    return 0


def _tasks(sweep: Sweep, todo: list, keep: str = "first") -> list[Task]:
    rules = load_rules(ASSETS / "rules.toml", sweep.pace)
    names = {sweep.species, *(v for f in sweep.factors if f.key == "species" for v in f.levels)}
    sources = {name: read_user_text(ASSETS / "lsystems" / name, MAX_SOURCE_BYTES, SweepError)  # (the one reader)
               for name in names}
    kept = {"all": lambda run: True, "first": lambda run: run.seed == sweep.seeds[0], "none": lambda run: False}
    return [Task(sweep, run, rules, sources, keep_tree=kept[keep](run)) for run in todo]


def day_seconds(sweep: Sweep) -> float:
    """How long a game day (one turn of the sun) lasts in the sweep's base regime, in game seconds."""
    return calendar(sweep.pace, sweep.base)[0]  # (the pace was checked when the sweep was read)


def write_outputs(sweep: Sweep, store: RunStore, everything: list, plots: bool = True,
                  echo: Callable[[str], None] = print) -> list[Path]:
    """tidy.csv, summary.csv and (with ``plots``) the figures, from the finished runs."""
    out = store.out
    tidy = store.table(everything)
    write_atomic(out / "tidy.csv", tidy)
    rows = list(csv.DictReader(io.StringIO(tidy)))
    finals = final_values(rows, sweep)
    write_atomic(out / "summary.csv", summary_csv(sweep, finals))
    files = [out / "tidy.csv", out / "summary.csv"]
    if plots:
        from arbor.game.render import figures

        files += figures.dose_response(sweep, finals, out / "dose_response", day_seconds(sweep))
        files += figures.time_series(sweep, _series(sweep, rows), out / "time_series", day_seconds(sweep))
        files += _thumbnails(sweep, store, everything, echo, rows)
    return files


def summary_csv(sweep: Sweep, finals: dict) -> str:
    """Per combination of levels and response, the response's unit and the spread over seeds of the final
    values."""
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow([*(f.name for f in sweep.factors), "response", "unit", *STATS])
    for levels, response, stats in summarize(finals):
        writer.writerow([*(cell(v) for v in levels), response, UNITS[response], *(cell(s) for s in stats)])
    return buf.getvalue()


def _series(sweep: Sweep, rows: list[dict]) -> dict:
    """levels -> (times, {response: seeds x samples}) from the tidy rows. A run that stopped early is filled
    to the longest run's samples with its last values (a dead tree stays as it died; a run stopped at a
    crossing stays where it crossed), so the mean over seeds does not jump when a run leaves it."""
    groups: dict[tuple, list[list[dict]]] = {}
    for run_rows in by_run(rows).values():
        levels = tuple(run_rows[0][f.name] for f in sweep.factors)
        groups.setdefault(levels, []).append(run_rows)
    series = {}
    for levels, members in groups.items():
        longest = max(members, key=len)
        times = np.array([float(r["time_s"]) for r in longest])
        values = {resp: np.full((len(members), len(times)), np.nan) for resp in sweep.responses}
        for k, member in enumerate(members):
            for resp in sweep.responses:
                column = [float(r[resp]) for r in member]
                values[resp][k, :len(column)] = column
                values[resp][k, len(column):] = column[-1]
        series[levels] = (times, values)
    return series


MAX_SEED_GRID = 240  # trees in the grid of every seed (above: the grid is left out, with a line saying so)


def death_note(rows: list[dict], day_seconds: float) -> str:
    """The words under a dead tree's thumbnail, from its run's tidy rows: the day it died (a [stop] table's
    dies = true), else the first sample that found it dead (when 'alive' is recorded), else "dead"."""
    if rows and rows[-1].get("stop") == "died":
        return f"died on day {float(rows[-1]['stop_time_s']) / day_seconds:.1f}"
    dead = [r for r in rows if "alive" in r and float(r["alive"]) == 0]
    return f"dead by day {float(dead[0]['time_s']) / day_seconds:.1f}" if dead else "dead"


def _thumbnails(sweep: Sweep, store: RunStore, everything: list, echo: Callable[[str], None],
                rows: list[dict]) -> list[Path]:
    """Render the kept final trees alike (one shared scale with a metre bar, so sizes compare): each level's
    first seed in a grid (thumbnails), and, when more seeds were kept (--keep all), every seed (seeds); a dead
    tree is marked with the day it died."""
    from arbor.engine.base.units import METRE
    from arbor.game.render import figures
    from arbor.game.render.renderer import headless_context
    from arbor.game.render.scale_bar import frame_for, render_to_scale

    kept = {(r.levels, r.seed): r for r in everything if (store.trees_dir / r.tree_name(sweep)).is_file()}
    if len(kept) > MAX_SEED_GRID:
        echo(f"the grid of every seed's tree is left out: {len(kept)} trees kept, more than {MAX_SEED_GRID}")
        kept = {key: r for key, r in kept.items() if r.seed == sweep.seeds[0]}
    rules = load_rules(ASSETS / "rules.toml", sweep.pace)
    rows_of = by_run(rows)
    meshes, notes = {}, {}
    for key, run in kept.items():
        world = read_garden(store.trees_dir / run.tree_name(sweep), rules).world
        meshes[key] = world.tree.geometry(world.clocks())
        if not world.sim.state.alive:
            notes[key] = death_note(rows_of.get(run.name, []), day_seconds(sweep))
    if not meshes:
        echo("thumbnails skipped: no kept trees (--keep none)")
        return []
    try:
        ctx = headless_context()
    except Exception as exc:  # no EGL / GL here: the tables and plots are still worth having
        echo(f"thumbnails skipped: no OpenGL for headless rendering ({exc})")
        return []
    try:
        frame = frame_for(max(float(g.turtle.bounds()[1][1]) for g in meshes.values()) / METRE)
        images = {k: render_to_scale(g.mesh, (300, 360), frame, pitch=8.0, ctx=ctx) for k, g in meshes.items()}
    finally:
        ctx.release()
    first = sweep.seeds[0]
    dead = {levels: note for (levels, seed), note in notes.items() if seed == first}
    files = figures.thumbnails(sweep, {levels: img for (levels, seed), img in images.items() if seed == first},
                               store.out / "thumbnails", dead)
    if any(seed != first for _, seed in images):
        files += figures.seed_grid(sweep, images, store.out / "seeds", notes)
    return files
