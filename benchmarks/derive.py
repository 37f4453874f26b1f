"""Derivation benchmark: four workloads against plain-Python and string-library peers, in one run.

Run: python -m benchmarks.derive [RUNS] [plants]   ("plants": the non-parametric plants only)
Workloads (each derived step by step to about a million modules; the timed step is the last one):
- parametric with real conditions: ABOP fig. 2.8 with conditions (apices count their order, internodes
  elongate while l < 400, widths thicken while w < 100: most old modules fail them late in the run);
- stochastic: ABOP fig. 1.27;
- context-sensitive: ABOP fig. 1.31a (bracket-aware contexts, + - F ignored);
- non-parametric: ABOP fig. 1.24 a, d, e.
Peers, in the same process, interleaved, best and median CPU time of RUNS (default 5): a plain-Python
rewriter (benchmarks/peers.py: modules as tuples, productions as functions) for all four; for the
non-parametric plants (timed from 1.0-1.2M modules to 3.2-4.9M) also one `str.replace` pass per rule,
the `l-system-fractals` 0.0.6 package and the string libraries `lsys` 0.2.0 and `LindenmayerSystem`
1.0.0 when installed (`pip install arbor[bench]`), and a memcpy of the output (the floor). Prints
modules per second (modules written) and the engine's speed-up over each peer; rewritten and copied
modules are counted separately. The results are checked against
each other (same string for the deterministic workloads, same length for the stochastic one's
distribution within 1 %).
"""

from __future__ import annotations

import os
import random
import sys
import time
from pathlib import Path

import numpy as np

from arbor.engine.lsystem.derive import MAX_BUDGET, Deriver
from arbor.engine.lsystem.lsys import load_lsystem, parse_lsystem
from benchmarks import peers

ASSETS = Path(__file__).resolve().parent.parent / "assets" / "lsystems"
PARAMETRIC = """
#define d1 94.74
#define d2 132.63
#define a 18.95
#define lr 1.109
#define vr 1.732
#define lmax 400
#define wmax 100
w: !(1)F(200)/(45)A(0)
p1: A(k) : k < 20 -> !(vr)F(50)[&(a)F(50)A(k+1)]/(d1)[&(a)F(50)A(k+1)]/(d2)[&(a)F(50)A(k+1)]
p2: F(l) : l < lmax -> F(l*lr)
p3: !(w) : w < wmax -> !(w*vr)
"""
TARGET = 1_000_000
PLANT_TARGET = 1_250_000  # the plants step from their last string up to this: 1.0-1.2M modules in, 3.2-4.9M out
MAX_STEPS = 200  # a workload that never reaches the target stops here


def best_median(fn, runs: int) -> tuple[float, float, object]:
    """Best and median CPU seconds of ``runs`` calls of ``fn``, and its last result (CPU time: the
    machine may be shared, and every peer here runs on one thread)."""
    times, result = [], None
    for _ in range(runs):
        start = time.process_time()
        result = fn()
        times.append(time.process_time() - start)
    return min(times), float(np.median(times)), result


def to_tuples(ls) -> list:
    """An engine L-string as the peers' tuples."""
    text = ls.sym.tobytes().decode("ascii")
    return [(c, tuple(ls.params[o:o + k].tolist())) for c, o, k in zip(text, ls.offsets.tolist(),
                                                                       ls.nparams.tolist(), strict=True)]


def _close(a: list, b: list) -> bool:
    """Same modules, parameters equal to float rounding."""
    return len(a) == len(b) and all(x[0] == y[0] and np.allclose(x[1], y[1]) for x, y in zip(a, b, strict=True))


def grown_to(system, target: int):
    """The engine's string one step before it passes ``target`` modules, and the deriver."""
    deriver = Deriver(system, budget=MAX_BUDGET)
    ls = system.axiom
    for _ in range(MAX_STEPS):
        nxt, _ = deriver.step(ls)
        if len(nxt) > target:
            break
        ls = nxt
    return ls, deriver


def report(name: str, modules_in: int, ours: tuple, peer_times: dict[str, tuple]) -> None:
    """One row: modules/s written by the engine and each peer, and the speed-ups."""
    out_len = ours[2]
    cells = [f"{name:16} {modules_in:>9,} -> {out_len:>9,}   engine {out_len / ours[0] / 1e6:6.2f} M/s "
             f"({ours[0] * 1e3:7.1f} / {ours[1] * 1e3:7.1f} ms)"]
    for peer, (best, _med) in peer_times.items():
        if peer == "memcpy":
            cells.append(f"   engine = {ours[0] / best:4.1f}x a memcpy of the output")
        else:
            cells.append(f"   {peer} {out_len / best / 1e6:6.2f} M/s x{best / ours[0]:5.1f}")
    print("".join(cells), flush=True)


def engine_step(deriver: Deriver, ls):
    """One engine step; returns (modules written, rewritten, copied)."""
    new, rep = deriver.step(ls)
    return len(new), rep.rewritten, len(ls) - rep.rewritten


