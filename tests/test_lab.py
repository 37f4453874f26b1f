import csv

import numpy as np
import pytest

from arbor.engine.base.errors import LSysError
from arbor.engine.life.experiment.lab import Lab, load_experiment
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.rules.schema import find_rule
from arbor.game.commands.lab import run_headless
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
    lab = Lab(load_experiment(path, LSYS), load_rules(ROOT / "assets" / "rules.toml", pace="demo"))
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
    assert sun["height"][-1] > 1.1 * shaded["height"][-1]  # the low sun feeds less: a smaller tree
    assert len(shade.series[0].time) == 1200 // 30 + 1  # a row every sample_every, both ends included


def test_headless_lab_writes_csv_pngs_and_saves(tmp_path):
    files = run_headless(short(EXPERIMENTS / "sun_vs_shade.toml", tmp_path, 300), tmp_path / "results")
    names = sorted(f.name for f in files)
    assert names == ["charts.png", "charts.svg", "full_sun.arbor", "results.csv", "scene.png", "shade.arbor"]
    with open(tmp_path / "results" / "results.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert rows[0].keys() >= {"time_s", "tree", "height", "girth", "modules", "leaves", "sun", "water"}
    assert {r["tree"] for r in rows} == {"Full sun", "Shade"} and len(rows) == 2 * (300 // 30 + 1)
    import pygame

    charts = pygame.image.load(str(tmp_path / "results" / "charts.png"))
    scene = pygame.image.load(str(tmp_path / "results" / "scene.png"))
    assert charts.get_width() > 1200 and charts.get_height() > 700 and scene.get_size() == (1280, 720)
    pixels = pygame.surfarray.array3d(charts).astype(int)
    red = (np.abs(pixels - np.array([230, 90, 60])).sum(axis=2) < 30).sum()
    blue = (np.abs(pixels - np.array([60, 140, 230])).sum(axis=2) < 30).sum()
    assert red > 500 and blue > 500  # both trees' lines are drawn


@pytest.mark.parametrize(
    "text, words",
    [
        ("seed = 1\nduration = 60\n", "1 to 6 [[tree]]"),
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


def test_lab_screen_draws_trees_side_by_side_and_exports(gl_ctx, tmp_path):
    import numpy as np
    import pygame

    from arbor.game.commands.lab import new_lab
    from arbor.game.input.events import DOWN, KEY_DOWN, InputEvent
    from arbor.game.screens.lab import LabScreen
    from arbor.game.screens.stack import ScreenStack

    lab = new_lab(short(EXPERIMENTS / "drought_vs_watered.toml", tmp_path, 900))
    size = (1280, 720)
    screen = LabScreen(gl_ctx, size, lab, results=tmp_path / "results")
    screens = ScreenStack(screen)  # (as the lab's window runs it)
    for name, speed in (("100x", 100.0), ("Pause", 0.0), ("10x", 10.0)):
        rect = screen.buttons[name]
        assert screens.handle_input(InputEvent(DOWN, 0.0, "touch:1", 0, *rect.center))
        assert screen.loop.speed == speed
    assert not screens.handle_input(InputEvent(KEY_DOWN, 0.0, "keyboard", key=pygame.K_ESCAPE))
    screen.loop.speed = 100.0
    for _ in range(200):
        screen.update(1 / 60)
    assert lab.worlds[0].sim.state.time == lab.worlds[2].sim.state.time > 300  # lock-step
    fbo = gl_ctx.framebuffer(color_attachments=[gl_ctx.renderbuffer(size)],
                             depth_attachment=gl_ctx.depth_renderbuffer(size))
    screen.draw(fbo)
    img = np.frombuffer(fbo.read(components=3, viewport=(0, 0, *size)), np.uint8).reshape(720, 1280, 3)[::-1]
    tiles = [img[60:380, i * 426 + 20:(i + 1) * 426 - 20].astype(int) for i in range(3)]
    # the tiles share camera, sky and ground; what differs between them is the trees
    changed = [np.abs(t - tiles[2]).sum(axis=2) > 60 for t in tiles]
    assert changed[0].sum() > 500 and changed[1].sum() > 300  # two living trees against the dry one
    folder = screen.export()
    assert sorted(p.name for p in folder.iterdir()) == [
        "charts.png", "charts.svg", "drought.arbor", "every_2_min.arbor", "results.csv", "screen.png",
        "watered.arbor"]


def test_lab_window_opens(tmp_path):
    import os
    import shutil
    import subprocess
    import sys

    if shutil.which("xvfb-run") is None:
        pytest.skip("needs xvfb-run (CI installs it)")
    shot = tmp_path / "lab.png"
    env = dict(os.environ, SDL_VIDEODRIVER="x11", SDL_AUDIODRIVER="dummy", ARBOR_MAX_FRAMES="3",
               ARBOR_SCREENSHOT=str(shot))
    cmd = ["xvfb-run", "-a", "-s", "-screen 0 1280x720x24", sys.executable, "-m", "arbor.game.cli", "lab",
           str(EXPERIMENTS / "sun_vs_shade.toml")]
    proc = subprocess.run(cmd, env=env, capture_output=True, timeout=120)
    assert proc.returncode == 0, proc.stderr.decode()[-2000:]
    assert shot.stat().st_size > 10_000


def test_the_live_charts_mark_where_a_tree_died():
    import pygame

    from arbor.engine.life.experiment.lab import Series
    from arbor.game.render.charts import COLORS, draw_panel

    pygame.font.init()
    font = pygame.font.Font(None, 26)
    trees = []
    for name, alive in (("Lives", [1.0] * 6), ("Dies", [1.0, 1.0, 1.0, 0.0, 0.0, 0.0])):
        s = Series(name, time=[0.0, 1.0, 2.0, 3.0, 4.0, 5.0], day=[0.0, 1.0, 2.0, 3.0, 4.0, 5.0])
        s.values["wilt"] = [0.0, 0.2, 0.6, 1.0, 1.0, 1.0] if name == "Dies" else [0.0] * 6
        s.values["alive"] = alive
        trees.append(s)
    surface = pygame.Surface((600, 300))
    rect = pygame.Rect(0, 0, 600, 300)
    draw_panel(surface, rect, "wilt", trees, font, font)
    plot = pygame.Rect(rect.left + 64, rect.top + 40, rect.width - 80, rect.height - 76)
    x, y = plot.left + plot.width * 3 / 5, plot.top  # day 3, fully wilted: where the Dies line ends alive
    arms = [surface.get_at((int(x + dx), int(y + dy)))[:3] for dx, dy in ((-8, -8), (8, 8))]
    assert all(tuple(c) == COLORS[1] for c in arms)  # two arms of the cross (off the line) in the tree's colour
    plain = pygame.Surface((600, 300))
    trees[1].values["alive"] = [1.0] * 6
    draw_panel(plain, rect, "wilt", trees, font, font)
    assert all(tuple(plain.get_at((int(x + dx), int(y + dy)))[:3]) != COLORS[1] for dx, dy in ((-8, -8), (8, 8)))


def test_the_competition_figure_draws_the_plot_against_the_tree_alone(tmp_path):
    import matplotlib.image as mpimg

    from arbor.engine.life.experiment.lab import Series
    from arbor.game.render.figures import competition

    def series(name, light, share):
        s = Series(name, time=list(range(8)), day=[float(d) for d in range(8)])
        s.values["light_day"], s.values["light_share"] = light, share
        return s

    grow = [0.0, 1.0, 2.0, 4.0, 6.0, 9.0, 12.0, 15.0]
    trees = [series(n, [g * f for g in grow], [0.5 * f] * 8) for n, f in (("West", 0.95), ("Middle", 0.9),
                                                                          ("East", 0.95))]
    png, svg = competition(trees, series("alone", grow, [0.5] * 8), tmp_path / "competition")
    text = svg.read_text(encoding="utf-8")
    assert "Middle: -10.0 % on average" in text and "time (game days)" in text  # the legend's mean, an axis unit
    image = mpimg.imread(png)[..., :3]
    assert image.shape[1] > 1000 and image.std() > 0.05


def test_every_lab_tree_has_a_lineage_of_its_own_and_two_of_them_breed_a_child_of_two_parents(tmp_path):
    from arbor.engine.life.keep.save import SavedGarden, write_garden
    from arbor.game.commands.family import breed_saves

    lab = Lab(load_experiment(EXPERIMENTS / "lesson_competition.toml", LSYS),
              load_rules(ROOT / "assets" / "rules.toml", pace="demo"))
    ids = [w.lineage.id for w in lab.worlds]
    assert len(set(ids)) == 3 and all(len(i) == 16 for i in ids)  # (one seed gave all three one id)
    again = Lab(load_experiment(EXPERIMENTS / "lesson_competition.toml", LSYS),
                load_rules(ROOT / "assets" / "rules.toml", pace="demo"))
    assert [w.lineage.id for w in again.worlds] == ids  # the same file, the same ids
    saves = []
    for world, regime in zip(lab.worlds[:2], lab.experiment.regimes, strict=False):
        saves.append(tmp_path / f"{regime.name}.arbor")
        write_garden(SavedGarden([world], lsystem_name=lab.experiment.lsystem.name), saves[-1])
    garden = breed_saves(saves[0], saves[1], seed=3, out=tmp_path / "child.arbor", now=0.0)
    assert sorted(garden.worlds[-1].lineage.parents) == sorted(ids[:2])  # a cross of two, not a self-cross


def test_meters_and_wilt_are_sampled_as_mean_min_and_max_since_the_last_sample(tmp_path):
    """A 240 s watering timetable swings the water meter within a day: a sample once a day gives the
    mean, lowest and highest of every step since the sample before it, not one instant of the swing."""
    path = tmp_path / "swing.toml"
    day = 2 * np.pi / find_rule("sun.speed").default  # s: a day of the sun at the default sun speed
    path.write_text(f'title = "Swing"\nseed = 2\nduration = 760\nsample_every = {day!r}\nseasons = false\n\n'
                    '[[tree]]\nname = "Timetable"\nwatering = { every = 240, seconds = 5 }\n', encoding="utf-8")
    lab = Lab(load_experiment(path, LSYS), load_rules(ROOT / "assets" / "rules.toml", pace="demo"))
    steps: list = []  # each step's meters after it, with None where a sample was taken (before the step)
    while lab.time < lab.experiment.duration - 1e-9:
        samples = len(lab.series[0].time)
        lab.step()
        if len(lab.series[0].time) > samples:
            steps.append(None)
        s = lab.worlds[0].sim.state
        steps.append({"sun": s.sun_meter, "water": s.water_meter, "wilt": s.wilt})
    marks = [i for i, v in enumerate(steps) if v is None]
    values = lab.series[0].values
    swings = 0
    for k in range(1, len(marks)):
        between = steps[marks[k - 1] + 1:marks[k]]
        for meter in ("sun", "water", "wilt"):
            trace = np.array([v[meter] for v in between])
            assert values[meter][k] == pytest.approx(trace.mean(), abs=1e-9)
            assert values[f"{meter}_min"][k] == trace.min() and values[f"{meter}_max"][k] == trace.max()
        swings += values["water_max"][k] - values["water_min"][k] > 0.3
    assert len(marks) >= 5 and swings >= 3  # the meter swung within most days, and the samples show it


def test_the_lab_window_says_under_each_tree_whether_it_lives_its_wilt_or_the_day_it_died():
    from arbor.engine.life.experiment.measure import Meters
    from arbor.game.screens.lab import tree_state

    lab = Lab(load_experiment(EXPERIMENTS / "drought_vs_watered.toml", LSYS),
              load_rules(ROOT / "assets" / "rules.toml", pace="demo"))
    world, meters = lab.worlds[0], Meters()
    world.sim.state.wilt = 0.25
    assert tree_state(world, meters).startswith("alive, wilt 0.25, ") and tree_state(world, meters).endswith(" m")
    world.sim.state.alive, meters.died = False, 12.4
    assert tree_state(world, meters) == "dead (day 12)"
