"""Garden -> Species: which species of the collection (assets/species.toml) Plant a tree plants next.

Each press moves to the next species the player has opened and says what it is; Plant a tree then plants
it (its L-system built from the collection, engine/life/lineage/species.py). A species opens with a
milestone of any tree of the garden (its ``unlock``: a first branch, a first fruit, a winter lived
through, a tree bred from two; the first ones are open from the start) and stays open (kept in
settings.toml); the journal page lists the species still to find and how. The collection is read at the
first use: one that cannot be read is said in one line, and the game's own species is planted.
"""

from __future__ import annotations

from collections.abc import Callable

from arbor.engine.base.errors import LSysError
from arbor.engine.life.lineage.lineage import species_of
from arbor.engine.life.lineage.species import Species, load_collection, species_system
from arbor.engine.life.world.garden import Garden
from arbor.engine.lsystem.lsys import LSystem
from arbor.game.paths import ASSETS
from arbor.game.strings import text

JOURNAL_KINDS = {"branch": "branch", "fruit": "fruit", "season": "winter"}  # journal entry -> milestone


def milestones(garden: Garden) -> set[str]:
    """The milestones the garden's trees have reached: start, and branch, fruit, winter (from their
    journals) and cross (a tree bred from two)."""
    reached = {"start"}
    for world in garden.worlds:
        reached |= {JOURNAL_KINDS[kind] for _, kind, _ in world.journal.entries if kind in JOURNAL_KINDS}
        if len(world.lineage.parents) == 2:
            reached.add("cross")
    return reached


class SpeciesChoice:
    """The species Plant a tree plants (see module docstring): ``own`` is the game's L-system, ``garden``
    gives the garden now, ``kept`` the species opened before and ``keep`` keeps newly opened ones."""

    def __init__(self, own: LSystem, garden: Callable[[], Garden], kept: Callable[[], set[str]] = set,
                 keep: Callable[[set[str]], None] = lambda keys: None) -> None:
        self.own, self.garden, self.kept, self.keep = own, garden, kept, keep
        self.collection: list[Species] | None = None  # read at the first use
        self.index = -1  # -1: the game's own species (before any press)
        self.problem = ""
        self._seen: set[str] | None = None  # the species open at the last watch (None: not looked yet)

    def species(self) -> list[Species]:
        """The collection (read once; [] when it cannot be read, and :attr:`problem` says why)."""
        if self.collection is None:
            try:
                self.collection = load_collection(ASSETS / "species.toml", ASSETS / "lsystems")
            except LSysError as err:
                self.collection, self.problem = [], err.message
        return self.collection

    def opened(self) -> list[Species]:
        """The species the player may plant now (the newly opened kept)."""
        reached, kept = milestones(self.garden()), self.kept()
        open_now = [s for s in self.species() if s.unlock in reached or s.key in kept]
        fresh = {s.key for s in open_now if s.unlock != "start"} - kept
        if fresh:
            self.keep(fresh)
        return open_now

    def watch(self) -> str:
        """The line that tells of species opened since the last look ('' when none): each is said once."""
        seen, now = self._seen, {s.key for s in self.opened()}
        self._seen = now
        fresh = [s for s in self.species() if s.key in now - (seen if seen is not None else now)]
        return text("messages.species_opened", names=", ".join(s.name for s in fresh)) if fresh else ""

    def next(self) -> str:
        """The next opened species; returns the line that says what it is (or why there is none)."""
        opened = self.opened()
        if not opened:
            return text("messages.species_unread", error=self.problem or "no species")
        keys = [s.key for s in opened]
        current = self.collection[self.index].key if self.index >= 0 else species_of(self.own.file)
        at = keys.index(current) if current in keys else -1
        chosen = opened[(at + 1) % len(opened)]
        self.index = self.collection.index(chosen)
        locked = len(self.species()) - len(opened)
        line = text("messages.species_chosen", name=chosen.name, about=chosen.about)
        return line + (" " + text("messages.species_locked", count=locked) if locked else "")

    def goals(self) -> list[str]:
        """The journal page's lines for the species still to find, each with the milestone that opens it."""
        opened = {s.key for s in self.opened()}
        return [text("journal.goal", name=s.name, how=text(f"journal.unlock_{s.unlock}"))
                for s in self.species() if s.key not in opened]

    def name(self) -> str:
        """The chosen species' name, as the Species button shows it."""
        if self.index < 0 or not self.collection:
            return text("menu.species_own")
        return self.collection[self.index].name

    def system(self) -> LSystem:
        """The L-system of the chosen species (the game's own until one is chosen)."""
        if self.index < 0 or not self.collection:
            return self.own
        chosen = self.collection[self.index]
        return self.own if chosen.key == species_of(self.own.file) else species_system(chosen, ASSETS / "lsystems")
