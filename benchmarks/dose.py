"""Dose and response: how the plant model answers the sun and the can (issue figures of the plant model).

Run: python -m benchmarks.dose [--seeds 6] [--days 30] [--workers 2] [--only sun|water]

1. The sun-height example sweep (assets/experiments/sweep_sun_height.toml: orbit height -0.3 .. 1, kept
   watered, an endless summer) with SEEDS seeds for DAYS game days: per level the mean height, leaf area,
   leaf clusters and width; then, for height and leaf area, the largest step between neighbouring levels
   against the mean step (goal: at most 2x) and whether the response rises with light at every step.
2. The watering example sweep (sweep_watering.toml: a can of 5 s every 20 .. 120 s, six levels): per level
   the mean height, leaf area, biomass and share of trees alive, which level is best (goal: an optimum with
   waterlogging and drought both worse, growth falling graded on both sides: no step between neighbouring
   levels larger than twice the mean step, steps taken by size on either side of the optimum).
5. The day-length sweep (sweep_day_length.toml: 8 .. 18 hours of daylight, the noon sun at 60 degrees at
   every one, kept watered): growth rises at every step, none larger than twice the mean step.
6. Waterlogging: how long a tree lives in soil kept flooded, by the species' flood tolerance (FLOOD), in
   game days and in real days of the declared time scale, at the demo and the home pace (the sun/water
   simulation alone: the roots' oxygen dose, wilting and death; engine/life/plant/soil.py).
3. The lab regimes: a sun at orbit height 0.9 against -0.3 for 30 game days with SEEDS seeds (height / width
   ratios, mean and spread: goal the low sun's crown at least 20 % flatter), and, one seed each, the examples
   light_and_water.toml (a low sun on one side: crown offset toward it at least 10 % of the height),
   sun_vs_shade.toml (the shaded tree: at most 70 % of the leaf area, a thinner trunk) and
   drought_vs_watered.toml (smaller, fewer leaves).
Every figure is read from the runs' last samples, as the sweep's summary.csv or the lab's CSV would give it.
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

from arbor.engine.life.experiment.lab import Lab, load_experiment
from arbor.engine.life.experiment.sweep import Sweep, execute, runs
from arbor.engine.life.experiment.sweep_file import load_sweep
from arbor.engine.life.rules.rules import load_rules
from arbor.game.commands.sweep import _tasks
from arbor.game.paths import ASSETS

DAY = 125.66667  # game seconds per day of the sun at the demo pace
SHOWN = ("height", "leaf_area", "biomass", "leaves", "width", "modules", "shed")


def shortened(name: str, days: float, seeds: int) -> Sweep:
    """The example sweep ``name`` with ``days`` game days and ``seeds`` seeds (all responses recorded)."""
    sweep = load_sweep(ASSETS / "experiments" / name, ASSETS / "lsystems")
    sweep.duration = days * DAY
    sweep.seeds = list(range(1, seeds + 1))
    sweep.responses = tuple(dict.fromkeys((*sweep.responses, *SHOWN, "alive")))
    return sweep


def finals(sweep: Sweep, workers: int) -> dict[tuple, dict[str, np.ndarray]]:
    """Every run's last sample, grouped by level: {levels: {response: values over the seeds}}."""
    tasks = _tasks(sweep, runs(sweep), "none")
    with ProcessPoolExecutor(workers) as pool:
        outcomes = list(pool.map(execute, tasks, chunksize=1))
    grouped: dict[tuple, dict[str, list[float]]] = {}
    for outcome in outcomes:
        group = grouped.setdefault(outcome.run.levels, {r: [] for r in sweep.responses})
        for r in sweep.responses:
            group[r].append(outcome.rows[-1][r])
    return {k: {r: np.array(v) for r, v in g.items()} for k, g in grouped.items()}


def steps(means: list[float]) -> tuple[float, bool]:
    """(largest step / mean step, every step up) of a response over increasing levels."""
    d = np.diff(np.asarray(means))
    return float(np.abs(d).max() / max(abs(d.mean()), 1e-12)), bool((d > 0).all())


