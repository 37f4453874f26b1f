"""Kill -9 while saving, many times: no save is ever corrupt, a garden never mixes generations, and the
next start leaves no temp file behind.

Run: python -m benchmarks.kill_saves [KILLS]   (default 100 for one tree and 100 for a 6-tree garden)
A child process grows a garden and saves it again and again; it is SIGKILLed at a random moment;
then the save is loaded as the game loads it (and stray temp files are cleaned as the game does at
start). Prints kills, corrupt saves, mixed gardens and temp files left.
"""

from __future__ import annotations

import os
import random
import signal
import subprocess
import sys
import time
from pathlib import Path
from tempfile import TemporaryDirectory

from arbor.engine.base.errors import LSysError
from arbor.engine.life.keep.save import read_garden
from arbor.game.screens.saves import remove_stale_temp_files

ROOT = Path(__file__).resolve().parent.parent
CHILD = """
import sys
from arbor.engine.life.keep.save import SavedGarden, write_garden
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import load_lsystem
system = load_lsystem("assets/lsystems/game_tree.lsys")
rules = load_rules("assets/rules.toml", pace="demo")
worlds = [World(system, rules, seed=k) for k in range(int(sys.argv[2]))]
for w in worlds:
    w.sim.state.sun_meter = w.sim.state.water_meter = 0.9
print("ready", flush=True)
while True:
    for w in worlds:  # one generation: every tree the same number of steps
        for _ in range(20):
            w.apply(Action.WATER, float(w.sim.state.water_meter < 0.6))
            w.step(0.5)
    write_garden(SavedGarden(worlds), sys.argv[1])
"""


def run(kills: int, trees: int, seed: int = 0) -> tuple[int, int, int, int]:
    """(corrupt, mixed, temp files found, temp files left) over ``kills`` kills of a child saving ``trees``
    trees."""
    rng = random.Random(seed)
    corrupt = mixed = found = left = 0
    with TemporaryDirectory() as tmp:
        path = Path(tmp) / "autosave.arbor"
        for _ in range(kills):
            child = subprocess.Popen([sys.executable, "-c", CHILD, str(path), str(trees)], cwd=ROOT,
                                     stdout=subprocess.PIPE)
            assert child.stdout is not None and child.stdout.readline().strip() == b"ready"
            time.sleep(rng.uniform(0.05, 1.5))
            child.send_signal(signal.SIGKILL)
            child.wait()
            child.stdout.close()
            found += remove_stale_temp_files(Path(tmp))
            left += sum(1 for p in Path(tmp).iterdir() if p.name.endswith(".tmp"))
            if not path.exists():
                continue  # killed before its first save finished: nothing to lose yet
            try:
                worlds = read_garden(path).worlds
            except LSysError:
                corrupt += 1
                continue
            mixed += len({w.steps for w in worlds}) > 1 or len(worlds) != trees
    return corrupt, mixed, found, left


def main() -> None:
    """Both scenarios, printed."""
    kills = int(sys.argv[1]) if len(sys.argv) > 1 else 100
    for trees in (1, 6):
        corrupt, mixed, found, left = run(kills, trees)
        print(f"{trees} tree(s): {kills} kills during saves: {corrupt} corrupt, {mixed} mixed gardens; "
              f"{found} half-written temp files found and removed at the next start, {left} left")


if __name__ == "__main__":
    os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
    main()
