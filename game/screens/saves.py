"""The game's save policy: resume the garden at start, autosave every minute and on quit, keep broken saves.

The whole garden is one file (``autosave.arbor``), written atomically. A save that cannot be read is
renamed to ``*.broken`` (never deleted) and a new tree is planted; time the player was away is lived
by the garden on load, in a bounded number of steps; a clock that went backwards (or cannot be read)
counts as no time away. Saves from before gardens were one file (``garden-*.arbor`` beside the
autosave) are read once and folded into the autosave; those beyond the garden's size are moved, unread,
into ``older-trees/`` beside it (and the player is told), never deleted.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable
from pathlib import Path

from arbor.engine.base.errors import LSysError
from arbor.engine.base.files import atomic_write, remove_stale_temp_files, set_aside
from arbor.engine.life.keep.away import AwaySummary, away_seconds, live_away
from arbor.engine.life.keep.generations import rotate
from arbor.engine.life.keep.save import Glance, SavedGarden, garden_text, peek_garden, read_garden, write_garden
from arbor.engine.life.plant.sim import sun_angle_at
from arbor.engine.life.rules.rules import Rules
from arbor.engine.life.world.commands import SunAt
from arbor.engine.life.world.garden import MAX_GARDEN, Garden
from arbor.engine.life.world.status import water_due
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import LSystem
from arbor.game.screens.config import GameConfig
from arbor.game.screens.state import GameState
from arbor.game.strings import duration, text
from arbor.game.watchdog import reading

LEGACY_FOLDER = "older-trees"  # beside the autosave: older garden-*.arbor files the garden had no room for


class SaveKeeper:
    """Loads, saves and autosaves one game's garden."""

    def __init__(self, state: GameState, config: GameConfig, rules: Rules, system: LSystem,
                 wall_clock: Callable[[], float], away: Callable[[], bool] = lambda: False) -> None:
        self.state, self.config, self.rules, self.system, self.wall_clock = state, config, rules, system, wall_clock
        self.away = away  # the player's Away setting: the garden is watered while they are gone
        self.last_autosave = state.clock()
        self.last_summary: AwaySummary | None = None
        self.saved_at = 0.0  # the wall-clock time the garden last loaded was saved at (seconds)
        self.start_message = ""  # what the last catch-up did, in one line ('' when it lived no time worth telling)
        self.fresh = False  # True when start() found no garden to resume: a new player
        self.folded: list[Path] = []  # older garden-*.arbor files read into the garden (removed once saved)

    @property
    def autosave_path(self) -> Path:
        """Where autosaves go (and where the game resumes from)."""
        return self.config.saves / "autosave.arbor"

    def new_world(self) -> World:
        """A fresh sapling with meters at a random 25-100 %, seeded from the config or the clock."""
        seed = self.config.seed if self.config.seed is not None else int(self.wall_clock() * 1000) % 2**31
        world = World(self.system, self.rules, seed=seed, replanted=True, planted=self.wall_clock())
        if self.rules.pace == "home":  # a day of the sun lasts a day: start it at the player's time of day
            now = time.localtime(self.wall_clock())
            world.apply(SunAt(sun_angle_at(now.tm_hour * 3600 + now.tm_min * 60 + now.tm_sec)))
        return world

    def start(self) -> Garden:
        """The garden the game starts with: the saved one when resuming, else a new sapling."""
        remove_stale_temp_files(self.config.saves)
        if self.config.resume and self.autosave_path.exists():
            garden = self.load(self.autosave_path)
            if garden is not None:
                return garden
        self.fresh = not self.autosave_path.exists()
        return Garden([self.new_world()])

    def load(self, path: Path, catch_up: bool = True) -> Garden | None:
        """A saved garden, grown by the time away; None (and the file kept as .broken) if unreadable.
        ``catch_up=False`` (Restore): the garden exactly as it was saved, none of the time since lived."""
        said_before = self.state.message, self.state.message_until
        try:
            with reading(path):  # (a watchdog sets aside the file a crash loop died reading)
                saved = read_garden(path, self.rules)
                saved.worlds += self._legacy_trees(path, len(saved.worlds))
                garden = saved.garden()
                seconds = away_seconds(self.wall_clock(), saved.saved_at, self.rules.away.cap_days) if catch_up \
                    else 0.0
                summary = live_away(garden, seconds, watered=self.away())
        except Exception as err:  # a save that breaks loading (a bug it finds) must never break the start
            self.folded = []  # (their trees are not in the garden now: their files stay)
            self._set_aside(path, err.message if isinstance(err, LSysError) else f"{type(err).__name__}: {err}")
            return None
        if saved.dropped:
            self.state.say(text("messages.lineage_dropped", count=saved.dropped, name=path.name), 8)
        self.last_summary, self.saved_at = summary, saved.saved_at
        told = (self.state.message, self.state.message_until) != said_before  # (a line said while loading)
        said = [self.state.message if told else "", away_message(summary) if summary.anything else "",
                next_care(garden.world) if catch_up else ""]
        self.start_message = " ".join(line for line in said if line)
        if self.start_message:
            self.state.say(self.start_message, 10)
        return garden

    def peek(self, path: Path) -> Glance | None:
        """A glance at the save at ``path`` as it was saved, for a preview (its trees not grown, no catch-up,
        nothing set aside; None when it cannot be read: Restore then says so when it is chosen)."""
        try:
            with reading(path):
                return peek_garden(path)
        except Exception:  # (a preview never breaks the game: the restore itself reports the error)
            return None

    def _legacy_trees(self, path: Path, have: int) -> list[World]:
        """Trees from garden-*.arbor files of older versions (one tree each), when loading the autosave."""
        if path != self.autosave_path:
            return []
        out, files = [], sorted(path.parent.glob("garden-*.arbor"))
        for legacy in files[: MAX_GARDEN - have]:
            try:
                world = read_garden(legacy, self.rules).world
            except LSysError as err:  # one bad neighbour does not lose the garden: keep it aside
                self._set_aside(legacy, err.message)
                continue
            out.append(world)
            self.folded.append(legacy)
        self._keep_apart(files[max(MAX_GARDEN - have, 0):], path.parent / LEGACY_FOLDER)
        return out

    def _keep_apart(self, files: list[Path], folder: Path) -> None:
        """Move older trees' files that do not fit in the garden into ``folder`` (never delete them: they
        were not read into the garden) and say so in one line."""
        if not files:
            return
        kept = 0
        try:
            folder.mkdir(exist_ok=True)
            for legacy in files:
                target = folder / legacy.name
                if not (target.exists() or target.is_symlink()):
                    os.rename(legacy, target)
                    kept += 1
        except OSError as exc:
            self.state.say(text("messages.legacy_not_moved", count=len(files), error=exc.strerror or str(exc)), 12)
            return
        self.state.say(text("messages.legacy_kept", count=kept, folder=folder.name, most=MAX_GARDEN), 12)

    def _set_aside(self, path: Path, error: str) -> None:
        """Keep an unreadable save under a name of its own (``*.broken``, ``*.2.broken``, ...) and say so
        in one line; a folder that cannot be written keeps it where it is (said too)."""
        try:
            kept = set_aside(path).name
        except OSError as exc:
            kept = text("messages.kept_in_place", error=exc.strerror or str(exc))
        self.state.say(text("messages.load_failed", name=path.name, error=error.splitlines()[0][:200], kept=kept), 12)

    def save(self, path: Path | None = None) -> bool:
        """Save the whole garden as one file (atomically); older garden-*.arbor files are folded in."""
        path = path or self.autosave_path
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            garden = self.state.garden
            if path == self.autosave_path:  # the last 5 autosaves are kept (engine/life/keep/generations.py)
                rotate(path)
            write_garden(SavedGarden.of(garden, self.config.lsystem.name, self.wall_clock()), path)
            if path == self.autosave_path:  # the older files now in the autosave (only those: never one unread)
                for legacy in self.folded:
                    legacy.unlink(missing_ok=True)
                self.folded = []
        except OSError as exc:
            self.state.say(text("messages.save_failed", error=exc.strerror), 6)
            return False
        self.last_autosave = self.state.clock()
        return True

    def autosave_if_due(self) -> None:
        """Autosave when the configured interval has passed since the last save."""
        if self.state.clock() - self.last_autosave >= self.config.autosave_seconds:
            self.save()


