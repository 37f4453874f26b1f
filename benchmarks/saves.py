"""Save and load of big trees: 100k-module saves, written and read back (best and median of 5).

Run: python -m benchmarks.saves
Trees of about 100,000 modules: the game tree (its living state: birth times, light, wood; most
parameters are full-precision floats; the grown tree's string repeated, so values repeat), the same
with every number made distinct (the writer's worst case), and the ABOP fig. 2.8 tree (short
numbers). For each: save (text, temp file, fsync, rename), the first load of the file (it parses the
embedded .lsys too; later loads reuse it), load (read, TOML, the L-string, checks), and the time
spent turning the L-string into text and back alone.
"""

from __future__ import annotations

import tempfile
import time
from pathlib import Path

import numpy as np

from arbor.engine.base.memory import keep_freed_memory
from arbor.engine.life.keep.save import SavedGarden, read_garden, write_garden
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.derive import Deriver
from arbor.engine.lsystem.lstring import concat, parse_lstring
from arbor.engine.lsystem.lsys import load_lsystem

ASSETS = Path(__file__).resolve().parent.parent / "assets"
TARGET = 100_000


def _times(fn, runs: int = 5) -> tuple[float, float]:
    out = []
    for _ in range(runs):
        start = time.perf_counter()
        fn()
        out.append((time.perf_counter() - start) * 1e3)
    return min(out), float(np.median(out))


def game_world(rules) -> World:
    """The game tree after 3,000 steps of a careful player, its string repeated to TARGET modules."""
    world = World(load_lsystem(ASSETS / "lsystems" / "game_tree.lsys"), rules, seed=3)
    for _ in range(3000):
        world.apply(Action.WATER, float(world.sim.state.water_meter < 0.6))
        world.step(0.5)
    ls = world.tree.lstring
    world.tree.lstring = concat(*([ls] * (TARGET // len(ls) + 1)))
    return world


def distinct_world(rules) -> World:
    """The game tree with every parameter made distinct (a tiny offset each): the worst case for the
    writer, which formats each distinct value once."""
    world = game_world(rules)
    ls = world.tree.lstring
    ls.params = ls.params + np.arange(len(ls.params)) * 1e-9
    return world


def abop_world(rules) -> World:
    """The ABOP fig. 2.8 tree derived past TARGET modules, in a world."""
    system = load_lsystem(ASSETS / "lsystems" / "abop_2_8_tree.lsys")
    world = World(system, rules, seed=1)
    ls = system.axiom
    deriver = Deriver(system)
    while len(ls) < TARGET:
        ls, _ = deriver.step(ls)
    world.tree.lstring = ls
    return world


def main() -> None:
    """Print the table (with the allocator set as `arbor` sets it)."""
    keep_freed_memory()
    rules = load_rules(ASSETS / "rules.toml", pace="demo")
    print(f"{'tree':10} {'modules':>8} {'numbers':>8} {'file MB':>8} {'save ms':>14} {'first load':>10} "
          f"{'load ms':>14} {'to_text ms':>14} {'parse ms':>14}")
    with tempfile.TemporaryDirectory() as folder:
        for name, world in (("game", game_world(rules)), ("distinct", distinct_world(rules)),
                            ("abop 2.8", abop_world(rules))):
            ls = world.tree.lstring
            path = Path(folder) / f"{name}.arbor"
            save = _times(lambda world=world, path=path: write_garden(SavedGarden([world]), path))
            slack = 2 * len(ls) / (world.system.budget or len(ls))  # (past the tree's own budget: allowed here)
            start = time.perf_counter()
            read_garden(path, rules, budget_slack=slack)  # the first load parses the embedded .lsys too
            first = (time.perf_counter() - start) * 1e3
            load = _times(lambda path=path, slack=slack: read_garden(path, rules, budget_slack=slack))
            text = ls.to_text()
            write = _times(ls.to_text)
            read = _times(lambda text=text: parse_lstring(text))
            print(f"{name:10} {len(ls):8,} {len(ls.params):8,} {path.stat().st_size / 1e6:8.2f} "
                  f"{save[0]:6.0f} /{save[1]:6.0f} {first:10.0f} "
                  + " ".join(f"{b:6.0f} /{m:6.0f}" for b, m in (load, write, read)))


if __name__ == "__main__":
    main()
