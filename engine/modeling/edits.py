"""Region edits (Onishi et al. 2003 sections 4.2 and 5.2): a chosen production set rewrites only the modules
whose turtle position lies inside a region of interest.

The built-in sets are ordinary .lsys files (assets/edits/): add or erase leaves, add or erase
blossoms and grow (the game tree's buds and apices in the region wake and are
due at once; an empty region gets a new axis, Onishi et al. 2003, 4.2). A system's own productions can be
applied in a region the same way. Prune removes the subtrees that start inside the region; Bend turns the
pieces inside it toward the ground in world terms (engine/modeling/bend.py).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from arbor.engine.lsystem import brackets
from arbor.engine.lsystem.derive import Deriver
from arbor.engine.lsystem.lstring import LString
from arbor.engine.lsystem.lsys import LSystem, load_lsystem
from arbor.engine.modeling.regions import seed_in_region

LSYS_EDITS = ("add_leaves", "erase_leaves", "add_blossoms", "erase_blossoms", "grow")
EDIT_SETS = (*LSYS_EDITS[:4], "bend", "grow", "prune")  # bend and prune are not rewrites (bend.py, prune_region)
WOOD = np.zeros(256, bool)
WOOD[[ord("F"), ord("I")]] = True


def load_edit_sets(folder: str | Path) -> dict[str, LSystem]:
    """The built-in production sets, by name, from ``folder`` (errors name file, line and column)."""
    return {name: load_lsystem(Path(folder) / f"{name}.lsys") for name in LSYS_EDITS}


def prune_region(ls: LString, positions: np.ndarray, region) -> tuple[LString, int]:
    """Remove every branch piece (F or I) that starts inside ``region`` together with everything that
    grows from it: the rest of its branch. The tree's first piece always stays (the trunk's base).
    Returns the new string and how many modules were removed."""
    wood = np.flatnonzero(WOOD[ls.sym])
    cut = wood[1:][region.contains(positions[wood[1:]])] if len(wood) > 1 else wood[:0]
    if len(cut) == 0:
        return ls, 0
    removed = brackets.rest_of_branches(ls.sym, cut)
    return ls.select(~removed), int(removed.sum())


def apply_edit(ls: LString, positions: np.ndarray, region, system: LSystem,
               extern: dict[str, float] | None = None, new_axis: str | None = None,
               budget: int | None = None) -> tuple[LString, int, int]:
    """Rewrite once with ``system``, only inside ``region``; ``positions`` are the modules' turtle
    positions. With ``new_axis`` (an axiom) an empty region gets a new axis at its centre. A module
    ``budget`` holds back rewrites that would grow the string past it (erasing always works).
    Returns the new string, how many modules were rewritten (-1 when a new axis was started) and
    how many rewrites the budget held back."""
    inside = region.contains(positions)
    if not inside.any():
        if new_axis is None or (budget is not None and len(ls) >= budget):
            return ls, 0, 0
        return seed_in_region(ls, new_axis, region.center), -1, 0
    known = set(system.externs)
    deriver = Deriver(system, budget=budget if budget is not None else 2**62)
    new, report = deriver.step(ls, {k: v for k, v in (extern or {}).items() if k in known}, only=inside)
    return new, report.rewritten, report.deferred
