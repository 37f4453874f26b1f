"""Temp files a killed save left behind are cleaned by every command that writes saves (issue 45: `arbor
import` left .tmp files after kill -9): atomic_write, which every save goes through, removes those of
its own target whose process is gone, never a live process's."""

from __future__ import annotations

import os
import subprocess
import sys

from arbor.engine.base.files import atomic_write


def _dead_pid() -> int:
    proc = subprocess.Popen([sys.executable, "-c", "pass"])
    proc.wait()
    return proc.pid


def test_a_write_removes_the_temp_files_of_dead_writers_of_the_same_file(tmp_path):
    dead = _dead_pid()
    stale = tmp_path / f".autosave.arbor.{dead}.tmp"
    stale.write_bytes(b"half a save")
    live = tmp_path / f".autosave.arbor.{os.getppid()}.tmp"  # (a live process's: left alone)
    live.write_bytes(b"being written")
    other = tmp_path / f".visitor-1.arbor.{dead}.tmp"  # (another file's: its own write cleans it)
    other.write_bytes(b"x")
    atomic_write(tmp_path / "autosave.arbor", b"garden")
    assert not stale.exists() and live.exists() and other.exists()
    assert (tmp_path / "autosave.arbor").read_bytes() == b"garden"