def run_parametric(runs: int) -> None:
    system = parse_lsystem(PARAMETRIC, "parametric")
    ls, deriver = grown_to(system, TARGET)
    tuples = to_tuples(ls)
    best, med, counts = best_median(lambda: engine_step(deriver, ls), runs)
    p_best, p_med, peer_out = best_median(lambda: peers.parametric_step(tuples), runs)
    new, _ = deriver.step(ls)
    assert to_tuples(new) == peer_out or _close(to_tuples(new), peer_out), "the peer and the engine disagree"
    print(f"  (parametric: {counts[1]:,} rewritten, {counts[2]:,} copied)")
    report("parametric", len(ls), (best, med, counts[0]), {"python": (p_best, p_med)})


def run_stochastic(runs: int) -> None:
    system = load_lsystem(ASSETS / "stochastic_plant.lsys")
    ls, deriver = grown_to(system, TARGET)
    tuples = to_tuples(ls)
    best, med, counts = best_median(lambda: engine_step(deriver, ls), runs)
    rng = random.Random(1)
    p_best, p_med, peer_out = best_median(lambda: peers.stochastic_step(tuples, rng), runs)
    assert abs(len(peer_out) - counts[0]) < 0.01 * counts[0], "the peer and the engine disagree"
    print(f"  (stochastic: {counts[1]:,} rewritten, {counts[2]:,} copied)")
    report("stochastic 1.27", len(ls), (best, med, counts[0]), {"python": (p_best, p_med)})


def run_context(runs: int) -> None:
    system = load_lsystem(ASSETS / "context_plant.lsys")
    ls, deriver = grown_to(system, TARGET)
    modules = [(c, ()) for c in ls.sym.tobytes().decode("ascii")]
    best, med, counts = best_median(lambda: engine_step(deriver, ls), runs)
    p_best, p_med, peer_out = best_median(lambda: peers.context_step(modules), runs)
    expected, _ = deriver.step(ls)
    assert "".join(m[0] for m in peer_out) == expected.sym.tobytes().decode("ascii"), "the peer and the engine disagree"
    print(f"  (context: {counts[1]:,} rewritten, {counts[2]:,} copied)")
    report("context 1.31a", len(ls), (best, med, counts[0]), {"python": (p_best, p_med)})


def run_plants(runs: int) -> None:
    try:
        from lsys import Lsys
    except ImportError:
        Lsys = None  # noqa: N806
    try:
        from LindenmayerSystem import LSystem as Lindenmayer
    except ImportError:
        Lindenmayer = None  # noqa: N806
    try:
        import l_system_fractals
    except ImportError:
        l_system_fractals = None
    for name, (_axiom, rules) in peers.PLANTS.items():
        system = load_lsystem(ASSETS / f"abop_{name.replace('.', '_')}.lsys")
        ls, deriver = grown_to(system, PLANT_TARGET)
        text = ls.sym.tobytes().decode("ascii")
        best, med, counts = best_median(lambda ls=ls, deriver=deriver: engine_step(deriver, ls), runs)
        tuples = [(c, ()) for c in text]
        timings = {"python": best_median(lambda t=tuples, r=rules: peers.plain_step(t, r), runs)[:2]}
        expected, _ = deriver.step(ls)
        expected_text = expected.sym.tobytes().decode("ascii")
        order = peers.replace_order(rules)
        b, m, out = best_median(lambda t=text, o=order: peers.replace_step(t, o), runs)
        assert out == expected_text, "str.replace disagrees"
        timings["str.replace"] = (b, m)
        if l_system_fractals is not None:
            b, m, out = best_median(lambda t=text, o=order: peers.fractals_step(t, o), runs)
            assert out == expected_text, "l-system-fractals disagrees"
            timings["l-system-fractals"] = (b, m)
        out_sym = expected.sym
        timings["memcpy"] = best_median(out_sym.copy, runs)[:2]
        if Lsys is not None:
            b, m, out = best_median(lambda t=text, r=rules: Lsys.expand(t, r, 1, memory_check=False), runs)
            assert out == expected_text, "lsys disagrees"
            timings["lsys"] = (b, m)
        if Lindenmayer is not None:
            def lindenmayer(t=text, r=rules):
                system = Lindenmayer(set(r), set(), t, r)
                system.iterate()
                return system.system[-1]
            b, m, out = best_median(lindenmayer, runs)
            assert out == expected_text, "LindenmayerSystem disagrees"
            timings["LindenmayerSystem"] = (b, m)
        print(f"  (plant {name}: {counts[1]:,} rewritten, {counts[2]:,} copied)")
        report(f"plant {name}", len(ls), (best, med, counts[0]), timings)


def main(runs: int, only_plants: bool = False) -> None:
    """Every workload (or only the non-parametric plants), with its peers."""
    print(f"engine vs peers, best of {runs} in CPU time (median in parentheses for the engine); "
          f"x = engine's speed-up; load average {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    if not only_plants:
        run_parametric(runs)
        run_stochastic(runs)
        run_context(runs)
    run_plants(runs)


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 5, "plants" in sys.argv[2:])
