"""One saves folder, one Arbor (issue 33): a second `arbor` on a folder another live process holds ends
in one line naming that process (exit 1); a lock left by a process that died is taken over, so the
watchdog's restart of a killed kiosk still starts."""

import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from arbor.engine.base.files import LOCK_NAME, FolderBusyError, FolderLock
from arbor.game import watchdog

ROOT = Path(__file__).resolve().parent.parent
HOLD = ("import sys, time\nfrom arbor.engine.base.files import FolderLock\n"
        "FolderLock(sys.argv[1]).acquire()\nprint('held', flush=True)\ntime.sleep(120)\n")


def _holder(folder: Path) -> subprocess.Popen:
    """Another process holding ``folder``'s lock (until killed)."""
    proc = subprocess.Popen([sys.executable, "-c", HOLD, str(folder)], stdout=subprocess.PIPE, text=True)
    assert proc.stdout.readline().strip() == "held"
    return proc


def _arbor(*args: str) -> subprocess.CompletedProcess:
    env = dict(os.environ, SDL_VIDEODRIVER="dummy", SDL_AUDIODRIVER="dummy")
    return subprocess.run([sys.executable, "-m", "arbor.game.cli", *args], env=env, cwd=ROOT, capture_output=True,
                          text=True, timeout=120)


def test_a_second_arbor_on_a_held_folder_says_who_holds_it(tmp_path):
    saves = tmp_path / "saves"
    holder = _holder(saves)
    kiosk_holder = _holder(saves / "kiosk")
    try:
        for args, folder, pid in ((["--saves", str(saves)], saves, holder.pid),
                                  (["--kiosk", "--saves", str(saves)], saves / "kiosk", kiosk_holder.pid)):
            second = _arbor(*args)
            assert second.returncode == 1
            assert second.stderr.strip().splitlines() == [
                f"arbor: the saves folder {folder} is in use by another Arbor (pid {pid}): close that one first, "
                "or start this one with --saves ANOTHER_FOLDER"]
        assert (saves / LOCK_NAME).read_text().strip() == str(holder.pid)
    finally:
        holder.kill()
        kiosk_holder.kill()
        holder.wait()
        kiosk_holder.wait()


def test_a_lock_left_by_a_dead_process_is_taken_over(tmp_path):
    holder = _holder(tmp_path)
    with pytest.raises(FolderBusyError) as busy:
        FolderLock(tmp_path).acquire()
    assert busy.value.pid == holder.pid
    holder.send_signal(signal.SIGKILL)  # as the watchdog kills a hung kiosk: no chance to clean up
    holder.wait()
    assert (tmp_path / LOCK_NAME).read_text().strip() == str(holder.pid)  # stale: a dead pid in the file
    lock = FolderLock(tmp_path).acquire()
    assert lock.held and (tmp_path / LOCK_NAME).read_text().strip() == str(os.getpid())
    lock.release()


def test_a_read_only_folder_is_not_locked_and_does_not_stop_the_start(tmp_path, monkeypatch):
    import errno

    def read_only(*args, **kwargs):
        raise OSError(errno.EROFS, os.strerror(errno.EROFS))

    monkeypatch.setattr(os, "open", read_only)
    lock = FolderLock(tmp_path).acquire()
    assert not lock.held


def test_the_watchdog_restart_takes_over_the_lock_of_the_child_it_killed(tmp_path):
    """The first run holds the lock and hangs (no heartbeat): the watchdog kills it; the restarted child
    gets the lock and quits as staff would."""
    runs = tmp_path / "runs"
    child = tmp_path / "child.py"
    child.write_text("import sys, time\nfrom pathlib import Path\nfrom arbor.engine.base.files import FolderLock\n"
                     f"runs = Path({str(runs)!r})\nn = int(runs.read_text()) if runs.exists() else 0\n"
                     "runs.write_text(str(n + 1))\n"
                     f"FolderLock({str(tmp_path / 'saves')!r}).acquire()\n"
                     f"if n == 0:\n    time.sleep(120)\nsys.exit({watchdog.STAFF_EXIT})\n")
    status = watchdog.watch([sys.executable, str(child)], sleep=lambda s: None, poll=0.1, hang=1.0, grace=1.0,
                            max_restarts=3)
    assert status == watchdog.STAFF_EXIT and runs.read_text() == "2"


@pytest.mark.skipif(shutil.which("xvfb-run") is None, reason="needs xvfb-run (CI installs it)")
def test_two_real_games_on_one_folder(tmp_path):
    saves = tmp_path / "saves"
    env = dict(os.environ, SDL_VIDEODRIVER="x11", SDL_AUDIODRIVER="dummy", ARBOR_HEARTBEAT=str(tmp_path / "beat"),
               ARBOR_TIMING="1")
    err = tmp_path / "stderr"
    first = subprocess.Popen(["xvfb-run", "-a", sys.executable, "-m", "arbor.game.cli", "--saves", str(saves)],
                             env=env, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=err.open("wb"))
    try:
        deadline = time.monotonic() + 150
        while b"arbor-timing garden" not in err.read_bytes():  # the first game is playing (its first frame)
            assert first.poll() is None and time.monotonic() < deadline, err.read_text()[-2000:]
            time.sleep(0.2)
        pid = int((saves / LOCK_NAME).read_text())
        second = _arbor("--saves", str(saves))
        assert second.returncode == 1 and len(second.stderr.strip().splitlines()) == 1
        assert f"is in use by another Arbor (pid {pid})" in second.stderr
        os.kill(pid, signal.SIGTERM)
        assert first.wait(timeout=30) == 0
    finally:
        if first.poll() is None:
            first.kill()
    assert (saves / "autosave.arbor").exists()


def test_a_lock_given_up_leaves_no_file_and_a_failed_start_none_either(tmp_path):
    """release() removes the lock file (holding it while it does); a start that found no display, which
    ends before the game could release it, removes it at exit; only a killed holder's file stays behind."""
    lock = FolderLock(tmp_path).acquire()
    assert (tmp_path / LOCK_NAME).is_file()
    lock.release()
    assert not (tmp_path / LOCK_NAME).exists()
    again = FolderLock(tmp_path).acquire()  # taken again at once: the next one makes a new file
    assert again.held
    again.release()
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY", "SDL_VIDEODRIVER")}
    saves = tmp_path / "saves"
    run = subprocess.run([sys.executable, "-m", "arbor.game.cli", "--saves", str(saves)], env=env, cwd=ROOT,
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 1 and "no display" in run.stderr
    assert saves.is_dir() and not (saves / LOCK_NAME).exists()


def test_a_lock_file_removed_between_open_and_lock_is_not_trusted(tmp_path, monkeypatch):
    """A holder releasing (removing its file) just after we opened it: we hold the new file, not the old."""
    import fcntl

    real, calls = fcntl.flock, []

    def flock(fd, how):
        if not calls:  # the first time: the file we opened is removed and another made, as a release does
            (tmp_path / LOCK_NAME).unlink()
            (tmp_path / LOCK_NAME).write_text("")
        calls.append(fd)
        return real(fd, how)

    monkeypatch.setattr(fcntl, "flock", flock)
    lock = FolderLock(tmp_path).acquire()
    assert len(calls) == 2 and os.fstat(lock.fd).st_ino == os.stat(tmp_path / LOCK_NAME).st_ino
    lock.release()
