"""The tree a headless command works on: grown from an .lsys source, or read from a save (.arbor)."""

from __future__ import annotations

import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from arbor.engine.base.errors import LSysError
from arbor.engine.geometry.mesh import LOD_LEVELS, merge_trees, tree_mesh
from arbor.engine.geometry.tree import TreeGeometry, build_geometry
from arbor.engine.life.keep.save import read_garden
from arbor.engine.lsystem.derive import Deriver
from arbor.engine.lsystem.lstring import LString
from arbor.engine.lsystem.lsys import load_lsystem


@dataclass
class TreeSource:
    """What the command was asked for: the source file and how to grow or pick the tree."""

    path: Path
    steps: int | None = None
    seed: int | None = None
    budget: int | None = None
    tree: int = 0  # which tree of a garden save


def is_save(path: Path) -> bool:
    """True for save files (.arbor), which hold grown trees rather than rules to grow one."""
    return path.suffix.lower() == ".arbor"


def derive_source(source: TreeSource):
    """Grow an .lsys source: (system, L-string); says on stderr when the module budget held growth back."""
    system = load_lsystem(source.path)
    if system.externs:
        names = ", ".join(system.externs)
        raise LSysError(f"this L-system needs values from the game at every step (#extern {names}); "
                        "grow it in the game and render its save (.arbor) instead", str(source.path))
    deriver = Deriver(system, seed=source.seed, budget=source.budget)
    asked = system.iterations if source.steps is None else source.steps
    result, reports = deriver.derive(steps=asked)
    if reports and reports[-1].only_copied and len(reports) < asked:
        print(f"module budget {deriver.budget:,} full at step {len(reports)} of {asked:,}: derivation stopped "
              f"there ({len(result):,} modules; every further step would only copy them)", file=sys.stderr)
    elif any(r.budget_hit for r in reports):
        held = sum(r.deferred for r in reports)
        print(f"module budget {deriver.budget:,} reached: {held:,} rewrites held back", file=sys.stderr)
    return system, result


def tree_geometry(source: TreeSource, lod: int, roots: bool = False) -> tuple[TreeGeometry, LString]:
    """The geometry of the asked-for tree at LOD ``lod``: exactly as it stands in a save (with its
    roots below the ground when ``roots``: exports carry them), or derived."""
    if is_save(source.path):
        if source.steps is not None or source.budget is not None:
            raise LSysError("--steps and --budget grow an .lsys source; a save holds a grown tree", str(source.path))
        worlds = read_garden(source.path).worlds
        if not 0 <= source.tree < len(worlds):
            raise LSysError(f"--tree {source.tree}: this save holds {len(worlds)} tree(s), numbered from 0",
                            str(source.path))
        world = worlds[source.tree]
        geometry = world.tree.geometry(world.clocks(), lod)
        if roots:
            below = tree_mesh(world.roots.turtle(), LOD_LEVELS[min(lod, len(LOD_LEVELS) - 1)])
            geometry.mesh = merge_trees([geometry.mesh, below], [np.zeros(3), np.zeros(3)])
        return geometry, world.tree.lstring
    system, ls = derive_source(source)
    return build_geometry(ls, system, lod=lod), ls
