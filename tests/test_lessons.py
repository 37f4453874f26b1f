"""The teacher's guide's lessons (docs/teaching.md) run as written, at reduced size: the files the guide
names, shortened (fewer days and seeds), through the very command the guide gives (read from it), and
what the guide says to expect shows in the numbers."""

from __future__ import annotations

import csv
import io
import re
from pathlib import Path

import numpy as np

from arbor.engine.life.experiment.lab import Lab, load_experiment
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.rules.schema import find_rule
from arbor.game.paths import ASSETS

DAY = 2 * np.pi / find_rule("sun.speed").default  # s: a day of the sun at the default sun speed

ROOT = Path(__file__).resolve().parent.parent
GUIDE = (ROOT / "docs" / "teaching.md").read_text(encoding="utf-8")


def shortened(name: str, tmp_path: Path, duration: float, seeds: int | None = None) -> Path:
    """The lesson's file with a shorter duration (and fewer seeds): nothing else changed."""
    text = (ASSETS / "experiments" / name).read_text(encoding="utf-8")
    text = re.sub(r"(?m)^duration = \d+", f"duration = {duration:.0f}", text)
    if seeds is not None:
        text = re.sub(r"(?m)^seeds = \d+", f"seeds = {seeds}", text)
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def as_written(name: str, path: Path, out: Path, *extra: str) -> None:
    """Run the guide's own command for the lesson file ``name`` (``arbor sweep|lab assets/experiments/NAME
    --out results/...``), on the shortened file ``path`` and into ``out``."""
    from arbor.game.cli import main
    from arbor.game.report import set_level

    command = re.search(rf"`arbor (sweep|lab) assets/experiments/{re.escape(name)} --out results/\w+`", GUIDE)
    assert command, f"docs/teaching.md gives no command for {name}"
    try:
        assert main(["-q", command.group(1), str(path), "--out", str(out), *extra]) == 0
    finally:
        set_level()


def finals(out: Path, factor: str, response: str) -> dict[str, float]:
    """The mean final value of ``response`` per level of ``factor``, from summary.csv."""
    rows = csv.DictReader(io.StringIO((out / "summary.csv").read_text(encoding="utf-8")))
    return {r[factor]: float(r["mean"]) for r in rows if r["response"] == response}


def test_the_guide_names_its_three_lesson_files_and_commands():
    for name, command in (("lesson_light.toml", "arbor sweep"), ("lesson_water.toml", "arbor sweep"),
                          ("lesson_competition.toml", "arbor lab")):
        assert f"{command} assets/experiments/{name}" in GUIDE
        assert (ASSETS / "experiments" / name).is_file()


def test_lesson_light_longer_days_catch_more_light(tmp_path):
    path = shortened("lesson_light.toml", tmp_path, 4 * DAY, seeds=2)
    out = tmp_path / "light"
    as_written("lesson_light.toml", path, out, "--workers", "1")  # with the figures the guide says to open
    light = finals(out, "Day length", "light_day")
    assert light["6"] < light["10"] < light["14"] < light["18"]  # the guide: light caught rises with day length
    assert finals(out, "Day length", "alive")["6"] == 1  # the guide: the 6-hour trees live
    for figure in ("dose_response.png", "time_series.png", "thumbnails.png"):
        assert (out / figure).stat().st_size > 10_000, figure


def test_lesson_light_the_short_day_s_sun_gives_the_share_the_guide_says():
    """The guide: at a 60° noon sun the 6-hour day gets 26 % of the 18-hour day's light (the game's sun, as the
    lab sets it: the day length sets the orbit's height, the noon elevation its side)."""
    from arbor.engine.life.experiment.schema import day_length_height, elevation_side
    from arbor.engine.life.plant.sim import Simulation
    from arbor.engine.life.rules.rules import Rules

    def daily(hours: float) -> float:
        rules = Rules()
        rules.seasons.enabled = False
        rules.sun.side = elevation_side(60, day_length_height(hours))
        sim = Simulation(rules)
        sim.set_orbit_height(day_length_height(hours))
        total = 0.0
        for k in range(1000):
            sim.state.sun_angle = 2 * np.pi * (k + 0.5) / 1000
            total += sim.sunshine()
        return total

    share = round(100 * daily(6) / daily(18))
    assert f"the 6-hour sun gives {share} % of the 18-hour sun's light a day" in GUIDE.replace("\n", " ")


