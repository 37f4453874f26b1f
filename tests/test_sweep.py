"""Sweeps: file checks, runs on a process pool, one process and a Dask LocalCluster giving the same CSVs,
Ctrl-C keeping finished runs, tables and figures a teacher can open."""

from __future__ import annotations

import csv
import io
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from arbor.engine.base.errors import LSysError
from arbor.engine.life.experiment.sweep_file import load_sweep
from arbor.game.commands.sweep import run_sweep
from arbor.game.paths import ASSETS

ROOT = Path(__file__).resolve().parent.parent
SWEEP = """
title = "Tiny sun sweep"
duration = 150
sample_every = 50
seeds = 3
seasons = false
responses = ["height", "girth", "leaves", "alive"]

[base]
watering = { below = 0.5, until = 0.7 }

[[factor]]
name = "Sun orbit height"
key = "orbit_height"
levels = [-0.6, 1.0]

[[factor]]
name = "Drain"
key = "water.drain_rate"
levels = [0.004, 0.02]
"""


@pytest.fixture(scope="module")
def sweep_file(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("sweep") / "tiny.toml"
    path.write_text(SWEEP, encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def pooled(sweep_file, tmp_path_factory) -> Path:
    """The tiny sweep on a two-process pool, with figures."""
    out = tmp_path_factory.mktemp("pooled")
    assert run_sweep(sweep_file, out, workers=2, echo=lambda _: None) == 0
    return out


def _rows(path: Path) -> list[dict]:
    return list(csv.DictReader(io.StringIO(path.read_text(encoding="utf-8"))))


def test_tidy_and_summary_tables(pooled):
    rows = _rows(pooled / "tidy.csv")
    assert len(rows) == 2 * 2 * 3 * 4  # levels x levels x seeds x samples (0, 50, 100, 150 s)
    assert list(rows[0]) == ["run", "seed", "Sun orbit height", "Drain", "time_s", "height", "girth", "leaves",
                             "alive"]
    assert {r["time_s"] for r in rows} == {"0", "50", "100", "150"}
    summary = _rows(pooled / "summary.csv")
    assert len(summary) == 4 * 4  # level combinations x responses
    height = {(r["Sun orbit height"], r["Drain"]): r for r in summary if r["response"] == "height"}
    low, high = height[("-0.6", "0.004")], height[("1", "0.004")]
    assert float(low["n"]) == 3 and float(low["p10"]) <= float(low["median"]) <= float(low["p90"])
    assert {(r["response"], r["unit"]) for r in summary} == {("height", "m"), ("girth", "cm"), ("leaves", "count"),
                                                             ("alive", "1 or 0")}
    finals = [float(r["height"]) for r in rows if r["time_s"] == "150" and r["Sun orbit height"] == "1"
              and r["Drain"] == "0.004"]
    assert np.isclose(float(high["mean"]), np.mean(finals))


def test_figures_are_real_pictures(pooled):
    import matplotlib.image as mpimg

    for name in ("dose_response", "time_series", "thumbnails"):
        png, svg = pooled / f"{name}.png", pooled / f"{name}.svg"
        assert svg.read_text(encoding="utf-8").lstrip().startswith("<?xml") and "<svg" in svg.read_text()
        img = mpimg.imread(png)[..., :3]
        assert img.shape[0] > 200 and img.shape[1] > 300
        assert img.std() > 0.05, f"{name}.png is nearly blank"
    thumbs = mpimg.imread(pooled / "thumbnails.png")[..., :3]
    greens = (thumbs[..., 1] > thumbs[..., 0] + 0.05) & (thumbs[..., 1] > thumbs[..., 2])
    assert greens.mean() > 0.05  # trees and grass were rendered, not empty frames
    kept = sorted(p.name for p in (pooled / "trees").glob("*.arbor"))  # first seed of each level combination
    assert kept == [f"orbit_height={h}_water.drain_rate={d}_seed01.arbor" for h in ("-0.6", "1") for d in
                    ("0.004", "0.02")]


def test_one_process_and_a_dask_cluster_give_identical_tables(sweep_file, pooled, tmp_path):
    from dask.distributed import LocalCluster

    single = tmp_path / "single"
    assert run_sweep(sweep_file, single, workers=1, plots=False, echo=lambda _: None) == 0
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        clustered = tmp_path / "cluster"
        assert run_sweep(sweep_file, clustered, scheduler=cluster.scheduler_address, plots=False,
                         echo=lambda _: None) == 0
    for name in ("tidy.csv", "summary.csv"):
        reference = (pooled / name).read_bytes()
        assert (single / name).read_bytes() == reference
        assert (clustered / name).read_bytes() == reference


def _like_a_terminal() -> None:
    """Ctrl-C as a shell delivers it: whatever this test process set up for its own signals (pools,
    clusters), the sweep starts with SIGINT unblocked and at its default."""
    signal.pthread_sigmask(signal.SIG_UNBLOCK, [signal.SIGINT])
    signal.signal(signal.SIGINT, signal.SIG_DFL)


@pytest.mark.skipif(sys.platform != "linux", reason="workers are forked on Linux only")
def test_workers_are_forked_from_a_quiet_process_and_spawned_beside_threads():
    script = ("import threading, time; from arbor.game.commands.sweep_runs import progress_bar, start_method; "
              "bar = progress_bar(3, 0, 'x', shown=False); print(start_method()); "
              "threading.Thread(target=time.sleep, args=(1,)).start(); print(start_method())")
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True).stdout
    assert out.split() == ["fork", "spawn"]  # the progress bar starts no thread; another thread forbids a fork


def test_ctrl_c_keeps_finished_runs_and_the_rerun_finishes(tmp_path):
    slow = tmp_path / "slow.toml"  # six runs of a few seconds each: Ctrl-C lands while most are to do
    text = SWEEP.replace("duration = 150", "duration = 1200").replace("sample_every = 50", "sample_every = 300")
    slow.write_text(text.split("[[factor]]\nname = \"Drain\"")[0], encoding="utf-8")
    out = tmp_path / "stopped"
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    proc = subprocess.Popen([sys.executable, "-m", "arbor.game.cli", "sweep", str(slow), "--out", str(out),
                             "--workers", "2", "--no-plots"], env=env, cwd=ROOT, preexec_fn=_like_a_terminal,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    deadline = time.monotonic() + 120
    while not list((out / "runs").glob("run*.csv")) and time.monotonic() < deadline and proc.poll() is None:
        time.sleep(0.02)
    proc.send_signal(signal.SIGINT)
    output, _ = proc.communicate(timeout=60)
    kept = {p.name: p.read_bytes() for p in (out / "runs").glob("run*.csv")}
    assert proc.returncode == 130, output
    assert "Traceback" not in output and "run the same command to resume" in output
    assert 1 <= len(kept) < 6
    for text in kept.values():  # every kept run is whole: its header and its five samples
        assert text.count(b"\n") == 6
    assert not list((out / "runs").glob(".*.tmp"))
    said = []
    assert run_sweep(slow, out, workers=2, plots=False, echo=said.append) == 0
    assert f"{len(kept)} already done" in said[0]
    assert all((out / "runs" / name).read_bytes() == text for name, text in kept.items())  # not run again
    rows = _rows(out / "tidy.csv")
    assert len(rows) == 6 * 5 and len({r["run"] for r in rows}) == 6


def test_a_folder_of_another_sweep_is_refused(sweep_file, pooled, tmp_path):
    other = tmp_path / "other.toml"
    other.write_text(SWEEP.replace("seeds = 3", "seeds = 4"), encoding="utf-8")
    with pytest.raises(LSysError, match="another sweep"):
        run_sweep(other, pooled, workers=1, echo=lambda _: None)


@pytest.mark.parametrize("change, message", [
    (("key = \"orbit_height\"", "key = \"water.nonsense\""), "unknown factor key 'water.nonsense' \\(use orbit_height"),
    (("seeds = 3", "seeds = 0"), "'seeds' must be 1 to"),
    (("seeds = 3", "seeds = 501"), "'seeds' must be 1 to 500"),
    (("levels = [-0.6, 1.0]", "levels = [1.0, 1.0]"), "must not repeat"),
    (("levels = [-0.6, 1.0]", "levels = [\"high\"]"), "'levels' must be a number"),
    (("\"alive\"]", "\"beauty\"]"), "unknown response 'beauty'"),
    (("sample_every = 50", "sample_every = 0.01"), "more than 2000 samples"),
    (("key = \"orbit_height\"", "key = \"species\""), "a species is the file name"),
    (("name = \"Drain\"", "name = \"Sun orbit height\""), "two factors are named 'Sun orbit height'"),
])
def test_bad_sweep_files_name_the_problem(tmp_path, change, message):
    path = tmp_path / "bad.toml"
    path.write_text(SWEEP.replace(*change), encoding="utf-8")
    with pytest.raises(LSysError, match=message) as err:
        load_sweep(path, ASSETS / "lsystems")
    assert str(path) in str(err.value)


def test_example_sweeps_load():
    for path in sorted((ASSETS / "experiments").glob("sweep_*.toml")):
        sweep = load_sweep(path, ASSETS / "lsystems")
        assert sweep.factors and len(sweep.seeds) >= 10


@pytest.mark.parametrize("flag, want", [("--quiet", 0), ("--verbose", 12)])
def test_a_quiet_sweep_says_nothing_and_a_verbose_one_a_line_per_run(sweep_file, tmp_path, capsys, flag, want):
    from arbor.game.cli import main
    from arbor.game.report import set_level

    try:
        args = [flag, "sweep", str(sweep_file), "--out", str(tmp_path / "out"), "--workers", "1", "--no-plots"]
        assert main(args) == 0
    finally:
        set_level()
    out, err = capsys.readouterr()
    runs = [line for line in out.splitlines() if line.startswith("run")]
    assert len(runs) == want and (out == "" if flag == "--quiet" else "arbor sweep:" in out)
    assert "%|" not in err  # no progress bar either way (tqdm draws on stderr)
    assert (tmp_path / "out" / "tidy.csv").exists()


@pytest.mark.parametrize("keep, seeds", [("all", ("03", "07")), ("first", ("03",)), ("none", ())])
def test_kept_trees_are_named_by_level_and_seed(tmp_path, keep, seeds):
    from arbor.game.cli import main
    from arbor.game.report import set_level

    path = tmp_path / "keep.toml"  # 2 levels x 2 seeds, 50 game seconds each
    text = SWEEP.replace("seeds = 3", "seeds = [3, 7]").replace("duration = 150", "duration = 50")
    path.write_text(text.split("[[factor]]\nname = \"Drain\"")[0], encoding="utf-8")
    try:
        args = ["-q", "sweep", str(path), "--out", str(tmp_path / "out"), "--workers", "1", "--no-plots"]
        assert main([*args, "--keep", keep]) == 0
    finally:
        set_level()
    kept = sorted(p.name for p in (tmp_path / "out" / "trees").iterdir())
    assert kept == sorted(f"orbit_height={h}_seed{s}.arbor" for h in ("-0.6", "1") for s in seeds)


def test_one_definition_of_the_same_experiment(sweep_file):
    """compare lets seeds differ, the builder does not; the length compares within the share given."""
    import dataclasses

    from arbor.engine.life.experiment.sweep import differences

    sweep = load_sweep(sweep_file, ASSETS / "lsystems")
    assert differences(sweep, sweep) == []
    reseeded = dataclasses.replace(sweep, seeds=[s + 100 for s in sweep.seeds], title="another title")
    assert differences(sweep, reseeded) == ["seeds"]
    assert differences(sweep, reseeded, seeds=False) == []
    longer = dataclasses.replace(sweep, duration=sweep.duration * 1.005, species="game_poplar.lsys")
    assert differences(sweep, longer) == ["duration", "species"]
    assert differences(sweep, longer, within=0.01) == ["species"]


def test_a_duration_in_game_days_or_years(tmp_path):
    """duration and sample_every take "N days" or "N years" (game days at the base's sun speed, a year of
    seasons.year_days); a text that is neither, or more than the limit, is one line at the value."""
    import math

    from arbor.engine.base.errors import SweepError
    from arbor.engine.life.rules.rules import load_rules

    rules = load_rules(ASSETS / "rules.toml", "demo")
    day = 2 * math.pi / rules.sun.speed
    text = ('title = "Years"\nduration = "{0}"\nsample_every = "{1}"\nseeds = 2\nresponses = ["height"]\n'
            '[base]\n{2}\n[[factor]]\nname = "Drain"\nkey = "water.drain_rate"\nlevels = [0.004]\n')
    path = tmp_path / "years.toml"
    path.write_text(text.format("2 years", "7 days", ""), encoding="utf-8")
    sweep = load_sweep(path, ASSETS / "lsystems")
    assert sweep.duration == pytest.approx(2 * rules.seasons.year_days * day) and sweep.sample_every == 7 * day
    path.write_text(text.format("1.5 years", "1 day", "sun_speed = 0.1"), encoding="utf-8")  # its own days
    sweep = load_sweep(path, ASSETS / "lsystems")
    assert sweep.duration == pytest.approx(1.5 * rules.seasons.year_days * 2 * math.pi / 0.1)
    path.write_text(text.format("1 year", "1 day", 'rules = { "sun.speed" = 0.1, "seasons.year_days" = 10 }'),
                    encoding="utf-8")  # (the rules the trees grow under)
    assert load_sweep(path, ASSETS / "lsystems").duration == pytest.approx(10 * 2 * math.pi / 0.1)
    path.write_text(text.format("2 weeks", "1 day", ""), encoding="utf-8")
    with pytest.raises(SweepError, match="'duration' must be a number of s of game time, or a text such as") as e:
        load_sweep(path, ASSETS / "lsystems")
    assert (e.value.line, e.value.col) == (2, 12)
    path.write_text(text.format("1000 years", "30 days", ""), encoding="utf-8")
    with pytest.raises(SweepError, match="'duration' must be above 0 and at most 604800 s of game time"):
        load_sweep(path, ASSETS / "lsystems")
