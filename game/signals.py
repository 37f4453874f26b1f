"""Stop signals: Ctrl-C (SIGINT), SIGTERM (what an operating system sends at shutdown, a service manager at
stop) and SIGHUP (the terminal closed) end a window's loop at the next frame, so the window saves the
garden as it does on a normal quit and exits 0, instead of a traceback and a lost minute of play.

Handlers set a flag and nothing else (Python runs them between bytecodes, so they never interrupt a
save halfway). They are installed after the window opened: SDL installs its own SIGTERM handler, which
turns the signal into a window-close event, and the kiosk ignores window-close from visitors.
"""

from __future__ import annotations

import signal

STOP_SIGNALS = tuple(getattr(signal, name) for name in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, name))


class StopSignals:
    """While entered, the stop signals only set :attr:`received` (the first one's number), or, while
    :attr:`leave_at_once` is set, end the process with status 0 at once; leaving puts the handlers that
    were there back."""

    def __init__(self) -> None:
        self.received: int | None = None
        self.leave_at_once = False  # True while there is nothing to save (a screen being built): exit at once
        self._old: dict[int, object] = {}

    def _handle(self, signum: int, frame) -> None:
        if self.received is None:
            self.received = signum
        if self.leave_at_once:  # (a lab or a viewer compiling or growing its trees: nothing is lost)
            raise SystemExit(0)

    def __enter__(self) -> StopSignals:
        for sig in STOP_SIGNALS:
            try:
                self._old[sig] = signal.signal(sig, self._handle)
            except ValueError:  # not the main thread (a test harness): signals stay as they are
                break
        return self

    def __exit__(self, *exc) -> None:
        for sig, old in self._old.items():
            signal.signal(sig, old)
        self._old.clear()

    @property
    def stop(self) -> bool:
        """True once a stop signal arrived."""
        return self.received is not None
