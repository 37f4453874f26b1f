"""Running a sweep: a local process pool (default), one process, or an existing Dask cluster.

Every finished run is written to DIR/runs/ at once (temp file, fsync, rename), so Ctrl-C, a crash or
a killed machine loses only the runs in flight; the same command run again skips what is done.
"""

from __future__ import annotations

import csv
import io
import multiprocessing
import signal
import sys
import threading
import time
import traceback
from collections.abc import Iterable, Iterator
from pathlib import Path

from arbor.engine.base.errors import LSysError, SweepError
from arbor.engine.base.files import atomic_write
from arbor.engine.base.reader import TOML_LIMIT, read_user_text
from arbor.engine.life.experiment.sweep import STOP_COLUMNS, Outcome, Run, Sweep, Task, cell, execute
from arbor.game.errors import UserError

RUN_CSV_LIMIT = 64 * 1024 * 1024  # bytes of one run's CSV read back (a run writes at most 2,000 rows)


class RunStore:
    """The runs of one sweep kept in a folder: one small CSV per finished run, kept trees as saves."""

    def __init__(self, out: Path, sweep: Sweep) -> None:
        self.out, self.sweep = out, sweep
        self.runs_dir, self.trees_dir = out / "runs", out / "trees"
        stamp = out / "sweep.toml"
        if stamp.is_file() and read_user_text(stamp, TOML_LIMIT, SweepError) != sweep.source:
            raise LSysError(f"{out} holds the runs of another sweep: choose a new --out folder", sweep.file)
        self.runs_dir.mkdir(parents=True, exist_ok=True)
        self.trees_dir.mkdir(exist_ok=True)
        if not stamp.is_file():
            write_atomic(stamp, sweep.source)

    @property
    def columns(self) -> list[str]:
        """The tidy table's columns: run, seed, one per factor, time, the responses (and, for a sweep with a
        [stop] table, why and when the run stopped)."""
        stops = list(STOP_COLUMNS) if self.sweep.stop is not None else []
        return ["run", "seed", *(f.name for f in self.sweep.factors), "time_s", *self.sweep.responses, *stops]

    def done(self) -> set[str]:
        """Names of the runs already finished."""
        return {p.stem for p in self.runs_dir.glob("run*.csv")}

    def keep(self, outcome: Outcome) -> None:
        """Write one finished run (and its tree, when kept)."""
        run = outcome.run
        buf = io.StringIO()
        writer = csv.writer(buf, lineterminator="\n")
        writer.writerow(self.columns)
        stops = [outcome.stop, cell(outcome.stop_time)] if self.sweep.stop is not None else []
        for row in outcome.rows:
            writer.writerow([run.name, run.seed, *(cell(v) for v in run.levels), cell(row["time_s"]),
                             *(cell(row[r]) for r in self.sweep.responses), *stops])
        if outcome.tree is not None:
            write_atomic(self.trees_dir / run.tree_name(self.sweep), outcome.tree)
        write_atomic(self.runs_dir / f"{run.name}.csv", buf.getvalue())

    def table(self, runs: list[Run]) -> str:
        """The tidy CSV of every run, in run order (the header once)."""
        parts = [",".join(self.columns) + "\n"]
        for run in runs:
            text = read_user_text(self.runs_dir / f"{run.name}.csv", RUN_CSV_LIMIT, SweepError)  # (the --out
            # folder is the user's: a FIFO or a link planted there is refused, not waited on)
            parts.append(text.split("\n", 1)[1])
        return "".join(parts)


def write_atomic(path: Path, text: str) -> None:
    """Write ``text`` so that ``path`` is either the old file or the whole new one."""
    atomic_write(path, text.encode("utf-8"))


def run_safely(task: Task) -> Outcome | tuple[Run, str]:
    """A run's outcome, or (run, error text) when it fails: one bad run must not stop the others."""
    try:
        return execute(task)
    except Exception:  # reported with the run's name; the sweep goes on
        return task.run, traceback.format_exc(limit=3)


def _quiet_interrupts() -> None:
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the parent's to handle


def outcomes(tasks: list[Task], workers: int, scheduler: str | None) -> Iterator[Outcome | tuple[Run, str]]:
    """Run ``tasks`` and yield each outcome as it finishes (in any order). Stops the workers when the
    consumer stops (Ctrl-C in the caller), so no run goes on in the background."""
    if not tasks:
        return
    if scheduler:
        yield from _dask(tasks, scheduler)
    elif workers == 1:
        yield from map(run_safely, tasks)
    else:
        pool = multiprocessing.get_context(start_method()).Pool(min(workers, len(tasks)), initializer=_quiet_interrupts)
        try:
            yield from pool.imap_unordered(run_safely, tasks)
        finally:
            pool.terminate()
            pool.join()


