"""The `arbor` command's conventions: --version, exit status 0 / 1 / 2, broken pipes that end quietly."""

from __future__ import annotations

import subprocess
import sys
from importlib.metadata import version

import pytest

from arbor.game.cli import main


def test_version_prints_the_installed_version(capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["--version"])
    assert exit_.value.code == 0 and capsys.readouterr().out.strip() == f"arbor {version('arbor')}"


def test_usage_errors_exit_2_and_run_time_failures_exit_1(tmp_path, capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["render", "--steps", "lots", "x.lsys"])
    assert exit_.value.code == 2
    assert main(["derive", str(tmp_path / "missing.lsys")]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) >= 1 and err[-1].startswith("arbor: ") and "missing.lsys" in err[-1]


def test_a_reader_that_goes_away_ends_the_output_quietly(tmp_path):
    source = tmp_path / "long.lsys"
    source.write_text("n: 18\nw: F\np1: F -> FF\n")  # 262,144 modules: far more than one pipe buffer
    proc = subprocess.Popen([sys.executable, "-m", "arbor.game.cli", "derive", str(source)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    assert proc.stdout.read(100)
    proc.stdout.close()  # like `| head -c 100`
    err = proc.stderr.read().decode()
    assert proc.wait(timeout=60) == 1 and err == ""


def test_the_watchdog_runs_help_once_and_stops_on_a_usage_error(capfd):
    from arbor.game.watchdog import USAGE_EXIT, watch
    from arbor.game.watchdog import main as watchdog

    assert watchdog(["--help"]) == 0 and "usage: arbor" in capfd.readouterr().out
    pauses = []
    assert watch([sys.executable, "-m", "arbor.game.cli", "--pace", "never"], sleep=pauses.append,
                 poll=0.05, max_restarts=2) == USAGE_EXIT
    assert pauses == []  # not restarted
    assert watch([sys.executable, "-c", "pass"], sleep=pauses.append, poll=0.05, max_restarts=2,
                 restart_clean=False) == 0
    assert pauses == []  # a clean quit of the home game is not restarted either


def test_derive_with_a_full_budget_stops_and_says_so(tmp_path, capsys):
    source = tmp_path / "double.lsys"
    source.write_text("w: F\np1: F -> FF\n")
    assert main(["derive", str(source), "--budget", "5000", "--steps", "1000"]) == 0
    out, err = capsys.readouterr()
    assert out.strip() == "F" * 5000
    assert err.strip().splitlines() == ["module budget 5,000 full at step 14 of 1,000: derivation stopped there "
                                        "(5,000 modules; every further step would only copy them)"]
