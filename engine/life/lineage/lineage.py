"""Lineage: who a tree's parents were, its generation, the seed that made it and when it was planted.

Every tree carries its own :class:`Lineage`; a garden keeps a :class:`Family` of every ancestor it has
known (trees replanted or shared away stay in the family), so the family tree can be drawn across
generations. Saves are untrusted: entries read back are checked field by field (identifiers of 16
lowercase hex digits, at most two parents, a generation above each parent's, finite times, short
plain names); anything else is dropped and counted, never trusted.
"""

from __future__ import annotations

import hashlib
import math
import re
from dataclasses import dataclass

MAX_FAMILY = 500  # ancestors a garden remembers
MAX_GENERATION = 10_000
_ID = re.compile(r"^[0-9a-f]{16}$")
_NAME = re.compile(r"^[A-Za-z0-9_ .\-]{1,40}$")


@dataclass(frozen=True)
class Lineage:
    """One tree's place in its family."""

    id: str
    parents: tuple[str, ...] = ()
    generation: int = 0
    seed: int = 0
    planted: float = 0.0  # wall-clock seconds (epoch) when it was planted
    species: str = "game_tree"

    def to_row(self) -> dict:
        """Plain data for a save file."""
        return {"id": self.id, "parents": list(self.parents), "generation": self.generation, "seed": self.seed,
                "planted": self.planted, "species": self.species}


def new_lineage(seed: int, planted: float, species: str, parents: tuple[Lineage, ...] = ()) -> Lineage:
    """A new tree's lineage: generation one above its oldest-line parent, an id from what made it."""
    key = f"{seed}|{planted!r}|{species}|{','.join(p.id for p in parents)}"
    generation = max((p.generation for p in parents), default=-1) + 1
    return Lineage(hashlib.sha256(key.encode()).hexdigest()[:16], tuple(dict.fromkeys(p.id for p in parents)),
                   min(generation, MAX_GENERATION), int(seed) % 2**63, float(planted), _clean_name(species))


def species_of(file: str) -> str:
    """A species name from an L-system's file name (game_tree, game_poplar, ...)."""
    name = re.split(r"[\\/]", file)[-1].split(" ")[0]
    return _clean_name(name.removesuffix(".lsys"))


def _clean_name(name: str) -> str:
    name = re.sub(r"[^A-Za-z0-9_ .\-]", "", str(name))[:40]
    return name or "tree"


def lineage_from_row(row) -> Lineage | None:
    """A lineage read from a save, or None when any field is missing, malformed or out of range."""
    if not isinstance(row, dict):
        return None
    ident, parents, generation = row.get("id"), row.get("parents", []), row.get("generation")
    seed, planted, species = row.get("seed"), row.get("planted"), row.get("species", "tree")
    ok = (isinstance(ident, str) and _ID.match(ident) is not None
          and isinstance(parents, list) and len(parents) <= 2
          and all(isinstance(p, str) and _ID.match(p) is not None and p != ident for p in parents)
          and _whole(generation, 0, MAX_GENERATION) and _whole(seed, 0, 2**63 - 1)
          and isinstance(planted, int | float) and not isinstance(planted, bool) and math.isfinite(planted)
          and abs(planted) < 1e11 and isinstance(species, str) and _NAME.match(species) is not None)
    if not ok:
        return None
    return Lineage(ident, tuple(dict.fromkeys(parents)), int(generation), int(seed), float(planted), species)


def _whole(x, low: int, high: int) -> bool:
    return isinstance(x, int) and not isinstance(x, bool) and low <= x <= high


class Family:
    """Every lineage a garden has known, by id (bounded; the oldest are forgotten first)."""

    def __init__(self, members: list[Lineage] | None = None) -> None:
        self.members: dict[str, Lineage] = {}
        for member in members or []:
            self.add(member)

    def add(self, lineage: Lineage) -> None:
        """Remember ``lineage`` (and forget the oldest when the family is full)."""
        self.members[lineage.id] = lineage
        while len(self.members) > MAX_FAMILY:
            self.members.pop(next(iter(self.members)))

    def get(self, ident: str) -> Lineage | None:
        """The lineage with id ``ident``, if known."""
        return self.members.get(ident)

    def ancestors(self, lineage: Lineage, depth: int = 50) -> list[Lineage]:
        """Known ancestors of ``lineage``, nearest first (each once; cycles cannot loop)."""
        out, seen, frontier = [], {lineage.id}, list(lineage.parents)
        while frontier and depth > 0:
            nxt = []
            for ident in frontier:
                parent = self.members.get(ident)
                if parent is not None and ident not in seen:
                    seen.add(ident)
                    out.append(parent)
                    nxt += list(parent.parents)
            frontier, depth = nxt, depth - 1
        return out

    @classmethod
    def from_rows(cls, rows) -> tuple[Family, int]:
        """Read saved rows; returns the family and how many rows were dropped. A parent link to an
        ancestor of the same or a later generation (impossible, so hostile) is cut."""
        lineages, dropped = [], 0
        for row in rows if isinstance(rows, list) else []:
            lineage = lineage_from_row(row)
            if lineage is None or len(lineages) >= MAX_FAMILY:
                dropped += 1
            else:
                lineages.append(lineage)
        by_id = {lin.id: lin for lin in lineages}
        family = cls()
        for lin in lineages:
            good = tuple(p for p in lin.parents if p not in by_id or by_id[p].generation < lin.generation)
            dropped += len(lin.parents) - len(good)
            family.add(Lineage(lin.id, good, lin.generation, lin.seed, lin.planted, lin.species))
        return family, dropped

    def to_rows(self) -> list[dict]:
        """Plain data for the save file."""
        return [m.to_row() for m in self.members.values()]
