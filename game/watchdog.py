"""A watchdog for kiosks: run Arbor in a child process and start it again whenever it dies or hangs.

`arbor watchdog --kiosk` keeps `arbor --kiosk` running:

* the child exits with STAFF_EXIT only when staff entered the PIN: then the watchdog stops too, and so it
  does when the child refused its arguments (USAGE_EXIT: restarting would only repeat the refusal) and for
  `arbor watchdog --help` / `--version` (run once), and for a clean quit (status 0) of anything but the kiosk
  (whose app never quits by itself: a 0 there means it alone was stopped, so it is restarted); any other
  end (a crash, a kill, a hang) is restarted after a pause that grows while crashes come quickly (1 s,
  2 s, 4 s, ... at most 30 s) and shrinks back after a good long run;
* the child touches a heartbeat file (``ARBOR_HEARTBEAT``) every second; if it stays silent for
  HANG_SECONDS it is killed and restarted (a hung app is never left on screen);
* the child notes which of the user's files it is reading at start (:func:`reading`: settings.toml,
  kiosk.toml, the saved garden) beside its heartbeat, and clears the note once the file was read;
* when the child dies young CRASH_LOOP times in a row, the file it was reading when it last died is set
  aside (``NAME.crashed``) and the log says which: a file that crashes the start must not keep the kiosk in
  a restart loop, and a save that loads is never the one set aside; a child killed as hung before its
  first heartbeat (a start that hangs, however long it took) counts as young. The child beats from its
  first-start screen on, while the kernels compile, so a slow first start is not taken for a hang;
* SIGTERM, SIGINT or SIGHUP to the watchdog (a shutdown) is passed on to the child, which saves and
  exits, and the watchdog stops.
"""

from __future__ import annotations

import contextlib
import logging
import os
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Iterator
from pathlib import Path

from arbor.engine.base.errors import LSysError
from arbor.engine.base.files import set_aside
from arbor.game.errors import UserError
from arbor.game.signals import StopSignals

log = logging.getLogger("arbor.watchdog")
STAFF_EXIT = 3  # staff quit with the PIN: the watchdog stops
USAGE_EXIT = 2  # the child refused its arguments (argparse): the watchdog stops, a restart would repeat it
ONCE = ("-h", "--help", "--version")  # arguments that only print: the child runs once
HANG_SECONDS = 30.0  # no heartbeat for this long (after the start-up grace) = hung
START_GRACE = 300.0  # seconds a starting app may take before its first heartbeat (the window's first frame:
# a loaded machine took 83-188 s to get there; the first-start screen beats while the kernels compile)
YOUNG = 20.0  # a run shorter than this counts as a crash at start
CRASH_LOOP = 3  # young crashes in a row before the saved garden is moved aside
PASS_ON_SECONDS = 10.0  # after passing a stop signal on, the child is killed if it has not exited by then


HUNG_AT_START = -10  # _run_once's status for a child killed as hung before it ever beat (a start that hangs)


def _run_once(command: list[str], heartbeat: Path, clock, poll: float, hang: float, grace: float,
              signals: StopSignals | None = None) -> int:
    """Run the child until it exits or its heartbeat stops for ``hang`` seconds (``grace`` seconds are
    allowed before the first beat); returns its status (-9 when killed as hung, HUNG_AT_START when it
    never beat at all). A stop signal to the watchdog is passed on to the child, which saves and exits
    (killed after PASS_ON_SECONDS)."""
    heartbeat.unlink(missing_ok=True)
    _note(heartbeat).unlink(missing_ok=True)
    started = clock()
    child = subprocess.Popen(command, env=dict(os.environ, ARBOR_HEARTBEAT=str(heartbeat)))
    while True:
        try:
            return child.wait(timeout=poll)
        except subprocess.TimeoutExpired:
            pass
        if signals is not None and signals.stop:
            log.info("signal %d: passing it on to arbor and stopping", signals.received)
            child.send_signal(signals.received)
            try:
                return child.wait(timeout=PASS_ON_SECONDS)
            except subprocess.TimeoutExpired:
                child.kill()
                return child.wait()
        beat = heartbeat.stat().st_mtime if heartbeat.exists() else None
        silent = time.time() - beat if beat is not None else clock() - started - grace + hang
        if silent > hang:
            log.error("arbor stopped answering (no heartbeat for %.0f s%s): killing it", silent,
                      "" if beat is not None else ", none since it started")
            child.kill()
            child.wait()
            return -9 if beat is not None else HUNG_AT_START


