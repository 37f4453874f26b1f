"""The game's collection of species (assets/species.toml): each a game L-system with the defines it changes.

A species is named by its table (the name its trees' lineage and saves carry) and grown by a ``base``
.lsys of the game (game_tree.lsys, game_poplar.lsys, spruce.lsys) with some of that file's ``#define`` values changed:
its source text is the base's with those lines rewritten, so a tree's save carries the species it grew
by and two species can be crossed (they share the base's modules and host values). The file is read
strictly: an unknown key, a define its base does not declare or a value that is not a finite number is a
SpeciesError naming the file, line and column.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from pathlib import Path

from arbor.engine.base.config import toml_position
from arbor.engine.base.errors import LSysError
from arbor.engine.base.reader import read_user_toml
from arbor.engine.lsystem.lsys import LSystem, load_lsystem, parse_lsystem

KEYS = ("name", "about", "base", "defines", "unlock")
UNLOCKS = ("start", "branch", "fruit", "winter", "cross")  # the milestones that open a species (see species.toml)
MAX_SPECIES = 32  # species in one collection at most


class SpeciesError(LSysError):
    """A species collection that cannot be used (file, line, column)."""


@dataclass(frozen=True)
class Species:
    """One species of the collection: ``key`` (its lineage's species name), the ``name`` and ``about``
    shown to the player, its ``base`` .lsys file name, the ``defines`` it changes and the milestone that
    ``unlock``s it (one of UNLOCKS)."""

    key: str
    name: str
    about: str
    base: str
    defines: dict[str, float] = field(default_factory=dict)
    unlock: str = "start"


def load_collection(path: str | Path, lsystems: str | Path) -> list[Species]:
    """The species of ``path`` in its order, each checked against its base in the folder ``lsystems``."""
    file = str(path)
    text, data = read_user_toml(path, SpeciesError)
    if not data or len(data) > MAX_SPECIES:
        raise SpeciesError(f"a collection holds 1 to {MAX_SPECIES} species", file, 1, 1)
    out, declared_by = [], {}  # (each base parsed once)
    for key, row in data.items():
        where = toml_position(text, key)
        if not isinstance(row, dict) or not re.fullmatch(r"[a-z][a-z0-9_]{0,39}", key):
            raise SpeciesError(f"[{key}] must be a table named in lower-case letters, digits and _", file, *where)
        for name in row:
            if name not in KEYS:
                raise SpeciesError(f"[{key}] has no key {name!r} (it takes {', '.join(KEYS)})", file,
                                   *toml_position(text, key, name))
        base = row.get("base")
        if not isinstance(base, str) or not re.fullmatch(r"[a-z0-9_]+\.lsys", base) \
                or not (Path(lsystems) / base).is_file():
            raise SpeciesError(f"[{key}] base must name a game .lsys of {lsystems}", file,
                               *toml_position(text, key, "base"))
        unlock = row.get("unlock", "start")
        if unlock not in UNLOCKS:
            raise SpeciesError(f"[{key}] unlock must be one of {', '.join(UNLOCKS)}", file,
                               *toml_position(text, key, "unlock"))
        species = Species(key, str(row.get("name", key)), str(row.get("about", "")), base,
                          _defines(row.get("defines", {}), key, file, text), unlock)
        if base not in declared_by:
            declared_by[base] = load_lsystem(Path(lsystems) / base).constants
        declared = declared_by[base]
        unknown = sorted(set(species.defines) - set(declared))
        if unknown:
            raise SpeciesError(f"[{key}] {base} declares no {', '.join(unknown)}", file,
                               *toml_position(text, key, "defines"))
        out.append(species)
    return out


def _defines(value, key: str, file: str, text: str) -> dict[str, float]:
    """The ``defines`` table of species ``key``: names of defines to finite numbers."""
    where = toml_position(text, key, "defines")
    if not isinstance(value, dict):
        raise SpeciesError(f"[{key}] defines must be a table of NAME = number", file, *where)
    out = {}
    for name, number in value.items():
        if not re.fullmatch(r"[A-Z][A-Z0-9_]*", name) or isinstance(number, bool) \
                or not isinstance(number, int | float) or not math.isfinite(number):
            raise SpeciesError(f"[{key}] defines: {name} must be a define's name with a finite number", file,
                               *where)
        out[name] = float(number)
    return out


def species_source(base_source: str, defines: dict[str, float]) -> str:
    """``base_source`` with each of ``defines``' ``#define NAME value`` lines given the new value (the
    line's comment is kept)."""
    names = "|".join(re.escape(name) for name in defines)
    if not names:
        return base_source
    return re.sub(rf"(?m)^(#define\s+)({names})(\s+)\S+",
                  lambda m: f"{m.group(1)}{m.group(2)}{m.group(3)}{defines[m.group(2)]:g}", base_source)


def species_system(species: Species, lsystems: str | Path) -> LSystem:
    """The L-system ``species`` grows by: its base's, with its defines (named ``KEY.lsys``, so its trees'
    lineage carries the species' name)."""
    base = load_lsystem(Path(lsystems) / species.base)
    if not species.defines:
        return base
    system = parse_lsystem(species_source(base.source, species.defines), f"{species.key}.lsys")
    system.budget = base.budget
    return system
