"""Garden -> Species: which species of the collection (assets/species.toml) Plant a tree plants next.

Each press moves to the next species of the collection and says what it is; Plant a tree then plants it
(its L-system built from the collection, engine/life/lineage/species.py). The collection is read at the
first press: one that cannot be read is said in one line, and the game's own species is planted.
"""

from __future__ import annotations

from arbor.engine.base.errors import LSysError
from arbor.engine.life.lineage.lineage import species_of
from arbor.engine.life.lineage.species import Species, load_collection, species_system
from arbor.engine.lsystem.lsys import LSystem
from arbor.game.paths import ASSETS
from arbor.game.strings import text


class SpeciesChoice:
    """The species Plant a tree plants (see module docstring); ``own`` is the game's L-system."""

    def __init__(self, own: LSystem) -> None:
        self.own = own
        self.collection: list[Species] | None = None  # read at the first press
        self.index = -1  # -1: the game's own species (before any press)

    def next(self) -> str:
        """The next species of the collection; returns the line that says what it is (or why not)."""
        if self.collection is None:
            try:
                self.collection = load_collection(ASSETS / "species.toml", ASSETS / "lsystems")
            except LSysError as err:
                self.collection = []
                return text("messages.species_unread", error=err.message)
        if not self.collection:
            return text("messages.species_unread", error="no species")
        own = species_of(self.own.file)
        start = next((k for k, s in enumerate(self.collection) if s.key == own), 0) if self.index < 0 else self.index
        self.index = (start + 1) % len(self.collection)
        chosen = self.collection[self.index]
        return text("messages.species_chosen", name=chosen.name, about=chosen.about)

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