def start_method() -> str:
    """How the pool's workers start: forked on Linux while no other thread runs (each worker is then a copy
    of this process, every module already imported: a second instead of a fresh interpreter's start-up
    and imports), else spawned (a fork of a process with threads may deadlock; macOS's frameworks forbid it)."""
    forkable = sys.platform == "linux" and "fork" in multiprocessing.get_all_start_methods()
    return "fork" if forkable and threading.active_count() == 1 else "spawn"


def _dask(tasks: list[Task], scheduler: str) -> Iterable[Outcome | tuple[Run, str]]:
    try:
        from dask.distributed import Client, as_completed
    except ImportError:
        raise UserError("--scheduler needs Dask: pip install 'arbor-trees[cluster]'") from None
    try:
        client = Client(scheduler, timeout="10s")
    except (OSError, TimeoutError) as exc:
        raise UserError(f"cannot reach the Dask scheduler at {scheduler} ({exc}): is it running?") from None
    futures = client.map(run_safely, tasks, pure=False)
    try:
        for future in as_completed(futures):
            yield future.result()
    finally:
        client.cancel(futures)
        client.close()


CALIBRATION_SECONDS = 0.5  # of the first run, stepped in the parent before the pool starts (after one step)


def calibrate(task: Task, seconds: float = CALIBRATION_SECONDS) -> float:
    """Seconds one run of ``task``'s sweep takes, estimated by stepping its lab for ``seconds`` (after a first
    step, which loads the kernels) and scaling to the sweep's duration (measured against whole runs of the
    sun-height and watering sweeps: 0.76-1.37 times the estimate)."""
    from arbor.engine.life.experiment.sweep import lab_for

    lab, _ = lab_for(task)
    duration = task.sweep.duration
    lab.step()
    begun, start = time.perf_counter(), lab.time
    while time.perf_counter() - begun < seconds and lab.time < duration - 1e-9:
        lab.step()
    return (time.perf_counter() - begun) / max(lab.time - start, 1e-9) * duration


def progress_bar(total: int, done: int, title: str, shown: bool = True, estimate: float | None = None):
    """A progress bar with an ETA: ``update()`` after each run, ``close()`` at the end; tqdm on a terminal,
    a line every tenth of the runs when piped; not drawn unless ``shown`` (--quiet, or --verbose's line
    per run). ``estimate``: the seconds the whole sweep should take (calibrate), shown until the first run
    ends (tqdm's own ETA takes over then)."""
    if not sys.stderr.isatty():
        return _Lines(total, done, title, shown, estimate)
    from tqdm import tqdm

    tqdm.monitor_interval = 0  # no monitor thread: the pool's workers may then be forked (see start_method)
    bar = tqdm(total=total, initial=done, unit="run", desc=title[:40], mininterval=0.5, dynamic_ncols=True,
               disable=not shown)
    if estimate is not None and shown:
        bar.set_postfix_str(f"about {estimate:.0f} s in all (calibrated)")
        first = bar.update

        def update(n: int = 1) -> None:
            bar.set_postfix_str("", refresh=False)
            bar.update = first
            first(n)

        bar.update = update
    return bar


class _Lines:
    """The piped form of the progress: a line at the start (with the calibrated estimate) and one each time
    another tenth of the runs is done, with the time left at the pace so far."""

    def __init__(self, total: int, done: int, title: str, shown: bool, estimate: float | None) -> None:
        self.total, self.done, self.title, self.shown = total, done, title, shown
        self.started, self.initial, self.said = time.perf_counter(), done, done * 10 // max(total, 1)
        if shown and done < total:
            about = f", about {estimate:.0f} s in all (calibrated on the first run's first steps)" if estimate else ""
            print(f"arbor: {title}: {done} of {total} runs done{about}", file=sys.stderr, flush=True)

    def update(self, n: int = 1) -> None:
        """Another run is done."""
        self.done += n
        tenth = self.done * 10 // max(self.total, 1)
        if self.shown and tenth > self.said:
            self.said = tenth
            pace = (time.perf_counter() - self.started) / max(self.done - self.initial, 1)
            left = f", about {pace * (self.total - self.done):.0f} s left" if self.done < self.total else ""
            print(f"arbor: {self.title}: {self.done} of {self.total} runs done{left}", file=sys.stderr, flush=True)

    def close(self) -> None:
        """Nothing to clear."""
