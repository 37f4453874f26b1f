"""A tree's journal: the milestones of its life, kept in its save and shown in the game's menu.

First branch, first flower, first fruit, every new metre of height, every winter survived (the tree's
birthday: its height and crown width that spring are kept beside it, ``sizes``), fruit picked, every
pruning (how many branches were cut).
Entries are (game time, what, number); a shared save is untrusted, so only known kinds with sane
numbers are read back (the rest is dropped and counted, never trusted).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from arbor.engine.base.units import METRE

KINDS = ("planted", "branch", "flower", "fruit", "height", "season", "harvest", "pruned")
MAX_ENTRIES = 400
MAX_SIZE_M = 1000.0  # a birthday's height or crown width read back from a save is at most this (metres)
MAX_METRES = 150  # the "every metre" milestones stop here (the tallest trees on Earth are about 116 m): a hostile
# save's F(1e12) must not write (or even look for) one entry per metre


@dataclass
class Journal:
    """Milestones in the order they happened."""

    entries: list[tuple[float, str, float]] = field(default_factory=list)
    sizes: dict[float, tuple[float, float]] = field(default_factory=dict)  # year survived -> (height, width) m

    def has(self, kind: str, value: float | None = None) -> bool:
        """True when a milestone of ``kind`` (with ``value``, if given) is written already."""
        return any(k == kind and (value is None or v == value) for _, k, v in self.entries)

    def write(self, time: float, kind: str, value: float = 0.0, once: bool = True) -> bool:
        """Add a milestone (once per kind and value, unless not ``once``: a pruning is written each time);
        False when it was there already or the journal is full."""
        if (once and self.has(kind, value)) or len(self.entries) >= MAX_ENTRIES:
            return False
        self.entries.append((float(time), kind, float(value)))
        return True

    def observe(self, world, height: float) -> list[tuple[str, float]]:
        """Write whatever the tree has newly reached (``height`` in scene units); returns the new ones."""
        s, ls = world.sim.state, world.tree.lstring
        new = []
        checks = [("branch", 0.0, ls.count("A") >= 2), ("flower", 0.0, ls.count("K") > 0),
                  ("fruit", 0.0, ls.count("O") > 0)]
        metres = min(math.floor(height / METRE), MAX_METRES) if math.isfinite(height) else 0
        if metres >= 1 and not self.has("height", float(metres)):
            written = {v for _, k, v in self.entries if k == "height"}
            checks += [("height", float(m), True) for m in range(1, metres + 1) if float(m) not in written]
        season = world.sim.season()
        if season.index == 0 and season.year >= 1 and s.alive:
            checks.append(("season", float(season.year), True))  # a spring after a winter: a year survived
        for kind, value, reached in checks:
            if reached and s.alive and self.write(s.time, kind, value):
                new.append((kind, value))
                if kind == "season":  # a birthday: how tall and wide the tree begins its year
                    self.sizes[value] = crown_size(world)
        return new

    def size_rows(self) -> list[list[float]]:
        """The birthdays' sizes for the save file: [year, height m, width m], by year."""
        return [[year, h, w] for year, (h, w) in sorted(self.sizes.items())]

    def read_sizes(self, rows) -> int:
        """Keep saved :meth:`size_rows` whose year is a winter survived in the journal and whose sizes are
        sane (0..MAX_SIZE_M m); returns how many rows were dropped."""
        years, dropped = {v for _, k, v in self.entries if k == "season"}, 0
        for row in rows if isinstance(rows, list) else []:
            ok = (isinstance(row, list) and len(row) == 3
                  and all(isinstance(x, int | float) and not isinstance(x, bool) and math.isfinite(x) for x in row)
                  and float(row[0]) in years and all(0.0 <= x <= MAX_SIZE_M for x in row[1:]))
            if ok:
                self.sizes[float(row[0])] = (float(row[1]), float(row[2]))
            else:
                dropped += 1
        return dropped

    def to_rows(self) -> list[list]:
        """Plain data for the save file."""
        return [[t, k, v] for t, k, v in self.entries]

    @classmethod
    def from_rows(cls, rows) -> tuple[Journal, int]:
        """Read saved rows; returns the journal and how many rows were dropped as unknown or malformed."""
        journal, dropped = cls(), 0
        for row in rows if isinstance(rows, list) else []:
            ok = (isinstance(row, list) and len(row) == 3 and row[1] in KINDS
                  and all(isinstance(x, int | float) and not isinstance(x, bool) and math.isfinite(x) and abs(x) < 1e12
                          for x in (row[0], row[2])))
            if ok and len(journal.entries) < MAX_ENTRIES:
                journal.entries.append((float(row[0]), row[1], float(row[2])))
            else:
                dropped += 1
        return journal, dropped


def crown_size(world) -> tuple[float, float]:
    """(height, crown width) of ``world``'s tree now, in metres to the millimetre (see :func:`turtle_size`)."""
    height, width = turtle_size(world.tree.geometry(world.clocks()).turtle)
    return round(height, 3), round(width, 3)


def turtle_size(turtle) -> tuple[float, float]:
    """(height, crown width) of a drawn tree, in metres: the top of its wood, and the largest horizontal extent
    of its wood and leaves (so a bare crown has one too)."""
    if not len(turtle.segments):
        return 0.0, 0.0
    ends = turtle.segments.end
    points = np.concatenate([ends, turtle.leaves.position]) if len(turtle.leaves) else ends
    flat = points[:, [0, 2]]
    return float(ends[:, 1].max()) / METRE, float((flat.max(axis=0) - flat.min(axis=0)).max()) / METRE
