"""Progress of a long headless command (a first start's compile, a render, an export, a landscape, a
derivation): a tqdm bar with its estimate of the time left on a terminal, one line per stage when the
output is piped or logged (a bar's carriage returns would fill a log), nothing under ``--quiet``.

A command that may pass 2 s opens a ``Progress`` over its measured work (seconds, modules, trees) and moves
it with ``to(done, stage)``; a command that ends sooner than ``QUIET_SECONDS`` shows nothing at all."""

from __future__ import annotations

import sys
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from typing import TextIO

from arbor.game import report

QUIET_SECONDS = 2.0  # a bar appears only once the work has taken this long (short commands stay one line)

# Seconds of work per unit, measured on 2 shared cores at load 8 (abop_2_8_tree at n 8-9, abop_1_24a at n 6-7,
# abop_2_6_monopodial at n 16, --lod 0): what a stage that is one call (numba, trimesh, GL) is expected to take.
MESH_PER_MODULE = 5e-6  # the turtle and the mesher (1-8 us a module)
TRIANGLES_PER_MODULE = 15  # (12.7 and 22 triangles a module at --lod 0)
PER_TRIANGLE = {"glb": 1.8e-6, "obj": 6e-6, "png": 7e-6}  # writing a GLB or OBJ, rendering and saving a PNG


class Progress:
    """A progress report on ``stream`` (stderr by default, so stdout keeps only a command's product)."""

    def __init__(self, what: str, total: float, unit: str = "", stream: TextIO | None = None,
                 tty: bool | None = None) -> None:
        self.what, self.total, self.unit = what, max(float(total), 1e-9), unit
        self.stream = stream or sys.stderr
        self.tty = self.stream.isatty() if tty is None else tty
        self.started = time.perf_counter()
        self.done, self.stage = 0.0, ""
        self._bar = None
        self._said = ""  # the last stage given a line when piped
        self._ended = False  # that line said 100 % done

    def __enter__(self) -> Progress:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def left(self) -> float | None:
        """Seconds still to go at the pace so far (None before any work is done)."""
        if self.done <= 0:
            return None
        return (time.perf_counter() - self.started) * (self.total - self.done) / self.done

    def line(self) -> str:
        """The piped form: what, the stage, the share done and the estimate of the time left."""
        left = self.left()
        estimate = f", about {left:.0f} s left" if left is not None and self.done < self.total else ""
        stage = f": {self.stage}" if self.stage else ""
        return f"arbor: {self.what}{stage} ({100 * self.done / self.total:.0f} % done{estimate})"

    def to(self, done: float, stage: str = "", total: float | None = None) -> None:
        """Move to ``done`` of ``total`` (now at ``stage``, when the work has named stages; ``total`` anew
        when the estimate of the whole changed)."""
        if total is not None:
            self.total = max(float(total), float(done), 1e-9)
            if self._bar is not None:
                self._bar.total = self.total
        self.done, self.stage = min(float(done), self.total), stage or self.stage
        if report.level < report.NORMAL or (time.perf_counter() - self.started < QUIET_SECONDS and self._bar is None \
                and not self._said):
            return
        if self.tty:
            bar = self._tqdm()
            bar.update(self.done - bar.n)
            left = self.left()
            about = f"{self.stage}, about {left:.0f} s left" if left is not None else self.stage
            bar.set_postfix_str(about, refresh=stage != self._said)  # a new stage is shown at once
            self._said = stage or self._said
        elif self.stage != self._said:
            self._said = self.stage
            self._ended = self.done >= self.total
            print(self.line(), file=self.stream, flush=True)

    def _tqdm(self):
        if self._bar is None:
            from tqdm import tqdm

            tqdm.monitor_interval = 0  # no monitor thread (a sweep's pool may fork after)
            self._bar = tqdm(total=self.total, desc=self.what, unit=self.unit or "it", file=self.stream,
                             mininterval=0.3, dynamic_ncols=True, leave=False,
                             bar_format="{desc}: {percentage:3.0f}%|{bar}| {elapsed}{postfix}")
        return self._bar

    @contextmanager
    def timed(self, stage: str, seconds: float) -> Iterator[None]:
        """A stage that is one long call expected to take ``seconds`` (the work's total counts them): the
        progress moves with the clock meanwhile, up to nine tenths of the stage until it ends."""
        start, base = time.perf_counter(), self.done
        ended = threading.Event()

        def tick() -> None:
            while not ended.wait(0.25):
                self.to(base + min(time.perf_counter() - start, 0.9 * seconds), stage)

        self.to(base, stage)
        ticker = threading.Thread(target=tick, name="arbor-progress", daemon=True)
        ticker.start()
        try:
            yield
        finally:
            ended.set()
            ticker.join()
        spent = time.perf_counter() - start  # the stage's real length replaces its estimate in the total
        self.to(base + spent, stage, total=self.total - seconds + spent)

    def close(self) -> None:
        """End the bar (a terminal's bar is cleared: the command's own report line follows); piped, a last
        line says the work is done."""
        if self._said and not self._ended and not self.tty and report.level >= report.NORMAL:
            self.done = self.total
            print(self.line(), file=self.stream, flush=True)
            self._said = ""
        if self._bar is not None:
            self._bar.close()
            self._bar = None
