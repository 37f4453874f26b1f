"""Derivation benchmark: the ABOP fig. 2.8 tree grown past 1 M modules.

Run: python -m benchmarks.derive
Prints, per step, modules in/out, time, modules rewritten per second and peak memory per module
(tracemalloc sees numpy's buffers). Goal (issue 2): >= 2,000,000 modules/s, <= 64 bytes/module.
"""

from __future__ import annotations

import time
import tracemalloc
from pathlib import Path

from engine.lsystem.derive import Deriver
from engine.lsystem.lsys import load_lsystem

SOURCE = Path(__file__).resolve().parent.parent / "assets" / "lsystems" / "abop_2_8_tree.lsys"
TARGET_MODULES = 1_000_000


def main() -> None:
    """Grow the tree step by step until it passes TARGET_MODULES, then one more step; print figures."""
    system = load_lsystem(SOURCE)
    deriver = Deriver(system)
    current = system.axiom
    print(f"{'step':>4} {'in':>10} {'out':>10} {'ms':>9} {'Mmod/s in':>10} {'Mmod/s out':>11} {'peak B/mod':>11}")
    total_in = total_time = 0.0
    step = 0
    while len(current) < 3 * TARGET_MODULES:
        tracemalloc.start()
        tracemalloc.reset_peak()
        start = time.perf_counter()
        new, _ = deriver.step(current)
        elapsed = time.perf_counter() - start
        _, peak = tracemalloc.get_traced_memory()
        tracemalloc.stop()
        per_module = peak / max(len(new), 1)
        print(
            f"{step:>4} {len(current):>10,} {len(new):>10,} {elapsed * 1e3:>9.1f} "
            f"{len(current) / elapsed / 1e6:>10.2f} {len(new) / elapsed / 1e6:>11.2f} {per_module:>11.1f}"
        )
        if len(current) >= 100_000:
            total_in += len(current)
            total_time += elapsed
        current, step = new, step + 1
    print(f"final string: {len(current):,} modules, {current.nbytes / len(current):.1f} bytes/module at rest")
    print(f"steps with >= 100k modules: {total_in / total_time / 1e6:.2f} M modules rewritten per second")


if __name__ == "__main__":
    main()