def table(sweep: Sweep, got: dict, columns: tuple[str, ...]) -> dict[str, list[float]]:
    """Print one row per level (means over seeds) and return the columns' means in level order."""
    unit = {"height": "m", "leaf_area": "m²", "biomass": "kg", "leaves": "", "width": "m", "alive": "share",
            "modules": "", "shed": ""}
    print(f"{sweep.factors[0].name:>40} " + " ".join(f"{c + (' ' + unit[c] if unit[c] else ''):>13}"
                                                   for c in columns))
    means: dict[str, list[float]] = {c: [] for c in columns}
    for level in sweep.factors[0].levels:
        row = got[(level,)]
        for c in columns:
            means[c].append(float(row[c].mean()))
        print(f"{level:>40} " + " ".join(f"{means[c][-1]:13.3f}" for c in columns))
    return means


def swept(name: str, label: str, days: float, seeds: int, workers: int) -> tuple[Sweep, dict[str, list[float]]]:
    """Run the example sweep ``name`` shortened, print its table under ``label``; the sweep and its means."""
    sweep = shortened(name, days, seeds)
    start = time.perf_counter()
    got = finals(sweep, workers)
    print(f"{label}: {len(runs(sweep))} runs of {days:g} days, {time.perf_counter() - start:.1f} s")
    return sweep, table(sweep, got, (*SHOWN, "alive"))


def daylight(orbit: float, samples: int = 2000) -> tuple[float, float]:
    """(hours of daylight, the day's mean sunshine as a share of a zenith sun's all day) at orbit height
    ``orbit`` (the demo pace, no seasons): what the sun sweep's levels give the tree."""
    from arbor.engine.life.plant.sim import Simulation

    rules = load_rules(ASSETS / "rules.toml", "demo")
    rules.seasons.enabled = False
    sim = Simulation(rules)
    sim.state.orbit_height = orbit
    shine = []
    for angle in np.linspace(0.0, 2 * np.pi, samples, endpoint=False):
        sim.state.sun_angle = float(angle)
        shine.append(sim.sunshine())
    return 24.0 * float(np.mean(np.array(shine) > 0)), float(np.mean(shine))


def sun(days: float, seeds: int, workers: int) -> None:
    """Part 1: the sun-height sweep and its steps; then what each level gives (day length, daily light) and
    the biomass's log steps per unit of daily light (a constant figure: growth compounds at a relative rate in
    proportion to the light, so the final size is exponential in it and the brightest step is the largest)."""
    sweep, means = swept("sweep_sun_height.toml", "sun height", days, seeds, workers)
    hw = [h / max(w, 1e-9) for h, w in zip(means["height"], means["width"], strict=True)]
    print("height / width by level: " + ", ".join(f"{r:.2f}" for r in hw))
    for name in ("height", "leaf_area", "biomass"):
        ratio, rising = steps(means[name])
        print(f"{name}: largest step / mean step {ratio:.2f} (goal <= 2), rises at every level: {rising}")
    given = [daylight(level) for level in sweep.factors[0].levels]
    print("daylight h by level: " + ", ".join(f"{h:.1f}" for h, _ in given))
    print("daily light (share of a zenith sun all day) by level: " + ", ".join(f"{d:.3f}" for _, d in given))
    light = np.array([d for _, d in given])
    relative = np.diff(np.log(np.maximum(means["biomass"], 1e-9))) / np.diff(light)
    print("ln(biomass) step per unit of daily light: " + ", ".join(f"{r:.1f}" for r in relative))


def species(days: float, seeds: int, workers: int) -> None:
    """Part 4: the two species under three suns: height / width and leaf clusters (the shade-tolerant game
    tree should keep a lower, wider crown in weak light than the intolerant poplar, which stretches up)."""
    sweep = shortened("sweep_species_sun.toml", days, seeds)
    got = finals(sweep, workers)
    print(f"species x sun: {len(runs(sweep))} runs of {days:g} days")
    print(f"{'species':>18} {'orbit':>6} {'height m':>9} {'width m':>8} {'h/w':>6} {'leaves':>7} {'shed':>6}")
    for kind in sweep.factors[1].levels:
        for level in sweep.factors[0].levels:
            v = {r: float(got[(level, kind)][r].mean()) for r in ("height", "width", "leaves", "shed")}
            print(f"{kind.removesuffix('.lsys'):>18} {level:6.2f} {v['height']:9.2f} {v['width']:8.2f} "
                  f"{v['height'] / max(v['width'], 1e-9):6.2f} {v['leaves']:7.0f} {v['shed']:6.0f}")


