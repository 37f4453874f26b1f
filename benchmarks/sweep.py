"""Sweep benchmark: one process against a 2-worker pool on the same sweep, and a single 30-day run.

Run: python -m benchmarks.sweep [--days DAYS] [--seeds SEEDS] [--workers N] [--profile]

1. The sun-height example (5 levels) with SEEDS seeds (default 4: 20 runs) of DAYS game days (default
   30, the example's own length), run by a fresh `arbor sweep` process in one process and then on a
   pool of N worker processes (default 2); prints both wall times (start-up included, as a teacher waits
   for it), the speed-up (goal: at least 1.8x on 2 workers), whether the two tidy CSVs are byte for byte
   equal, and the load average before and after: on a shared machine the speed-up is only as good as
   the cores the others leave free. ``--days 30 --seeds 20`` is the example sweep at its full size.

   Why 30 days (until issue 30's last stop the default was 10 days x 4 seeds): a teacher's sweep is the
   example's 30 days x 20 seeds, 100 runs of about 1.6 s each, close to 3 minutes of work, against about
   0.8 s that no pool can share (the interpreter and the numpy and numba imports, 0.4 s; numba's first
   load of the compiled kernels, 0.35 s; the tables at the end). In 20 runs of 10 days (6.5 s of work,
   0.2-0.5 s a run) that fixed part is 11 % of one process's time, which alone caps 2 workers at 1.80x
   before any cost of running two processes; in the teacher's sweep it is 0.5 %. 30 days x 4 seeds (20
   runs, 32 s of work) keeps the runs as long as a teacher's and the benchmark near a minute;
   ``--days 10`` gives the old figure (1.66-1.70x measured at load 0.9-1.3, against 1.84-1.87x here).
2. One run of that sweep at its full 30 game days (orbit height 0.7, seed 1, kept watered), timed as
   wall and CPU time (goal: at most 3 s); with ``--profile``, cProfile's top functions of that run.
"""

from __future__ import annotations

import argparse
import cProfile
import io
import os
import pstats
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from arbor.engine.life.experiment.sweep import execute, runs
from arbor.engine.life.experiment.sweep_file import load_sweep
from arbor.game.commands.sweep import _tasks
from arbor.game.paths import ASSETS

DAY = 125.66667  # game seconds per day of the sun at the demo pace
EXAMPLE = ASSETS / "experiments" / "sweep_sun_height.toml"


def load() -> str:
    """The load average (1, 5, 15 min) as text, with the cores it is shared by."""
    one, five, fifteen = os.getloadavg()
    return f"load average {one:.1f} {five:.1f} {fifteen:.1f} on {os.cpu_count()} cores"


def pool_speedup(days: float, seeds: int, workers: int) -> None:
    """The shortened sweep in one process, then on ``workers`` processes, timed (same runs, same tables)."""
    source = EXAMPLE.read_text(encoding="utf-8")
    source = source.replace("duration = 3770", f"duration = {days * DAY:.0f}").replace("seeds = 20",
                                                                                     f"seeds = {seeds}")
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "sweep.toml"
        path.write_text(source, encoding="utf-8")
        count = len(runs(load_sweep(path, ASSETS / "lsystems")))
        print(f"before: {load()}", flush=True)
        times = {}
        for name, n in (("one process", 1), (f"{workers} workers", workers)):
            # each as a teacher runs it: a fresh `arbor sweep` process (start-up, imports and the compiled
            # kernels' first load counted for both; a pool forked from a warm parent would hide them)
            command = [sys.executable, "-m", "arbor.game.cli", "-q", "sweep", str(path), "--out", str(Path(tmp) / name),
                       "--workers", str(n), "--no-plots", "--keep", "none"]
            start = time.perf_counter()
            status = subprocess.run(command, capture_output=True, text=True)
            times[name] = time.perf_counter() - start
            assert status.returncode == 0, f"{name}: the sweep failed: {status.stderr[-500:]}"
            print(f"{name:>14}: {count} runs of {days:g} days in {times[name]:6.1f} s", flush=True)
        one, pool = times.values()
        tables = [(Path(tmp) / name / "tidy.csv").read_bytes() for name in times]
        print(f"speed-up {one / pool:.2f}x on {workers} workers (goal >= 1.8x); identical tidy CSVs: "
              f"{tables[0] == tables[1]}")
        print(f"after: {load()}")


def single_run(profile: bool) -> None:
    """One 30-day run of the example (orbit height 0.7, seed 1), after a warm-up run (numba, caches)."""
    sweep = load_sweep(EXAMPLE, ASSETS / "lsystems")
    everything = runs(sweep)
    task = _tasks(sweep, [r for r in everything if r.levels == (0.7,) and r.seed == sweep.seeds[0]], "none")[0]
    execute(task)
    wall, cpu = time.perf_counter(), time.process_time()
    outcome = execute(task)
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    final = outcome.rows[-1]
    print(f"one 30-day run: {wall:.2f} s wall, {cpu:.2f} s CPU (goal <= 3 s); {load()}; final height "
          f"{final['height']:.3f} m, {final['modules']:.0f} modules")
    if profile:
        profiler = cProfile.Profile()
        profiler.runcall(execute, task)
        text = io.StringIO()
        pstats.Stats(profiler, stream=text).sort_stats("tottime").print_stats(15)
        print(text.getvalue())


def main() -> None:
    """Parse the options and run both parts."""
    parser = argparse.ArgumentParser(prog="python -m benchmarks.sweep", description=__doc__.split("\n")[0])
    parser.add_argument("--days", type=float, default=30.0, help="game days of each pooled run (default 30)")
    parser.add_argument("--seeds", type=int, default=4, help="seeds per level (5 levels; default 4)")
    parser.add_argument("--workers", type=int, default=2, help="worker processes of the pool (default 2)")
    parser.add_argument("--profile", action="store_true", help="cProfile the 30-day run")
    args = parser.parse_args()
    pool_speedup(args.days, args.seeds, args.workers)
    single_run(args.profile)


if __name__ == "__main__":
    main()
