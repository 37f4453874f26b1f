import csv

import pytest

from engine.errors import LSysError
from engine.lab import Lab, load_experiment
from engine.sim import load_rules
from game.lab import run_headless
from tests.conftest import ROOT

LSYS = ROOT / "assets" / "lsystems"
EXPERIMENTS = ROOT / "assets" / "experiments"


def short(path, tmp_path, duration=600):
    text = path.read_text()
    text = "\n".join(f"duration = {duration}" if line.startswith("duration") else line for line in text.splitlines())
    out = tmp_path / path.name
    out.write_text(text)
    return out


def run(path):
    lab = Lab(load_experiment(path, LSYS), load_rules(ROOT / "assets" / "rules.toml"))
    lab.run()
    return lab


def test_same_seed_and_regime_give_identical_results(tmp_path):
    path = short(EXPERIMENTS / "drought_vs_watered.toml", tmp_path)
    a, b = run(path), run(path)
    assert [s.values for s in a.series] == [s.values for s in b.series]
    assert [w.tree.lstring.to_text() for w in a.worlds] == [w.tree.lstring.to_text() for w in b.worlds]


def test_regimes_make_the_expected_difference(tmp_path):
    lab = run(short(EXPERIMENTS / "drought_vs_watered.toml", tmp_path, duration=1200))
    final = {s.name: {k: v[-1] for k, v in s.values.items()} for s in lab.series}
    assert final["Watered"]["height"] > final["Every 2 min"]["height"] > 2 * final["Drought"]["height"]
    assert final["Drought"]["wilt"] == 1.0 and final["Watered"]["wilt"] == 0.0
    shade = run(short(EXPERIMENTS / "sun_vs_shade.toml", tmp_path, duration=1200))
    sun, shaded = (s.values for s in shade.series)
    assert sun["modules"][-1] > 1.2 * shaded["modules"][-1]
    assert len(shade.series[0].time) == 1200 // 30 + 1  # a row every sample_every, both ends included


def test_headless_lab_writes_csv_pngs_and_saves(tmp_path):
    files = run_headless(short(EXPERIMENTS / "sun_vs_shade.toml", tmp_path, 300), tmp_path / "results")
    names = sorted(f.name for f in files)
    assert names == ["charts.png", "full_sun.arbor", "results.csv", "scene.png", "shade.arbor"]
    with open(tmp_path / "results" / "results.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert rows[0].keys() >= {"time_s", "tree", "height", "girth", "modules", "leaves", "sun", "water"}
    assert {r["tree"] for r in rows} == {"Full sun", "Shade"} and len(rows) == 2 * (300 // 30 + 1)
    import pygame

    charts = pygame.image.load(str(tmp_path / "results" / "charts.png"))
    scene = pygame.image.load(str(tmp_path / "results" / "scene.png"))
    assert charts.get_size() == (1600, 900) and scene.get_size() == (1280, 720)
    red = sum(1 for x in range(0, 1600, 4) for y in range(0, 900, 4) if charts.get_at((x, y))[:3] == (230, 90, 60))
    assert red > 50  # the first tree's lines are drawn


@pytest.mark.parametrize(
    "text, words",
    [
        ("seed = 1\nduration = 60\n", "1 to 4 [[tree]]"),
        ('duration = "long"\n[[tree]]\nname = "a"\n', "'duration' must be a number"),
        ('duration = 60\n[[tree]]\nname = "a"\nwatering = 3\n', "'watering' is"),
        ('duration = 60\n[[tree]]\nname = "a"\nrules = { "sun.brightness" = 2 }\n', "unknown rule"),
        ('duration = 60\nlsystem = "../../etc/passwd"\n[[tree]]\nname = "a"\n', "file name"),
        ("duration = 60\n[[tree]\n", "not valid TOML"),
    ],
)
def test_bad_experiments_are_clear_errors(tmp_path, text, words):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(LSysError) as info:
        load_experiment(path, LSYS)
    assert words in info.value.message and str(path) in info.value.file
