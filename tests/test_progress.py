"""Progress of long commands: a tqdm bar with the time left on a terminal, one line per stage when piped,
nothing under -q; a sweep's estimate before its first run ends comes from a calibration of that run."""

from __future__ import annotations

import io
import re

import pytest

from arbor.game import progress, report
from arbor.game.cli import main
from arbor.game.progress import Progress


@pytest.fixture
def at_once(monkeypatch):
    """Progress shown from the first moment (not only after 2 s), at the normal level."""
    monkeypatch.setattr(progress, "QUIET_SECONDS", 0.0)
    monkeypatch.setattr(report, "level", report.NORMAL)


def test_piped_progress_is_one_line_per_stage_with_an_estimate(at_once):
    out = io.StringIO()
    with Progress("work", 10.0, stream=out, tty=False) as bar:
        bar.to(2.0, "first")
        bar.to(3.0, "first")  # the same stage: no new line
        bar.to(5.0, "second")
        bar.to(10.0, "second")
    lines = out.getvalue().splitlines()
    assert [line.split(" (")[0] for line in lines] == ["arbor: work: first", "arbor: work: second",
                                                      "arbor: work: second"]
    assert re.search(r"\(20 % done, about \d+ s left\)$", lines[0]) and lines[-1].endswith("(100 % done)")


def test_a_terminal_gets_a_bar_with_the_time_left(at_once):
    out = io.StringIO()
    with Progress("work", 10.0, unit="s", stream=out, tty=True) as bar:
        bar.to(4.0, "meshing")
    text = out.getvalue()
    assert "work:  40%|" in text and "meshing, about " in text and " s left" in text


def test_quiet_shows_no_progress(at_once, monkeypatch):
    monkeypatch.setattr(report, "level", report.QUIET)
    out = io.StringIO()
    with Progress("work", 1.0, stream=out, tty=False) as bar:
        bar.to(0.5, "a")
    assert out.getvalue() == ""


def test_a_timed_stage_moves_with_the_clock_and_counts_its_real_length(at_once):
    import time

    out = io.StringIO()
    with Progress("work", 1.0, stream=out, tty=False) as bar, bar.timed("sleeping", 1.0):
        time.sleep(0.6)
        assert 0.2 < bar.done < 0.9  # the ticker moved it meanwhile
    assert bar.total == pytest.approx(bar.done) and 0.55 < bar.done < 1.0


def test_export_reports_each_stage_when_piped(at_once, tmp_path, capsys, lsys_dir):
    from arbor.game.first_start import warm_kernels

    warm_kernels()  # (kernels changed since the last build would add a first start's lines)
    assert main(["export", str(lsys_dir / "abop_2_8_tree.lsys"), "--steps", "5", "--out", str(tmp_path / "t.glb")]) == 0
    err = capsys.readouterr().err.splitlines()
    stages = [line.split(": ", 2)[2].split(" (")[0] for line in err]
    assert stages[:5] == [f"deriving: step {k} of 5" for k in range(1, 6)]
    assert stages[5].startswith("meshing ") and stages[5].endswith(" modules")
    assert set(stages[6:]) == {"writing GLB"}  # (and its last line, 100 % done)
    assert all(re.search(r"\(\d+ % done", line) for line in err)
    assert main(["export", str(lsys_dir / "abop_2_8_tree.lsys"), "--out", str(tmp_path / "u.glb"), "-q"]) == 0
    assert capsys.readouterr().err == ""


def test_a_sweep_shows_its_calibrated_estimate_before_the_first_run_ends(capsys, monkeypatch):
    from arbor.engine.life.experiment.sweep import runs
    from arbor.engine.life.experiment.sweep_file import load_sweep
    from arbor.game.commands.sweep import _tasks
    from arbor.game.commands.sweep_runs import calibrate, progress_bar
    from arbor.game.paths import ASSETS

    sweep = load_sweep(ASSETS / "experiments" / "sweep_sun_height.toml", ASSETS / "lsystems")
    seconds = calibrate(_tasks(sweep, runs(sweep)[:1])[0], seconds=0.2)
    assert 0.05 < seconds < 600  # one 30-day run: a second or two on 2 cores
    bar = progress_bar(20, 0, "Sun height", estimate=seconds * 10)
    for _ in range(20):
        bar.update()
    bar.close()
    lines = capsys.readouterr().err.splitlines()
    assert lines[0].startswith("arbor: Sun height: 0 of 20 runs done, about ") and "calibrated" in lines[0]
    assert len(lines) == 11 and lines[-1] == "arbor: Sun height: 20 of 20 runs done"
