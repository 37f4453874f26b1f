"""The experiment builder (arbor lab FILE --build): a sweep set up with the mouse or a finger alone.

Rows of large buttons choose what varies (the schema's factors, each with its unit and the levels it may
take), its levels, the species, the seeds, the game days, the watering and the responses; Save writes
the sweep file (the same TOML a teacher writes by hand, with comments: engine/life/experiment/builder.py),
Run saves it and runs it beside the window (its progress shown: runs done of all), its tables and figures
going to results/NAME/. A file given that exists is opened to be changed.
"""

from __future__ import annotations

import math
import threading
import time
from collections.abc import Callable
from pathlib import Path

import moderngl
import pygame

from arbor.engine.base.errors import LSysError
from arbor.engine.life.experiment.builder import (
    FACTORS,
    MAX_DAYS,
    MAX_SEEDS,
    SPECIES,
    WATERING,
    Draft,
    NotBuildableError,
    draft_of,
)
from arbor.engine.life.experiment.sweep import differences, runs
from arbor.engine.life.experiment.sweep_file import load_sweep
from arbor.game.input.events import DOWN, InputEvent
from arbor.game.paths import ASSETS
from arbor.game.render.renderer import Overlay
from arbor.game.screens.stack import Screen, quit_asked

ROW_H, PAD, LEFT = 58, 10, 250  # pixels: a row of buttons, the gap between buttons, the labels' column
COUNT_EVERY = 0.5  # seconds between looks into a running sweep's runs folder (a glob of up to thousands of files)
INK, PAPER, ON, OFF = (245, 245, 240), (236, 236, 228), (70, 120, 60), (60, 66, 60)