def graded(means: list[float]) -> tuple[float, int, bool]:
    """(largest step / mean step, the best level's index, whether the response rises at every step up to the
    best level and falls at every step after it) of a response over increasing levels; a step is taken by
    its size, so a response with an optimum is judged on both sides alike."""
    d = np.diff(np.asarray(means))
    best = int(np.argmax(means))
    shaped = bool((d[:best] > 0).all() and (d[best:] < 0).all())
    return float(np.abs(d).max() / max(float(np.abs(d).mean()), 1e-12)), best, shaped


def water(days: float, seeds: int, workers: int) -> None:
    """Part 2: the watering sweep, its best level and how graded it falls on either side."""
    sweep, means = swept("sweep_watering.toml", "watering", days, seeds, workers)
    levels = sweep.factors[0].levels
    for name in ("leaf_area", "biomass", "height"):
        ratio, best, shaped = graded(means[name])
        inner = 0 < best < len(levels) - 1
        print(f"{name}: best at every {levels[best]:g} s, an optimum inside the range (waterlogging and drought "
              f"both worse): {inner}; rises to it and falls after it at every step: {shaped}; largest step / mean "
              f"step {ratio:.2f} (goal <= 2)")


def day_length(days: float, seeds: int, workers: int) -> None:
    """Part 5: the day-length sweep at a fixed noon elevation and its steps."""
    _, means = swept("sweep_day_length.toml", "day length", days, seeds, workers)
    for name in ("leaf_area", "biomass", "height"):
        ratio, rising = steps(means[name])
        print(f"{name}: largest step / mean step {ratio:.2f} (goal <= 2), rises at every level: {rising}")


def survival(rules, tolerance: float, limit_days: float = 400.0) -> float:
    """Game days a tree of flood tolerance ``tolerance`` lives in soil kept waterlogged (the meter held at
    full; the sun/water simulation alone, both meters' growth already earned)."""
    from arbor.engine.life.plant.sim import Simulation

    sim = Simulation(rules)
    sim.flood_tolerance = tolerance
    sim.state.sun_cycle.earned = sim.state.water_cycle.earned = 1
    day = 2 * np.pi / rules.sun.speed
    dt, t = day / 1000, 0.0
    while sim.state.alive and t < limit_days * day:
        sim.state.water_meter = 1.0
        sim.step(dt)
        t += dt
    return t / day


def flood(_days: float, _seeds: int, _workers: int) -> None:
    """Part 6: survival in waterlogged soil by species, on the declared time scale."""
    from arbor.engine.life.lineage.species import load_collection
    from arbor.engine.life.plant.photosynthesis import real_days
    from arbor.engine.life.rules.rules import species_trait

    collection = load_collection(ASSETS / "species.toml", ASSETS / "lsystems")
    print("waterlogged soil (Kozlowski 1997: flood-intolerant seedlings live 1-4 weeks, tolerant ones months)")
    print(f"{'species':>10} {'FLOOD':>6} " + " ".join(f"{pace + ' game days':>16} {pace + ' real days':>15}"
                                                   for pace in ("demo", "home")))
    for species in collection:
        defines = dict(species.defines)
        if "FLOOD" not in defines:  # the base .lsys's own
            text = (ASSETS / "lsystems" / species.base).read_text(encoding="utf-8")
            found = [ln.split()[2] for ln in text.splitlines() if ln.startswith("#define FLOOD ")]
            defines["FLOOD"] = float(found[0]) if found else None
        cells = []
        for pace in ("demo", "home"):
            rules = load_rules(ASSETS / "rules.toml", pace)
            rules.seasons.enabled = False
            tolerance = species_trait(defines, "FLOOD", "water.flood_tolerance", rules.water.flood_tolerance)
            lived = survival(rules, tolerance)
            cells.append(f"{lived:16.2f} {lived * real_days(rules):15.0f}")
        print(f"{species.name:>10} {tolerance:6.2g} " + " ".join(cells))


HIGH_LOW = """title = "High and low sun"
seasons = false
seed = {seed}
duration = 3770
sample_every = 125.66667
[[tree]]
name = "Orbit height 0.9"
orbit_height = 0.9
watering = { below = 0.55, until = 0.75 }
[[tree]]
name = "Orbit height -0.3"
orbit_height = -0.3
watering = { below = 0.55, until = 0.75 }
"""


def lab_finals(path) -> list[tuple[str, dict[str, float]]]:
    """Run one lab experiment file; each tree's name and last sample."""
    experiment = load_experiment(path, ASSETS / "lsystems")
    lab = Lab(experiment, load_rules(ASSETS / "rules.toml", experiment.pace))
    lab.run()
    return [(s.name, {m: v[-1] for m, v in s.values.items() if v}) for s in lab.series]


