"""Context neighbours: the engine's compiled loop against the whole-array numpy version, same run.

Run: python -m benchmarks.context
The string is ABOP fig. 1.31a derived past a million modules (as in benchmarks.derive). Prints the
first call (numba compiles, or loads its cache) and the best and median of 7 calls of each, and checks
that both give the same neighbours.
"""

from __future__ import annotations

import time

import numpy as np

from arbor.engine.lsystem import context
from arbor.engine.lsystem.lsys import load_lsystem
from benchmarks import context_numpy
from benchmarks.derive import ASSETS, TARGET, best_median, grown_to


def main() -> None:
    """Print the comparison."""
    system = load_lsystem(ASSETS / "context_plant.lsys")
    ls, _ = grown_to(system, TARGET)
    start = time.perf_counter()
    context.neighbours(ls.sym, system.ignore)
    print(f"{len(ls):,} modules; first call (compile or cache load) {(time.perf_counter() - start) * 1e3:.0f} ms")
    ours = best_median(lambda: context.neighbours(ls.sym, system.ignore), 7)
    peer = best_median(lambda: context_numpy.neighbours(ls.sym, system.ignore), 7)
    assert all(np.array_equal(a, b) for a, b in zip(ours[2], peer[2], strict=True)), "they disagree"
    print(f"compiled loop {ours[0] * 1e3:6.1f} / {ours[1] * 1e3:6.1f} ms   numpy {peer[0] * 1e3:6.1f} / "
          f"{peer[1] * 1e3:6.1f} ms   speed-up x{peer[0] / ours[0]:.1f}")


if __name__ == "__main__":
    main()
