"""A watchdog for kiosks: run Arbor in a child process and start it again whenever it dies.

`arbor watchdog --kiosk` keeps `arbor --kiosk` running. A clean exit (status 0: staff quit with the
PIN) ends the watchdog; anything else restarts the app after a short pause that grows while crashes
come quickly (1 s, 2 s, 4 s, ... at most 30 s) and shrinks back after a good long run.
"""

from __future__ import annotations

import logging
import subprocess
import sys
import time
from collections.abc import Callable

log = logging.getLogger("arbor.watchdog")


def watch(command: list[str], sleep: Callable[[float], None] = time.sleep, clock=time.monotonic,
          max_restarts: int | None = None) -> int:
    """Run ``command`` until it exits with status 0; restart it otherwise. Returns the last status."""
    delay, restarts = 1.0, 0
    while True:
        started = clock()
        status = subprocess.call(command)
        if status == 0:
            return 0
        restarts += 1
        log.error("arbor exited with status %s; restart #%d in %.0f s", status, restarts, delay)
        if max_restarts is not None and restarts > max_restarts:
            return status
        sleep(delay)
        delay = 1.0 if clock() - started > 60 else min(delay * 2, 30.0)


def main(args: list[str]) -> int:
    """`arbor watchdog ARGS...`: keep `arbor ARGS...` alive."""
    logging.basicConfig(level=logging.INFO)
    return watch([sys.executable, "-m", "game.cli", *args])
