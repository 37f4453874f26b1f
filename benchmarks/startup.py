"""Start-up figures of the game window: cold (numba's cache empty: a first start after install) and warm.

Run: python -m benchmarks.startup [RUNS]
Each run starts `arbor` under a virtual display (xvfb-run -a) with ARBOR_TIMING set, a fresh saves folder
and ARBOR_MAX_FRAMES=30, and reads the milestones the app prints: the first frame (the title screen),
the garden's first frame (seconds since launch, and the CPU seconds the process had spent by then, all
its threads: the figure to read on a shared machine) and the window's close; the exit figure is from the
close to the process's end.
The cold run points NUMBA_CACHE_DIR at an empty folder; the warm runs reuse that folder.
The game may write Python's bytecode cache (__pycache__) even when the calling shell says
PYTHONDONTWRITEBYTECODE: a player's install has it from the first start on (without it every start compiled
each Arbor module from source again: 0.2-0.35 s more CPU).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def run_once(cache: Path, saves: Path) -> dict[str, float]:
    """One start of the game window; seconds since launch of each milestone, and the exit time."""
    env = dict(os.environ, SDL_VIDEODRIVER="x11", SDL_AUDIODRIVER="dummy", ARBOR_TIMING="1",
               ARBOR_MAX_FRAMES="30", ARBOR_SAVES=str(saves), NUMBA_CACHE_DIR=str(cache))
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    arbor = str(Path(sys.executable).with_name("arbor"))
    run = subprocess.run(["xvfb-run", "-a", "-s", "-screen 0 1280x720x24", arbor], env=env,
                         capture_output=True, text=True, timeout=900)
    ended = time.time()
    figures: dict[str, float] = {}
    for line in run.stderr.splitlines():
        if line.startswith("arbor-timing "):
            _, what, since, wall, cpu = line.split()
            figures[what], figures[f"{what}-cpu"] = float(since), float(cpu)
            if what == "closed":
                figures["exit"] = ended - float(wall)
    if run.returncode != 0 or "garden" not in figures:
        raise SystemExit(f"arbor failed ({run.returncode}): {run.stderr.strip()[-400:]}")
    return figures


def main() -> None:
    """Print the cold run and RUNS warm runs (default 3)."""
    runs = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    work = Path(tempfile.mkdtemp(prefix="arbor-startup-"))
    try:
        cache = work / "numba-cache"
        cache.mkdir()
        print(f"load average {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
        print(f"{'run':<8}{'first frame s':>15}{'garden s':>10}{'garden CPU s':>14}{'exit after close s':>20}")
        for i in range(runs + 1):
            saves = work / f"saves{i}"
            f = run_once(cache, saves)
            print(f"{'cold' if i == 0 else f'warm {i}':<8}{f['first-frame']:>15.2f}{f['garden']:>10.2f}"
                  f"{f['garden-cpu']:>14.2f}{f['exit']:>20.2f}", flush=True)
        print(f"load average {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