class BuilderScreen(Screen):
    """Builds one sweep file by taps on buttons (see module docstring)."""

    def __init__(self, ctx: moderngl.Context | None, size: tuple[int, int], path: Path,
                 run_sweep: Callable[..., int], results: Path = Path("results"), workers: int | None = None) -> None:
        self.ctx, self.size, self.path, self.results, self.workers = ctx, size, path, results, workers
        self.run_sweep = run_sweep  # (game/commands/sweep.py's, given by the window: a screen runs no command)
        self.message = ""
        self.draft = Draft()
        if path.is_file():
            self.draft = reopen(path, self._day_seconds())
            self.message = f"Opened {path.name}"
        self.running: threading.Thread | None = None
        self.status: dict = {}
        pygame.font.init()
        self.font, self.small = pygame.font.Font(None, 34), pygame.font.Font(None, 28)
        self.overlay = Overlay(ctx, size) if ctx is not None else None
        self.surface = pygame.Surface(size, pygame.SRCALPHA)
        self.buttons: dict[tuple, pygame.Rect] = {}
        self._shown: tuple | None = None  # what the surface shows (redrawn only when that changes)
        self._counted = (-1.0, 0)  # (when, runs done) of the last look into the runs folder
        self._layout()

    @staticmethod
    def _day_seconds() -> float:
        """A game day at the demo pace (the builder's sweeps keep the lab's pace), in game seconds."""
        from arbor.engine.life.rules.rules import load_rules

        return 2 * math.pi / load_rules(ASSETS / "rules.toml", "demo").sun.speed

    # -- the buttons ------------------------------------------------------------------------------------
    def rows(self) -> list[tuple[str, list[tuple[tuple, str, bool]]]]:
        """Each row's label and its buttons: (what the button does, its words, whether it is chosen)."""
        d = self.draft
        unit = f" ({d.unit})" if d.unit else ""
        rows = [("What changes", [(("factor", -1), "<", False), (("factor", 0), f"{d.name}{unit}", True),
                                  (("factor", 1), ">", False)]),
                ("Its levels", [(("level", v), _words(v), v in d.levels) for v in d.ladders[d.factor]])]
        if d.factor != "species":
            rows.append(("Species", [(("species", s), s.removesuffix(".lsys"), s == d.species) for s in SPECIES]))
        rows += [("Seeds per level", [(("seeds", -1), "-", False), (("seeds", 0), str(d.seeds), True),
                                      (("seeds", 1), "+", False)]),
                 ("Game days", [(("days", -1), "-", False), (("days", 0), str(d.days), True),
                                (("days", 1), "+", False)])]
        if not d.factor.startswith("watering."):
            rows.append(("Watering", [(("water", w), w, w == d.watering) for w in WATERING]))
        half = (len(d.offered) + 1) // 2
        rows += [("Measure", [(("response", r), r, r in d.responses) for r in d.offered[:half]]),
                 ("", [(("response", r), r, r in d.responses) for r in d.offered[half:]]),
                 ("", [(("save",), "Save", False), (("run",), "Run", False)])]
        return rows

    def _layout(self) -> None:
        """Where each button is (rows from the top, buttons as wide as their words)."""
        self.buttons = {}
        y = 70
        for _, buttons in self.rows():
            x = LEFT
            for action, words, _ in buttons:
                width = max(56, self.small.size(words)[0] + 28)
                if x + width > self.size[0] - PAD:
                    x, y = LEFT, y + ROW_H
                self.buttons[action] = pygame.Rect(x, y, width, ROW_H - PAD)
                x += width + PAD
            y += ROW_H

    def press(self, action: tuple) -> None:
        """What a button does."""
        d = self.draft
        kind = action[0]
        if kind == "factor" and action[1]:
            keys = list(FACTORS)
            d.choose_factor(keys[(keys.index(d.factor) + action[1]) % len(keys)])
        elif kind == "level":
            d.toggle_level(action[1])
        elif kind == "species":
            d.species = action[1]
        elif kind == "seeds":
            d.seeds = min(MAX_SEEDS, max(1, d.seeds + action[1] * (1 if d.seeds < 10 else 5)))
        elif kind == "days":
            d.days = min(MAX_DAYS, max(1, d.days + action[1] * (1 if d.days < 10 else 5)))
        elif kind == "water":
            d.watering = action[1]
        elif kind == "response":
            d.toggle_response(action[1])
        elif kind in ("save", "run"):
            try:
                (self.save if kind == "save" else self.run)()
            except (LSysError, OSError) as exc:  # (a folder gone or read-only: the draft stays, the reason shows)
                self.message = f"Not saved: {getattr(exc, 'strerror', None) or exc}; the experiment is still here"
        self._layout()

    def save(self) -> Path:
        """Write the sweep file (read back at once: what is saved is what runs)."""
        from arbor.engine.base.files import atomic_write

        atomic_write(self.path, self.draft.toml(self._day_seconds()).encode("utf-8"))
        load_sweep(self.path, ASSETS / "lsystems")  # (valid by construction; a bug here is not a teacher's)
        self.message = f"Saved {self.path}"
        return self.path

    def run(self) -> None:
        """Save, then run the sweep beside the window (tables and figures in results/NAME/)."""
        if self.running is not None and self.running.is_alive():
            self.message = "A run is going on: wait for it to end"
            return
        self.save()
        sweep = load_sweep(self.path, ASSETS / "lsystems")
        out = self.results / self.path.stem
        self.status = {"out": out, "total": len(runs(sweep)), "said": [], "status": None}

        def work() -> None:
            try:
                self.status["status"] = self.run_sweep(self.path, out, self.workers, echo=self.status["said"].append,
                                                       keep="first")
            except Exception as exc:  # (whatever ends the run, the window says so and goes on)
                self.status["said"].append(str(exc) or type(exc).__name__)
                self.status["status"] = 1

        self.running = threading.Thread(target=work, daemon=True)
        self.running.start()

    def progress(self) -> str:
        """The run's progress in words ("" before any run)."""
        if not self.status:
            return ""
        out, total = self.status["out"], self.status["total"]
        if time.monotonic() - self._counted[0] > COUNT_EVERY:
            done = len(list((out / "runs").glob("run*.csv"))) if (out / "runs").is_dir() else 0
            self._counted = (time.monotonic(), done)
        done = self._counted[1]
        if self.status["status"] is None:
            return f"Running: {done} of {total} runs done"
        if self.status["status"] == 0:
            return f"Done: {total} runs; tables and figures in {out}"
        return f"Stopped: {(self.status['said'] or ['see the terminal'])[-1]}"

    # -- the screen -------------------------------------------------------------------------------------
    def handle(self, e: InputEvent) -> InputEvent | None:
        """Taps on the buttons; a quit (the window's close, or Esc) is left over."""
        if (asked := quit_asked(e)) is not None:
            return asked
        if e.kind == DOWN and e.dims == 2:
            for action, rect in list(self.buttons.items()):
                if rect.collidepoint(e.x, e.y):
                    self.press(action)
                    break
        return None

    def draw(self, fbo: moderngl.Framebuffer) -> None:
        """The rows of buttons, the file's name and what happened last."""
        fbo.use()
        fbo.clear(*(c / 255 for c in PAPER), 1.0)
        shown = (tuple(self.rows()), self.message, self.progress())
        if shown != self._shown:
            self.picture()
        self.overlay.draw_surface(self.surface, shown != self._shown)
        self._shown = shown

    def picture(self) -> pygame.Surface:
        """The builder drawn on its surface (what draw shows)."""
        s = self.surface
        s.fill((*PAPER, 255))
        s.blit(self.font.render(f"Experiment builder: {self.path.name}", True, (30, 30, 30)), (PAD * 2, 20))
        y = 70
        for (label, buttons) in self.rows():
            first = self.buttons[buttons[0][0]]
            if label:
                s.blit(self.font.render(label, True, (40, 40, 40)), (PAD * 2, first.y + 12))
            for action, words, chosen in buttons:
                rect = self.buttons[action]
                pygame.draw.rect(s, (*(ON if chosen else OFF), 255), rect, border_radius=10)
                text = self.small.render(words, True, INK)
                s.blit(text, text.get_rect(center=rect.center))
            y = max(y, first.bottom)
        lines = [self.message, self.progress()]
        for k, line in enumerate(x for x in lines if x):
            s.blit(self.small.render(line, True, (30, 30, 30)), (PAD * 2, self.size[1] - 70 + 32 * k))
        return s


def reopen(path: Path, day_seconds: float) -> Draft:
    """The draft of an existing sweep file, if the builder would write a file that runs the same experiment
    (else NotBuildableError naming what it would change: such a file is edited as text)."""
    import tempfile

    before = load_sweep(path, ASSETS / "lsystems")
    draft = draft_of(before, day_seconds)
    with tempfile.TemporaryDirectory() as folder:
        again = Path(folder) / path.name
        again.write_text(draft.toml(day_seconds), encoding="utf-8")
        differ = differences(before, load_sweep(again, ASSETS / "lsystems"), within=0.01)  # (it rounds to days)
    if differ:
        raise NotBuildableError(f"the builder cannot keep its {', '.join(differ)} as written: edit it in a text "
                                "editor")
    return draft


def _words(level) -> str:
    return level.removesuffix(".lsys") if isinstance(level, str) else f"{level:g}"
