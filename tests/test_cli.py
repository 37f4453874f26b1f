"""The `arbor` command's conventions: --version, exit status 0 / 1 / 2, broken pipes that end quietly."""

from __future__ import annotations

import subprocess
import sys
from importlib.metadata import version
from pathlib import Path

import pytest

from arbor.engine.base.version import DISTRIBUTION
from arbor.game.cli import main


def test_version_prints_the_installed_version(capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["--version"])
    assert exit_.value.code == 0 and capsys.readouterr().out.strip() == f"arbor {version(DISTRIBUTION)}"


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


@pytest.mark.parametrize("line", [
    ["-q", "derive", "SRC"], ["derive", "SRC", "-q"], ["derive", "-q", "SRC"],
    ["--saves", "DIR", "import", "card.png"], ["import", "card.png", "--saves", "DIR"],
])
def test_every_global_option_is_taken_before_or_after_the_command(line):
    """Global options anywhere on the line, as git and pip accept theirs; given before the command, the
    command's own copy does not reset it."""
    from arbor.game.cli import build_parser

    args = build_parser().parse_args(line)
    assert args.quiet is ("-q" in line)
    assert args.saves == (Path("DIR") if "--saves" in line else None)
    assert args.verbose is False and args.tuio_port == 3333


def test_quiet_after_the_command_silences_the_report(tmp_path, capsys):
    source = tmp_path / "t.lsys"
    source.write_text("n: 2\nw: F\np1: F -> F[+F]F\n")
    assert main(["render", str(source), "--out", str(tmp_path / "t.png"), "--size", "64x64", "-q"]) == 0
    assert main(["render", str(source), "--out", str(tmp_path / "u.png"), "--size", "64x64"]) == 0
    out = capsys.readouterr().out
    assert "t.png" not in out and "u.png" in out
    with pytest.raises(SystemExit) as exit_:
        main(["-q", "render", str(source), "-v"])
    assert exit_.value.code == 2


def test_missing_files_and_folders_are_named_before_any_work(tmp_path, capsys):
    """A missing source or output folder is one line naming it (not an internal temp file's name)."""
    source = tmp_path / "t.lsys"
    source.write_text("n: 1\nw: F\n")
    assert main(["export", str(tmp_path / "nope.lsys")]) == 1
    assert main(["export", str(source), "--out", str(tmp_path / "no" / "x.glb")]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert err[0] == f"arbor: {tmp_path / 'nope.lsys'}: No such file or directory"
    assert err[1] == f"arbor: {tmp_path / 'no'}: no such folder (to write x.glb in)"
    assert ".tmp" not in "".join(err)


def test_watchdog_help_documents_the_watchdog(capsys):
    from arbor.game.watchdog import HANG_SECONDS, START_GRACE

    assert main(["watchdog", "--help"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("usage: arbor watchdog") and f"{HANG_SECONDS:g} s" in out and f"{START_GRACE:g} s" in out


def test_a_teachers_command_without_matplotlib_says_what_to_install(tmp_path, capsys, monkeypatch):
    """matplotlib is the `lab` extra: without it, lab and a plotted sweep are one line naming the extra."""
    import importlib.util

    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec", lambda name, *a: None if name == "matplotlib" else real(name, *a))
    toml = tmp_path / "x.toml"
    toml.write_text("")
    assert main(["lab", str(toml), "--out", str(tmp_path / "o")]) == 1
    assert main(["sweep", str(toml), "--out", str(tmp_path / "o")]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 2 and all("pip install 'arbor-trees[lab]'" in line for line in err)


def test_a_command_s_help_lists_only_the_options_it_takes(capsys):
    """-q, -v and --saves go with every command; the window's input options (TUIO, recording, replay) with
    the windows (the game, view, lab); the game's own (--pace, --kiosk, --windowed) with the game alone."""
    from arbor.game.cli import build_parser

    parser = build_parser()
    for command, shown, hidden in (("compare", ("--saves", "-q"), ("--tuio", "--kiosk", "--record")),
                                   ("view", ("--tuio", "--replay"), ("--kiosk", "--pace"))):
        with pytest.raises(SystemExit):
            parser.parse_args([command, "--help"])
        out = capsys.readouterr().out
        assert all(flag in out for flag in shown) and not any(flag in out for flag in hidden), out
    assert parser.parse_args(["view", "x.lsys", "--tuio"]).tuio is True
    assert parser.parse_args(["--kiosk", "--windowed"]).kiosk is True
    with pytest.raises(SystemExit) as exit_:
        parser.parse_args(["render", "x.lsys", "--kiosk"])
    assert exit_.value.code == 2
