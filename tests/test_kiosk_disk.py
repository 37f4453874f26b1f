"""The kiosk and its operating system (issue 33): a full disk (a small tmpfs) does not make the idle reset
reload in a loop (the visitor's tree is kept in memory and said so, then written once there is room);
a read-only saves folder with a bad save still starts (the bad save only reported), in-process and as
the real `arbor --kiosk` under xvfb-run."""

import errno
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from arbor.game.screens.game import Game, GameConfig
from arbor.game.screens.kiosk import Kiosk, KioskConfig
from arbor.game.screens.saves import VisitorSaves
from tests.conftest import FakeClock

SIZE = (1280, 720)
ROOT = Path(__file__).resolve().parent.parent


@pytest.fixture
def disk(tmp_path):
    """A 2 MB tmpfs of our own (root only: skipped elsewhere), unmounted afterwards."""
    mount = tmp_path / "disk"
    mount.mkdir()
    if subprocess.run(["mount", "-t", "tmpfs", "-o", "size=2m", "tmpfs", str(mount)], capture_output=True).returncode:
        pytest.skip("needs to mount a small tmpfs (root)")
    try:
        yield mount
    finally:
        subprocess.run(["umount", "-l", str(mount)], capture_output=True)


def _fill(folder: Path) -> None:
    """Fill the disk up to its last byte."""
    fd = os.open(folder / "filler", os.O_WRONLY | os.O_CREAT)
    try:
        for chunk in (65536, 4096, 1):
            try:
                while True:
                    os.write(fd, b"\0" * chunk)
            except OSError as exc:
                assert exc.errno == errno.ENOSPC
    finally:
        os.close(fd)


def _kiosk(gl_ctx, folder: Path, clock: FakeClock) -> Kiosk:
    config = KioskConfig(attract_after=1e6, reset_after=30.0, care_after=1e6, speed=10.0)
    k = Kiosk(lambda: Game(gl_ctx, SIZE, GameConfig(saves=folder, seed=2, resume=True), clock=clock), config,
              folder, clock=clock)
    k.fbo = gl_ctx.framebuffer(color_attachments=[gl_ctx.renderbuffer(SIZE)],
                               depth_attachment=gl_ctx.depth_renderbuffer(SIZE))
    return k


def test_a_full_disk_does_not_make_the_idle_reset_loop(gl_ctx, disk, caplog):
    clock = FakeClock(50.0)
    folder = disk / "kiosk"
    kiosk = _kiosk(gl_ctx, folder, clock)
    kiosk.game.save()
    made = []
    real_make = kiosk.make_game
    kiosk.make_game = lambda: made.append(1) or real_make()  # every reload of the garden counted
    _fill(disk)
    clock.t += 31.0  # the visitor has gone
    assert kiosk.frame([], 1 / 60, kiosk.fbo)
    assert "could not be saved (No space left on device): 1 kept" in kiosk.game.state.message
    assert "could not save the visitor's tree (No space left on device): 1 kept in memory" in caplog.text
    for _ in range(200):
        clock.t += 1 / 60
        assert kiosk.frame([], 1 / 60, kiosk.fbo)
    assert kiosk.recoveries == 0 and made == []  # (it reloaded 399 times in 600 frames)
    assert len(kiosk.visitors.waiting) == 1 and not list(folder.glob("visitor-*.arbor"))
    (disk / "filler").unlink()  # room again: the next reset writes the kept tree and the new one
    kiosk._touched(None)
    clock.t += 31.0
    kiosk.frame([], 1 / 60, kiosk.fbo)
    assert kiosk.visitors.waiting == [] and len(list(folder.glob("visitor-*.arbor"))) == 2


