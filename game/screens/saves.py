"""The game's save policy: resume the garden at start, autosave every minute and on quit, keep broken saves.

A save that cannot be read is renamed to ``*.broken`` (never deleted) and a new tree is planted; time
the player was away is lived by the tree on load (up to one in-game day).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING

from engine.base.errors import LSysError
from engine.life.garden import Garden
from engine.life.save import load_world, save_world
from engine.life.world import World
from game.strings import text

if TYPE_CHECKING:
    from game.screens.game import Game


class SaveKeeper:
    """Loads, saves and autosaves one game's garden."""

    def __init__(self, game: Game) -> None:
        self.game = game
        self.last_autosave = game.clock()

    @property
    def autosave_path(self) -> Path:
        """Where autosaves go (and where the game resumes from)."""
        return self.game.config.saves / "autosave.arbor"

    def new_world(self) -> World:
        """A fresh sapling with meters at a random 25-100 %, seeded from the config or the clock."""
        game = self.game
        seed = game.config.seed if game.config.seed is not None else int(game.wall_clock() * 1000) % 2**31
        world = World(game.system, game.rules, seed=seed)
        world.apply("replant", 1.0)
        game.input_log = [(0, "replant", 1.0)]
        return world

    def start(self) -> Garden:
        """The garden the game starts with: the saved one when resuming, else a new sapling."""
        game = self.game
        if game.config.resume and self.autosave_path.exists():
            world = self.load(self.autosave_path)
            if world is not None:
                others = [w for w in map(self.load, sorted(game.config.saves.glob("garden-*.arbor"))) if w]
                return Garden([*others, world], current=len(others))
        return Garden([self.new_world()])

    def load(self, path: Path) -> World | None:
        """A saved tree, grown by the time away; None (and the file kept as .broken) if unreadable."""
        game = self.game
        try:
            world, saved_at = load_world(path, game.rules)
        except LSysError as err:
            kept = path.with_name(path.name + ".broken")
            path.replace(kept)
            game.say(text("messages.load_failed", name=path.name, error=err.message, kept=kept.name), 12)
            return None
        away = max(game.wall_clock() - saved_at, 0.0)
        day = 2 * math.pi / max(world.sim.state.sun_speed, 1e-6)
        grown = min(away, day)
        world.catch_up(grown)
        if grown > 1:
            game.say(text("messages.welcome_back", minutes=grown / 60), 6)
        return world

    def save(self, path: Path | None = None) -> bool:
        """Save the cared-for tree (atomically) and, with the autosave, the rest of the garden."""
        game = self.game
        path = path or self.autosave_path
        name = game.config.lsystem.name
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            save_world(game.world, path, name, game.wall_clock())
            if path == self.autosave_path:
                others = game.others
                for k, other in enumerate(others):
                    save_world(other, path.parent / f"garden-{k}.arbor", name, game.wall_clock())
                for stale in sorted(path.parent.glob("garden-*.arbor"))[len(others):]:
                    stale.unlink()
        except OSError as exc:
            game.say(text("messages.save_failed", error=exc.strerror), 6)
            return False
        self.last_autosave = game.clock()
        return True

    def autosave_if_due(self) -> None:
        """Autosave when the configured interval has passed since the last save."""
        if self.game.clock() - self.last_autosave >= self.game.config.autosave_seconds:
            self.save()