class VisitorSaves:
    """The kiosk's visitor trees, each saved as ``visitor-STAMP.arbor`` in the kiosk's folder when its
    visitor has gone. A save the disk refuses (full, read-only) is kept in memory as its text, the last
    MAX_KEPT of them, and written at a later reset once there is room: the reset goes on (a fresh
    sapling), never into a reload loop, and the tree is not lost while the kiosk runs."""

    MAX_KEPT = 3

    def __init__(self, folder: Path, wall_clock: Callable[[], float] = time.time) -> None:
        self.folder, self.wall_clock = folder, wall_clock
        self.waiting: list[tuple[str, bytes]] = []  # (file name, save text) not written yet

    def keep(self, saved: SavedGarden) -> str | None:
        """Save ``saved`` (and those kept before it); None when every one is written, else the reason
        the disk gave (the unwritten ones stay in :attr:`waiting`)."""
        stamp = time.strftime("%Y%m%d-%H%M%S", time.localtime(self.wall_clock()))
        self.waiting.append((f"visitor-{stamp}.arbor", garden_text(saved).encode("utf-8")))
        del self.waiting[:-self.MAX_KEPT]
        while self.waiting:
            name, data = self.waiting[0]
            try:
                self.folder.mkdir(parents=True, exist_ok=True)
                atomic_write(_free_name(self.folder / name), data)
            except OSError as exc:
                return exc.strerror or str(exc)
            self.waiting.pop(0)
        return None