def lab(_days: float, seeds: int, workers: int) -> None:
    """Part 3: the lab regimes (one process each, ``workers`` at a time); the high and low sun with ``seeds``
    seeds (the crowns' height / width: mean and standard deviation over the seeds)."""
    with tempfile.TemporaryDirectory() as tmp:
        high_low = []
        for seed in range(1, seeds + 1):
            high_low.append(Path(tmp) / f"high_low_{seed}.toml")
            high_low[-1].write_text(HIGH_LOW.replace("{seed}", str(seed)), encoding="utf-8")
        files = [*high_low, *(ASSETS / "experiments" / n for n in
                              ("light_and_water.toml", "sun_vs_shade.toml", "drought_vs_watered.toml"))]
        with ProcessPoolExecutor(workers) as pool:
            results = list(pool.map(lab_finals, files, chunksize=1))
    print(f"{'lab tree':>24} {'height m':>9} {'width m':>8} {'h/w':>6} {'offset/h':>8} {'leaf m²':>8} "
          f"{'leaves':>7} {'girth cm':>8}")
    for found in results[seeds:]:
        for name, v in found:
            hw = f"{v['height'] / v['width']:6.2f}" if v["width"] > 0 else f"{'-':>6}"  # (a dead stick has none)
            print(f"{name:>24} {v['height']:9.2f} {v['width']:8.2f} {hw} "
                  f"{v['offset'] / max(v['height'], 1e-9):8.2f} {v['leaf_area']:8.2f} {v['leaves']:7.0f} "
                  f"{v['girth']:8.2f}")
    crowns(results[:seeds])


def crowns(results: list[list[tuple[str, dict[str, float]]]]) -> None:
    """The high and low sun's crowns over the seeds: each seed's height / width, then their means, standard
    deviations and how far the means differ (goal: the low sun's crown at least 20 % flatter)."""
    print(f"{'orbit 0.9 vs -0.3, seed':>24} {'height m':>9} {'width m':>8} {'h/w':>6} {'height m':>9} "
          f"{'width m':>8} {'h/w':>6}")
    ratios = []
    for seed, ((_, hi), (_, lo)) in enumerate(results, 1):
        a, b = (v["height"] / max(v["width"], 1e-9) for v in (hi, lo))
        ratios.append((a, b))
        print(f"{seed:>24} {hi['height']:9.2f} {hi['width']:8.2f} {a:6.2f} {lo['height']:9.2f} {lo['width']:8.2f} "
              f"{b:6.2f}")
    hw = np.array(ratios)
    (a, b), (sa, sb) = hw.mean(axis=0), hw.std(axis=0, ddof=1) if len(hw) > 1 else (0.0, 0.0)
    flatter = int((hw[:, 1] < hw[:, 0]).sum())
    print(f"orbit 0.9 vs -0.3 after 30 days, {len(hw)} seeds: h/w {a:.2f} +- {sa:.2f} vs {b:.2f} +- {sb:.2f} "
          f"(sd), the low sun's {(a - b) / a:+.0%} flatter (goal >= 20 %; flatter in {flatter} of {len(hw)} seeds)")


def main() -> None:
    """Parse the options and run the parts."""
    parser = argparse.ArgumentParser(prog="python -m benchmarks.dose", description=__doc__.split("\n")[0])
    parser.add_argument("--seeds", type=int, default=6, help="seeds per level (default 6)")
    parser.add_argument("--days", type=float, default=30.0, help="game days of each run (default 30)")
    parser.add_argument("--workers", type=int, default=2, help="worker processes (default 2)")
    parser.add_argument("--only", choices=("sun", "water", "lab", "species", "daylength", "flood"),
                        help="run one part only")
    args = parser.parse_args()
    one, five, _ = os.getloadavg()
    print(f"load average {one:.1f} {five:.1f} on {os.cpu_count()} cores")
    if args.only in (None, "sun"):
        sun(args.days, args.seeds, args.workers)
    if args.only in (None, "water"):
        water(args.days, args.seeds, args.workers)
    if args.only in (None, "lab"):
        lab(args.days, args.seeds, args.workers)
    if args.only in (None, "species"):
        species(args.days, args.seeds, args.workers)
    if args.only in (None, "daylength"):
        day_length(args.days, args.seeds, args.workers)
    if args.only in (None, "flood"):
        flood(args.days, args.seeds, args.workers)


if __name__ == "__main__":
    main()