def test_kept_visitor_trees_are_bounded(tmp_path, monkeypatch):
    from arbor.game.screens import saves

    def full(path, data):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(saves, "atomic_write", full)
    from arbor.engine.life.keep.save import SavedGarden
    from arbor.engine.life.rules.rules import load_rules
    from arbor.engine.life.world.world import World
    from arbor.engine.lsystem.lsys import load_lsystem

    world = World(load_lsystem("assets/lsystems/game_tree.lsys"), load_rules("assets/rules.toml"), seed=1)
    visitors = VisitorSaves(tmp_path)
    for _ in range(10):
        assert visitors.keep(SavedGarden([world])) == "No space left on device"
    assert len(visitors.waiting) == VisitorSaves.MAX_KEPT


def _read_only(disk: Path) -> None:
    if subprocess.run(["mount", "-o", "remount,ro", str(disk)], capture_output=True).returncode:
        pytest.skip("cannot remount read-only")


def test_a_read_only_folder_with_a_bad_save_still_starts(gl_ctx, disk):
    folder = disk / "kiosk"
    folder.mkdir()
    (folder / "autosave.arbor").write_text("format = 2\n[[trees]]\nbroken")
    _read_only(disk)
    clock = FakeClock(50.0)
    kiosk = _kiosk(gl_ctx, folder, clock)
    message = kiosk.game.state.message
    assert message.startswith("Could not load autosave.arbor") and "Read-only file system" in message
    for _ in range(30):
        clock.t += 1 / 60
        assert kiosk.frame([], 1 / 60, kiosk.fbo)
    assert kiosk.recoveries == 0 and (folder / "autosave.arbor").read_text().endswith("broken")


@pytest.mark.skipif(shutil.which("xvfb-run") is None, reason="needs xvfb-run (CI installs it)")
def test_the_real_kiosk_starts_on_a_read_only_folder_with_a_bad_save(disk):
    (disk / "kiosk").mkdir()
    (disk / "kiosk" / "autosave.arbor").write_text("not a save")
    _read_only(disk)
    env = dict(os.environ, SDL_VIDEODRIVER="x11", SDL_AUDIODRIVER="dummy", ARBOR_MAX_FRAMES="20")
    proc = subprocess.run(["xvfb-run", "-a", sys.executable, "-m", "arbor.game.cli", "--kiosk", "--windowed",
                           "--saves", str(disk)], env=env, cwd=ROOT, capture_output=True, text=True, timeout=180)
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert "Traceback" not in proc.stderr and "Read-only file system" in proc.stderr  # the log, on stderr
    assert (disk / "kiosk" / "autosave.arbor").read_text() == "not a save"


def test_a_start_that_hangs_has_its_garden_moved_aside_by_the_watchdog(tmp_path):
    """Each start hangs before its first heartbeat for longer than a young crash (60 s of the watchdog's
    clock, run 100 times fast here): after three the garden is moved aside and the fourth start plays."""
    import time

    from arbor.game.watchdog import CRASH_LOOP, STAFF_EXIT, watch

    folder = tmp_path / "kiosk"
    folder.mkdir()
    (folder / "autosave.arbor").write_text("a save whose load hangs")
    counter = tmp_path / "runs"
    script = (f"import pathlib, sys, time; p = pathlib.Path({str(counter)!r}); n = int(p.read_text()) "
              f"if p.exists() else 0; p.write_text(str(n + 1))\n"
              f"save = pathlib.Path({str(folder)!r}) / 'autosave.arbor'\n"
              "if save.exists(): (pathlib.Path(__import__('os').environ['ARBOR_HEARTBEAT'] + '.reading')"
              ".write_text(str(save)), time.sleep(120))\n"  # loading it hangs, no heartbeat ever
              f"sys.exit({STAFF_EXIT})")
    status = watch([sys.executable, "-c", script], sleep=lambda s: None, clock=lambda: time.monotonic() * 100,
                   poll=0.02)
    assert status == STAFF_EXIT and counter.read_text() == str(CRASH_LOOP + 1)
    assert not (folder / "autosave.arbor").exists() and len(list(folder.glob("autosave.*crashed"))) == 1