def _free_name(path: Path) -> Path:
    """``path``, or ``NAME-2.arbor``, ... when a save of that name is there already (two resets a second)."""
    n = 1
    while path.with_name(f"{path.stem}{'' if n == 1 else f'-{n}'}{path.suffix}").exists():
        n += 1
    return path.with_name(f"{path.stem}{'' if n == 1 else f'-{n}'}{path.suffix}")


def next_care(world: World) -> str:
    """The line at a player's return that says when the cared-for tree will next want water (now, in about
    how long, or not for days); '' for a dead tree."""
    due = water_due(world)
    if not world.sim.state.alive:
        return ""
    if due is None:
        return text("messages.water_later")
    return text("messages.water_now") if due <= 0 else text("messages.water_due", when=duration(due))


def away_message(summary: AwaySummary) -> str:
    """One line for the player: how long they were away and what their tree did meanwhile."""
    hours = summary.seconds / 3600
    when = text("away.days", days=hours / 24) if hours >= 36 else text("away.hours", hours=hours) if hours >= 1.5 \
        else text("away.minutes", minutes=summary.seconds / 60)
    parts = []
    if summary.died:
        parts.append(text("away.died"))
    else:
        if summary.waterings:
            parts.append(text("away.watered", count=summary.waterings))
        if summary.grown >= 0.005:
            parts.append(text("away.grew", metres=summary.grown))
        if summary.shed:
            parts.append(text("away.shed", count=summary.shed))
        if summary.blossoms:
            parts.append(text("away.flowered"))
        if summary.fruit:
            parts.append(text("away.fruit", count=summary.fruit))
        if summary.wilted:
            parts.append(text("away.wilted"))
        elif summary.thirsty:
            parts.append(text("away.thirsty"))
    return text("away.line", when=when, what=", ".join(parts) or text("away.rested"))