def watch(command: list[str], sleep: Callable[[float], None] = time.sleep, clock=time.monotonic,
          max_restarts: int | None = None, poll: float = 1.0,
          hang: float = HANG_SECONDS, grace: float = START_GRACE, restart_clean: bool = True) -> int:
    """Run ``command`` until it exits with STAFF_EXIT; restart it otherwise (also when it hangs).
    After CRASH_LOOP young deaths the file the child was reading is set aside. ``restart_clean``:
    whether a clean quit (status 0) is restarted too (the kiosk) or ends the watch. Returns the last
    status."""
    delay, restarts, young = 1.0, 0, 0
    with tempfile.TemporaryDirectory(prefix="arbor-watchdog-") as tmp, StopSignals() as signals:
        heartbeat = Path(tmp) / "heartbeat"
        while not signals.stop:
            started = clock()
            status = _run_once(command, heartbeat, clock, poll, hang, grace, signals)
            if signals.stop:  # SIGTERM at shutdown: the child had it too; nothing is restarted
                return status
            if status == STAFF_EXIT:
                log.info("staff quit the kiosk: the watchdog stops")
                return status
            if status == 0 and not restart_clean:
                log.info("arbor quit cleanly: the watchdog stops")
                return status
            if status == USAGE_EXIT:
                log.error("arbor refused its arguments (status %d): the watchdog stops", status)
                return status
            lived = clock() - started
            young = young + 1 if lived < YOUNG or status == HUNG_AT_START else 0
            if young >= CRASH_LOOP:
                _set_culprit_aside(heartbeat)
                young = 0
            restarts += 1
            log.error("arbor exited with status %s after %.0f s; restart #%d in %.0f s", status, lived, restarts, delay)
            if max_restarts is not None and restarts > max_restarts:
                return status
            sleep(delay)
            delay = 1.0 if lived > 60 else min(delay * 2, 30.0)
        return 0


def _note(heartbeat: Path) -> Path:
    """The file beside the heartbeat where the child notes the user's file it is reading."""
    return heartbeat.with_name(heartbeat.name + ".reading")


@contextlib.contextmanager
def reading(path: str | Path) -> Iterator[None]:
    """While the body runs, note (for a watchdog, when one runs this process) that the user's file
    ``path`` is being read; the note is cleared when the body finished or refused the file in one clear
    line (an LSysError, UserError or OSError: the caller says so and goes on). Any other exception leaves
    it (the process may die of it; the window's first frame clears it, :func:`started`), so a crash or a
    hang while reading leaves it, and a crash loop sets that file aside, not another."""
    beat = os.environ.get("ARBOR_HEARTBEAT")
    note = _note(Path(beat)) if beat else None
    if note is not None:
        with contextlib.suppress(OSError):
            note.write_text(str(Path(path).absolute()), encoding="utf-8")
    try:
        yield
    except (LSysError, UserError, OSError):
        _clear(note)
        raise
    _clear(note)


def _clear(note: Path | None) -> None:
    if note is not None:
        with contextlib.suppress(OSError):
            note.unlink(missing_ok=True)


def started() -> None:
    """The start is over (the first frame is shown): no file read at start is to blame for what follows."""
    beat = os.environ.get("ARBOR_HEARTBEAT")
    if beat:
        with contextlib.suppress(OSError):
            _note(Path(beat)).unlink(missing_ok=True)


def _set_culprit_aside(heartbeat: Path) -> Path | None:
    """After a crash loop: set aside (``NAME.crashed``) the file the child was reading when it last died,
    and say which; returns where it went (None when the child was not reading a file: nothing is moved,
    so a garden that loads is never set aside for another file's fault)."""
    try:
        culprit = Path(_note(heartbeat).read_text(encoding="utf-8").strip())
    except (OSError, UnicodeDecodeError):
        log.error("arbor keeps crashing at start, not while reading a file: nothing set aside (see above)")
        return None
    try:
        kept = set_aside(culprit, ".crashed")
    except OSError as exc:
        log.error("arbor keeps crashing at start while reading %s, which cannot be set aside (%s)", culprit,
                  exc.strerror or exc)
        return None
    log.error("arbor keeps crashing at start while reading %s: set it aside as %s", culprit, kept.name)
    return kept


def main(args: list[str]) -> int:
    """`arbor watchdog ARGS...`: keep `arbor ARGS...` alive. Returns the status the watchdog stopped on:
    STAFF_EXIT, USAGE_EXIT, or the child's own for --help / --version."""
    logging.basicConfig(level=logging.INFO)
    command = [sys.executable, "-m", "arbor.game.cli", *args]
    if any(arg in ONCE for arg in args):
        return subprocess.call(command)
    return watch(command, restart_clean="--kiosk" in args)
