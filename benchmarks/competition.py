"""Competition figure: lesson 3's three trees on one plot (1.5 m apart) against the same tree alone.

Run: python -m benchmarks.competition [--days DAYS] [--out docs/lab_competition.png]

Grows assets/experiments/lesson_competition.toml as written (West, Middle, East in a row, 1.5 m apart,
shading each other) and once more with each tree on a plot of its own (the control: the three are then
the same tree), prints per tree the light intercepted (share of full sun, m² x h a day at the end, the
total since planting against the lone tree) and the biomass, and draws the figure (PNG and SVG).
"""

from __future__ import annotations

import argparse
import re
import tempfile
import time
from pathlib import Path

import numpy as np

from arbor.engine.life.experiment.lab import Lab, load_experiment
from arbor.engine.life.rules.rules import load_rules
from arbor.game.paths import ASSETS
from arbor.game.render.figures import competition

DAY = 125.66667  # game seconds per day of the sun at the demo pace
LESSON = ASSETS / "experiments" / "lesson_competition.toml"


def grown(text: str, folder: Path, name: str) -> Lab:
    """The lab of ``text`` (an experiment file's text), run to its end."""
    path = folder / name
    path.write_text(text, encoding="utf-8")
    lab = Lab(load_experiment(path, ASSETS / "lsystems"), load_rules(ASSETS / "rules.toml", "demo"))
    lab.run()
    return lab


def main() -> None:
    """Both labs, the numbers and the figure."""
    parser = argparse.ArgumentParser(prog="python -m benchmarks.competition", description=__doc__.split("\n")[0])
    parser.add_argument("--days", type=float, default=None, help="game days (default: the lesson's 25)")
    parser.add_argument("--out", type=Path, default=Path("docs/lab_competition.png"))
    args = parser.parse_args()
    text = LESSON.read_text(encoding="utf-8")
    if args.days is not None:
        text = re.sub(r"(?m)^duration = \d+", f"duration = {args.days * DAY:.0f}", text)
    start = time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp:
        plot = grown(text, Path(tmp), "plot.toml")
        alone = grown(re.sub(r"(?m)^spacing = .*$", "", text), Path(tmp), "alone.toml").series[1]
    lone = float(np.sum(alone.values["light_day"]))
    last = alone.values["light_day"][-1]
    print(f"{'tree':>8}  light share (mean, day 3 on)  light a day at the end (m² x h, vs alone)  "
          "total since planting vs alone  biomass (kg)")
    for s in [*plot.series, alone]:
        name = "alone" if s is alone else s.name
        share = float(np.mean(s.values["light_share"][3:]))
        total = 100.0 * (float(np.sum(s.values["light_day"])) / lone - 1.0)
        end = s.values["light_day"][-1]
        print(f"{name:>8}  {share:28.3f}  {end:30.1f} ({100 * (end / last - 1):+5.1f} %)  {total:+27.1f} %  "
              f"{s.values['biomass'][-1]:12.2f}")
    days = plot.worlds[0].sim.state.sun_turns
    title = f"{plot.experiment.title}: {plot.experiment.spacing:g} m apart, {days:.0f} game days, noon sun overhead"
    for path in competition(plot.series, alone, args.out.with_suffix(""), title=title):
        print(path)
    print(f"({time.perf_counter() - start:.0f} s)")


if __name__ == "__main__":
    main()
