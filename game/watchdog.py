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
* when the child dies young CRASH_LOOP times in a row, the kiosk's saved garden is moved aside
  (``*.crashed``): a save that crashes the start must not keep the kiosk in a restart loop; a child
  killed as hung before its first heartbeat (a start that hangs, however long it took) counts as young;
* SIGTERM, SIGINT or SIGHUP to the watchdog (a shutdown) is passed on to the child, which saves and
  exits, and the watchdog stops.
"""

from __future__ import annotations

import logging
import os
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

from arbor.game.signals import StopSignals

log = logging.getLogger("arbor.watchdog")
STAFF_EXIT = 3  # staff quit with the PIN: the watchdog stops
USAGE_EXIT = 2  # the child refused its arguments (argparse): the watchdog stops, a restart would repeat it
ONCE = ("-h", "--help", "--version")  # arguments that only print: the child runs once
HANG_SECONDS = 30.0  # no heartbeat for this long (after the start-up grace) = hung
START_GRACE = 60.0  # seconds a starting app may take before its first heartbeat
YOUNG = 20.0  # a run shorter than this counts as a crash at start
CRASH_LOOP = 3  # young crashes in a row before the saved garden is moved aside
PASS_ON_SECONDS = 10.0  # after passing a stop signal on, the child is killed if it has not exited by then


def _saves_folder(args: list[str]) -> Path:
    """The kiosk's save folder the child will use (``--saves DIR``, ARBOR_SAVES, else the default)."""
    from arbor.game.paths import default_saves

    saves = os.environ.get("ARBOR_SAVES")
    for i, arg in enumerate(args):
        if arg == "--saves" and i + 1 < len(args):
            saves = args[i + 1]
        elif arg.startswith("--saves="):
            saves = arg.split("=", 1)[1]
    return (Path(saves) if saves else default_saves()) / "kiosk"


HUNG_AT_START = -10  # _run_once's status for a child killed as hung before it ever beat (a start that hangs)


def _run_once(command: list[str], heartbeat: Path, clock, poll: float, hang: float, grace: float,
              signals: StopSignals | None = None) -> int:
    """Run the child until it exits or its heartbeat stops for ``hang`` seconds (``grace`` seconds are
    allowed before the first beat); returns its status (-9 when killed as hung, HUNG_AT_START when it
    never beat at all). A stop signal to the watchdog is passed on to the child, which saves and exits
    (killed after PASS_ON_SECONDS)."""
    heartbeat.unlink(missing_ok=True)
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
          max_restarts: int | None = None, saves: Path | None = None, poll: float = 1.0,
          hang: float = HANG_SECONDS, grace: float = START_GRACE, restart_clean: bool = True) -> int:
    """Run ``command`` until it exits with STAFF_EXIT; restart it otherwise (also when it hangs).
    ``saves``: the kiosk's folder, whose garden is moved aside after a crash loop. ``restart_clean``:
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
            if young >= CRASH_LOOP and saves is not None:
                _move_garden_aside(saves)
                young = 0
            restarts += 1
            log.error("arbor exited with status %s after %.0f s; restart #%d in %.0f s", status, lived, restarts, delay)
            if max_restarts is not None and restarts > max_restarts:
                return status
            sleep(delay)
            delay = 1.0 if lived > 60 else min(delay * 2, 30.0)
        return 0


def _move_garden_aside(folder: Path) -> None:
    """Keep the kiosk's saved garden as *.crashed so the next start plants a fresh one."""
    save = folder / "autosave.arbor"
    if save.exists():
        kept = save.with_name(f"autosave.{int(time.time())}.crashed")
        save.replace(kept)
        log.error("arbor keeps crashing at start: moved %s aside as %s", save.name, kept.name)


def main(args: list[str]) -> int:
    """`arbor watchdog ARGS...`: keep `arbor ARGS...` alive. Returns the status the watchdog stopped on:
    STAFF_EXIT, USAGE_EXIT, or the child's own for --help / --version."""
    logging.basicConfig(level=logging.INFO)
    command = [sys.executable, "-m", "arbor.game.cli", *args]
    if any(arg in ONCE for arg in args):
        return subprocess.call(command)
    return watch(command, saves=_saves_folder(args), restart_clean="--kiosk" in args)