def test_lesson_water_has_an_optimum_with_waterlogging_and_drought_both_worse(tmp_path):
    path = shortened("lesson_water.toml", tmp_path, 10 * DAY, seeds=2)
    out = tmp_path / "water"
    as_written("lesson_water.toml", path, out, "--workers", "1", "--no-plots")
    low = finals(out, "Time between drinks", "water_min")
    assert low["20"] > low["60"] > low["120"]  # the guide: the longer the wait, the lower the meter falls
    assert finals(out, "Time between drinks", "water")["20"] > 0.9  # the guide: every 20 s the soil stays near full
    biomass = finals(out, "Time between drinks", "biomass")
    best = max(biomass, key=biomass.get)
    assert best in ("30", "45", "60", "90")  # the guide: an optimum inside the range ...
    assert biomass["20"] < 0.8 * biomass[best] and biomass["120"] < 0.8 * biomass[best]  # ... both ends worse
    assert all(finals(out, "Time between drinks", "alive")[k] == 1 for k in biomass)  # (graded: none dies)


def test_lesson_competition_the_middle_tree_is_shaded(tmp_path):
    path = shortened("lesson_competition.toml", tmp_path, 25 * DAY)  # (as written)
    out = tmp_path / "competition"
    as_written("lesson_competition.toml", path, out)
    rows = list(csv.DictReader(io.StringIO((out / "results.csv").read_text(encoding="utf-8"))))
    caught = {}
    for tree in ("West", "Middle", "East"):
        light = [float(r["light_day"]) for r in rows if r["tree"] == tree][-5:]
        caught[tree] = sum(light) / len(light)
    assert caught["Middle"] < min(caught["West"], caught["East"])  # shaded from both sides: it catches least
    alone = path.with_name("alone.toml")  # the control: the same trees, each on a plot of its own
    alone.write_text(re.sub(r"(?m)^spacing = .*$", "", path.read_text(encoding="utf-8")), encoding="utf-8")
    control = Lab(load_experiment(alone, ASSETS / "lsystems"), load_rules(ASSETS / "rules.toml", "demo"))
    control.run()
    assert caught["Middle"] < 0.95 * np.mean(control.series[1].values["light_day"][-5:])
    assert all((out / name).is_file() for name in ("charts.png", "scene.png", "middle.arbor"))
    lab = Lab(load_experiment(path, ASSETS / "lsystems"), load_rules(ASSETS / "rules.toml", "demo"))
    assert [w.position[0] for w in lab.worlds] == [-8.0, 0.0, 8.0]  # 0.8 m apart (10 scene units a metre)


def test_lesson_pruning_a_raised_crown_builds_less_and_roots_take_a_larger_share(tmp_path):
    path = shortened("lesson_pruning.toml", tmp_path, 9 * DAY, seeds=1)
    out = tmp_path / "pruning"
    as_written("lesson_pruning.toml", path, out, "--workers", "1", "--no-plots", "--keep", "none")
    biomass = finals(out, "Lowest branches cut", "biomass")
    assert biomass["0"] > biomass["0.2"] > biomass["0.6"]  # the guide: the more cut, the less the tree builds
    assert finals(out, "Lowest branches cut", "pruned")["0"] == 0  # the control is never cut
    ratio = finals(out, "Lowest branches cut", "root_shoot")
    assert ratio["0.6"] > ratio["0"]  # the roots keep their share while the crown is cut
    height = finals(out, "Lowest branches cut", "height")
    assert 0.8 * height["0"] < height["0.6"] < 1.2 * height["0"]  # the guide: height changes little


def test_every_csv_column_is_documented_with_its_unit():
    from arbor.engine.life.experiment.measure import METRICS, UNITS

    doc = (ROOT / "docs" / "columns.md").read_text(encoding="utf-8")
    for name in ("run", "seed", "time_s", "day", "tree", *METRICS):
        assert re.search(rf"^\| `{name}` \| [^|]+ \| .+ \|$", doc, re.M), f"{name} is not in docs/columns.md"
    for name, unit in UNITS.items():
        if unit not in ("count", "1 or 0"):
            assert f"| `{name}` | {unit} |" in doc, f"{name}: docs/columns.md does not give the unit {unit}"
