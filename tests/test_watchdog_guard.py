"""The watchdog's crash-loop guard sets aside the file the child died reading (settings.toml,
kiosk.toml, a save), never a garden that loads; and a slow first start is not taken for a hang (issue 45:
a 2 KB settings.toml crashed every kiosk start and the watchdog moved the visitors' autosave aside
instead; healthy starts on a loaded machine were killed at 60 s)."""

from __future__ import annotations

import contextlib
import os
import sys
import time
from pathlib import Path

import pytest

from arbor.engine.life.keep.save_check import SaveError
from arbor.game.watchdog import STAFF_EXIT, reading, started, watch

NOTE = "pathlib.Path(os.environ['ARBOR_HEARTBEAT'] + '.reading').write_text({!r})\n"


def _script(counter: Path, body: str) -> str:
    return (f"import os, pathlib, sys, time; p = pathlib.Path({str(counter)!r}); n = int(p.read_text()) "
            f"if p.exists() else 0; p.write_text(str(n + 1))\n{body}")


def test_a_crash_loop_sets_aside_the_settings_file_not_the_garden(tmp_path):
    folder = tmp_path / "kiosk"
    folder.mkdir()
    (folder / "autosave.arbor").write_text("a garden that loads")
    settings = folder / "settings.toml"
    settings.write_text("x = " + "[" * 3000)
    body = (f"if pathlib.Path({str(settings)!r}).exists():\n    " + NOTE.format(str(settings)) +
            f"    sys.exit(1)\nsys.exit({STAFF_EXIT})\n")
    status = watch([sys.executable, "-c", _script(tmp_path / "runs", body)], sleep=lambda s: None, poll=0.05)
    assert status == STAFF_EXIT and (tmp_path / "runs").read_text() == "4"
    assert (folder / "autosave.arbor").read_text() == "a garden that loads"
    assert not settings.exists() and (folder / "settings.toml.crashed").read_text().startswith("x = [[[")


def test_a_crash_loop_not_while_reading_a_file_moves_nothing(tmp_path, caplog):
    folder = tmp_path / "kiosk"
    folder.mkdir()
    (folder / "autosave.arbor").write_text("a garden that loads")
    body = f"sys.exit(1 if n < 3 else {STAFF_EXIT})\n"
    assert watch([sys.executable, "-c", _script(tmp_path / "runs", body)], sleep=lambda s: None,
                 poll=0.05) == STAFF_EXIT
    assert sorted(p.name for p in folder.iterdir()) == ["autosave.arbor"]
    assert "not while reading a file: nothing set aside" in caplog.text


def test_a_slow_first_start_is_not_killed(tmp_path):
    """The first heartbeat comes 190 s into the start (the watchdog's clock runs 100 times fast here): a
    loaded machine's first start, which the old 60 s grace killed as hung."""
    body = ("time.sleep(1.9); pathlib.Path(os.environ['ARBOR_HEARTBEAT']).touch(); time.sleep(0.3)\n"
            f"sys.exit({STAFF_EXIT})\n")
    status = watch([sys.executable, "-c", _script(tmp_path / "runs", body)], sleep=lambda s: None, poll=0.02,
                   clock=lambda: time.monotonic() * 100, hang=1000.0)
    assert status == STAFF_EXIT and (tmp_path / "runs").read_text() == "1"


def test_the_reading_note_is_cleared_once_read_and_kept_when_reading_fails(tmp_path, monkeypatch):
    beat = tmp_path / "heartbeat"
    note = tmp_path / "heartbeat.reading"
    monkeypatch.setenv("ARBOR_HEARTBEAT", str(beat))
    with reading(tmp_path / "settings.toml"):
        assert note.read_text() == str(tmp_path / "settings.toml")
    assert not note.exists()
    try:
        with reading(tmp_path / "autosave.arbor"):
            raise RuntimeError("died reading it")
    except RuntimeError:
        pass
    assert note.read_text() == str(tmp_path / "autosave.arbor")
    with pytest.raises(SaveError), reading(tmp_path / "broken.arbor"):  # refused in one line: the caller goes on
        raise SaveError("not a garden", "broken.arbor", 1, 1)
    assert not note.exists()
    with contextlib.suppress(RuntimeError), reading(tmp_path / "autosave.arbor"):
        raise RuntimeError("died reading it")
    started()  # the first frame: the start is over
    assert not note.exists()
    monkeypatch.delenv("ARBOR_HEARTBEAT")
    with reading(tmp_path / "x"):  # (no watchdog: nothing written)
        assert not os.listdir(tmp_path)
