"""Sweep benchmark: a 100-run sweep in one process against the local process pool (every core).

Run: python -m benchmarks.sweep [DAYS]
The sweep is the sun-height example (5 levels x 20 seeds) shortened to DAYS game days (default 10).
Prints the wall time of each way, the speed-up, and whether the two tidy CSVs are byte for byte equal.
"""

from __future__ import annotations

import os
import sys
import tempfile
import time
from pathlib import Path

from arbor.game.commands.sweep import run_sweep
from arbor.game.paths import ASSETS

DAY = 125.66667  # game seconds per day of the sun at the demo pace


def main(days: float) -> None:
    """Both runs of the shortened sweep, timed."""
    source = (ASSETS / "experiments" / "sweep_sun_height.toml").read_text(encoding="utf-8")
    source = source.replace("duration = 3770", f"duration = {days * DAY:.0f}")
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "sweep.toml"
        path.write_text(source, encoding="utf-8")
        times = {}
        for name, workers in (("one process", 1), (f"pool of {os.cpu_count()}", None)):
            start = time.perf_counter()
            status = run_sweep(path, Path(tmp) / name, workers=workers, plots=False, echo=lambda _: None)
            times[name] = time.perf_counter() - start
            assert status == 0, f"{name}: the sweep failed"
            print(f"{name:>14}: 100 runs of {days:g} days in {times[name]:6.1f} s", flush=True)
        one, pool = times.values()
        tables = [(Path(tmp) / name / "tidy.csv").read_bytes() for name in times]
        print(f"speed-up {one / pool:.2f}x on {os.cpu_count()} cores; identical tidy CSVs: {tables[0] == tables[1]}")


if __name__ == "__main__":
    main(float(sys.argv[1]) if len(sys.argv) > 1 else 10.0)
