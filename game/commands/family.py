"""`arbor breed` (two saves cross into a child's save) and `arbor lineage` (a save's family tree as text)."""

from __future__ import annotations

import time
from pathlib import Path

from arbor.engine.base.errors import LSysError
from arbor.engine.life.keep.save import SavedGarden, read_garden, write_garden
from arbor.engine.life.lineage.lineage import Family, Lineage
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.garden import Garden
from arbor.game.paths import ASSETS


def _tree(path: Path, index: int | None) -> tuple[SavedGarden, int]:
    saved = read_garden(path, load_rules(ASSETS / "rules.toml"))
    index = saved.current if index is None else index
    if not 0 <= index < len(saved.worlds):
        raise LSysError(f"this save holds {len(saved.worlds)} tree(s), numbered from 0", str(path))
    return saved, index


def breed_saves(a: Path, b: Path, seed: int, out: Path, tree_a: int | None = None, tree_b: int | None = None,
                now: float | None = None) -> Garden:
    """Cross the cared-for (or chosen) trees of two saves; write a garden holding the child sapling,
    with both parents' families, to ``out``."""
    mother_save, i = _tree(a, tree_a)
    father_save, j = _tree(b, tree_b)
    mother, father = mother_save.worlds[i], father_save.worlds[j]
    garden = Garden([mother], 0, family=Family([*mother_save.family.members.values(),
                                               *father_save.family.members.values(), father.lineage]))
    child = garden.breed(mother, father, seed, mother.rules, time.time() if now is None else now)
    child.position = (0.0, 0.0)
    out.parent.mkdir(parents=True, exist_ok=True)
    write_garden(SavedGarden([child], 0, now, [], garden.family, lsystem_name=f"{child.lineage.species}.lsys"), out)
    return garden


def lineage_text(path: Path) -> str:
    """The family tree of every tree in a save, as indented text (ancestors nearest first)."""
    saved = read_garden(path, load_rules(ASSETS / "rules.toml"))
    family = saved.family
    for world in saved.worlds:
        family.add(world.lineage)
    lines = [f"{path.name}: {len(saved.worlds)} tree(s), {len(family.members)} in the family"]
    if saved.dropped:
        lines.append(f"({saved.dropped} family entries could not be trusted and were left out)")
    for number, world in enumerate(saved.worlds, 1):
        lines.append(f"tree {number}: {_describe(world.lineage)}")
        lines += _ancestry(family, world.lineage, "  ", set())
    return "\n".join(lines)


def _ancestry(family: Family, lineage: Lineage, indent: str, seen: set[str]) -> list[str]:
    out = []
    for k, ident in enumerate(lineage.parents):
        last = k == len(lineage.parents) - 1
        parent = family.get(ident)
        branch = "`-- " if last else "|-- "
        if parent is None:
            out.append(f"{indent}{branch}{ident} (not known here)")
            continue
        out.append(f"{indent}{branch}{_describe(parent)}")
        if ident not in seen:
            seen.add(ident)
            out += _ancestry(family, parent, indent + ("    " if last else "|   "), seen)
    return out


def _describe(lineage: Lineage) -> str:
    planted = time.strftime("%Y-%m-%d", time.gmtime(lineage.planted)) if lineage.planted > 0 else "unknown date"
    return f"{lineage.id} {lineage.species}, generation {lineage.generation}, seed {lineage.seed}, planted {planted}"
