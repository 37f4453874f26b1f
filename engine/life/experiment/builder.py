"""The experiment builder's model: a one-factor sweep chosen from lists (no typing), written as the same
TOML a teacher writes by hand, with comments; an existing sweep file reopened into it.

Every choice is valid by construction: the factors are the schema's (engine/life/experiment/schema.py,
with their units), each offered with a ladder of levels inside its range and the [base] it needs (a
watering timetable for the interval between drinks, a pruning schedule for a share to cut); seeds, days
and responses are bounded counts and lists. ``Draft.toml()`` is read back by sweep_file.load_sweep.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from arbor.engine.life.experiment import schema
from arbor.engine.life.experiment.sweep import Sweep

SPECIES = ("game_tree.lsys", "game_poplar.lsys")
FACTORS: dict[str, tuple[str, tuple]] = {  # key -> (name, the levels offered)
    "day_length": ("Day length", (6, 8, 10, 12, 14, 16, 18)),
    "sun_elevation": ("Noon sun elevation", (20, 30, 45, 60, 75, 90)),
    "orbit_height": ("Sun orbit height", (-0.4, 0.0, 0.35, 0.7, 1.0)),
    "watering.every": ("Time between drinks", (30, 60, 120, 240, 480)),
    "watering.below": ("Water when the meter falls below", (0.2, 0.3, 0.4, 0.5, 0.6)),
    "prune.lowest": ("Lowest branches cut", (0, 0.2, 0.4, 0.6)),
    "prune.keep_height": ("Head the tree back to", (0.8, 1.2, 1.6, 2.0)),
    "species": ("Species", SPECIES),
}
RESPONSES = ("height", "biomass", "leaf_area", "light_day", "net_carbon", "girth", "leaves", "water_min",
             "wilt_max", "alive")
WATERING = ("kept watered", "never watered")
MAX_SEEDS, MAX_DAYS = 50, 60
DAY_LENGTH, ELEVATION = 14, 60  # the [base] sun of every builder sweep (unless it is the factor)


class NotBuildableError(ValueError):
    """A sweep file the builder cannot show (two factors, a factor it does not offer): edit it as text."""


@dataclass
class Draft:
    """A one-factor sweep being built: what the builder's buttons change."""

    factor: str = "day_length"
    levels: list = field(default_factory=lambda: [6, 10, 14, 18])
    species: str = "game_tree.lsys"
    seeds: int = 8
    days: int = 20
    responses: list[str] = field(default_factory=lambda: ["height", "biomass", "leaf_area", "alive"])
    watering: str = "kept watered"
    ladders: dict = field(default_factory=lambda: {k: tuple(v[1]) for k, v in FACTORS.items()})
    offered: tuple = RESPONSES
    named: str | None = None  # a title of the file's own (None: made from the factor)
    label: str | None = None  # the factor's name of the file's own (None: the builder's)
    day_length: float | None = DAY_LENGTH  # [base]'s hours of daylight (None: the game's own sun)
    elevation: float | None = ELEVATION  # [base]'s noon sun, degrees (None: the game's own)

    @property
    def name(self) -> str:
        """The factor's name in the tables and on the axes."""
        return self.label or FACTORS[self.factor][0]

    @property
    def unit(self) -> str:
        """The factor's unit (the schema's), or "" (species)."""
        spec = schema.FACTOR_KEYS.get(self.factor)
        return spec.unit if spec else ""

    def choose_factor(self, key: str) -> None:
        """Vary ``key`` (its first, middle and last levels chosen)."""
        self.factor, self.label = key, None
        ladder = self.ladders[key]
        self.levels = sorted({ladder[0], ladder[len(ladder) // 2], ladder[-1]}, key=ladder.index)

    def toggle_level(self, level) -> None:
        """A level on or off (the last one stays: a sweep has at least one)."""
        if level in self.levels:
            if len(self.levels) > 1:
                self.levels.remove(level)
        else:
            ladder = self.ladders[self.factor]
            self.levels = sorted([*self.levels, level], key=ladder.index)

    def toggle_response(self, response: str) -> None:
        """A response on or off (the last one stays)."""
        if response in self.responses:
            if len(self.responses) > 1:
                self.responses.remove(response)
        else:
            self.responses = [r for r in self.offered if r in (*self.responses, response)]

    def title(self) -> str:
        """The sweep's title, from its factor."""
        return self.named or f"{self.name}: {len(self.levels)} levels x {self.seeds} seeds"

    def toml(self, day_seconds: float) -> str:
        """The sweep file, as a teacher would write it (with comments); ``day_seconds``: a game day's length."""
        lines = ["# Made with Arbor's experiment builder (arbor lab FILE --build): change it there or here;",
                 "# docs/lab.md explains every key.",
                 f"title = {_text(self.title())}"]
        if self.factor != "species":
            lines.append(f"species = {_text(self.species)}")
        lines += [f"duration = {self.days * day_seconds:.6g}   # game seconds: {self.days} game days",
                  f"sample_every = {day_seconds:.6g}   # one sample a game day",
                  f"seeds = {self.seeds}   # seeds 1 to {self.seeds}, the same at every level",
                  "seasons = false   # an endless summer: the factor alone changes",
                  f"responses = [{', '.join(_text(r) for r in self.responses)}]   # docs/columns.md",
                  "", "[base]   # what every run shares"]
        lines += self._base()
        unit = f" ({self.unit})" if self.unit else ""
        lines += ["", "[[factor]]", f"name = {_text(self.name)}", f"key = {_text(self.factor)}   # varies{unit}",
                  f"levels = [{', '.join(_level(v) for v in self.levels)}]", ""]
        return "\n".join(lines)

    def _base(self) -> list[str]:
        base = []
        if self.factor not in ("day_length", "orbit_height") and self.day_length is not None:
            base.append(f"day_length = {self.day_length:g}   # hours of daylight")
        if self.factor not in ("sun_elevation", "orbit_height") and self.elevation is not None:
            base.append(f"sun_elevation = {self.elevation:g}   # degrees at noon")
        if self.factor == "watering.every":
            base.append("watering = { every = 60, seconds = 5 }   # a 5 s drink on a timetable (the factor sets it)")
        elif self.factor == "watering.below" or self.watering == "kept watered":
            base.append("watering = { below = 0.5, until = 0.7 }   # kept watered")
        else:
            base.append('watering = "never"')
        if self.factor == "prune.lowest":
            base.append("prune = { every_days = 4, lowest = 0.2 }   # every 4 game days (the factor sets the share)")
        elif self.factor == "prune.keep_height":
            base.append("prune = { every_days = 4, keep_height = 1.2 }   # every 4 game days (the factor sets it)")
        return base


def _text(value: str) -> str:
    """A TOML basic string (the builder's own words: no quotes or backslashes in them)."""
    return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'


def _level(value) -> str:
    return _text(value) if isinstance(value, str) else f"{value:g}"


def draft_of(sweep: Sweep, day_seconds: float) -> Draft:
    """The builder's draft of an existing sweep file (its own levels and responses offered beside the
    builder's); NotBuildableError for a sweep the builder cannot show."""
    if len(sweep.factors) != 1 or sweep.factors[0].key not in FACTORS:
        keys = ", ".join(f.key for f in sweep.factors)
        raise NotBuildableError(f"the builder shows sweeps of one of its factors ({', '.join(FACTORS)}); this one "
                           f"varies {keys}: edit it in a text editor")
    factor = sweep.factors[0]
    own_title = None if re.fullmatch(r".*: \d+ levels x \d+ seeds", sweep.title) else sweep.title  # (not ours)
    draft = Draft(factor=factor.key, species=sweep.species, seeds=len(sweep.seeds), named=own_title,
                  label=factor.name, day_length=sweep.base.day_length, elevation=sweep.base.sun_elevation,
                  days=max(1, min(MAX_DAYS, round(sweep.duration / day_seconds))),
                  responses=list(sweep.responses),
                  watering="never watered" if sweep.base.watering.below is None and sweep.base.watering.every is None
                  else "kept watered")
    ladder = draft.ladders[factor.key]
    own = (*ladder, *(v for v in factor.levels if v not in ladder))  # (the file's own levels offered too)
    own = tuple(sorted(own)) if all(not isinstance(v, str) for v in own) else own
    draft.ladders[factor.key] = own
    draft.levels = sorted(factor.levels, key=own.index)
    draft.offered = (*RESPONSES, *(r for r in sweep.responses if r not in RESPONSES))
    if sweep.seeds != list(range(1, len(sweep.seeds) + 1)) or len(sweep.seeds) > MAX_SEEDS:
        raise NotBuildableError("the builder gives seeds 1 to N; this file lists its own: edit it in a text editor")
    return draft
