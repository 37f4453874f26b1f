"""Pruning a tree: heading it back to a height, or raising its crown by cutting its lowest branches.

A cut removes an internode and everything that grows from it (the rest of its branch, as a saw would):
the L-string loses those modules, the pieces fall as a shed branch does (:attr:`GrowingTree.fallen`),
and the journal records how many branches were cut. The plant model stays consistent without more
bookkeeping: the wood that stays keeps the girth it built (wood never shrinks, pipe model), the
sugar in store stays in store, and the carbon budget's leaf area and sapwood (what upkeep is charged on)
are measured again from the string that is left at once, not at the next light reading. Old wood
consolidated into one internode of several pieces (engine/life/plant/consolidate.py) is cut as one.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from arbor.engine.base.units import METRE
from arbor.engine.life.form.interpret import INTERNODE, pipe_area
from arbor.engine.life.plant import carbon
from arbor.engine.life.plant.growth import LightScene, fallen_pieces, remove_empty_branches
from arbor.engine.lsystem import brackets
from arbor.engine.lsystem.lstring import params_where

if TYPE_CHECKING:
    from arbor.engine.life.world.world import World

WOOD = np.zeros(256, bool)
WOOD[[ord("F"), ord("I")]] = True


def prune(world: World, keep_height: float | None = None, lowest: float = 0.0) -> int:
    """Cut ``world``'s tree now: every shoot that reaches above ``keep_height`` metres is cut back at the
    first piece of wood that rises above it (the tree keeps nothing higher), and the ``lowest`` share
    (0..1) of the branches on the trunk, the lowest first, are cut at the trunk. The trunk's first
    piece always stays. Returns how many branches were cut (written in the journal when any were)."""
    tree, now = world.tree, world.sim.state.length_time
    scene = tree.light_scene(world.clocks())
    starts = cut_points(scene, tree.lstring, keep_height, lowest)
    if len(starts) == 0:
        return 0
    ls = tree.lstring
    keep_wood(ls, scene.turtle.segments, tree.geometry_constants)
    removed = brackets.rest_of_branches(ls.sym, starts)
    tree.fallen.append(fallen_pieces(scene, removed, now))
    tree.lstring = remove_empty_branches(ls.select(~removed))
    cut = branches_cut(ls.sym, starts)
    remeasure(world)
    world.journal.write(world.sim.state.time, "pruned", float(cut), once=False)
    return cut


def cut_points(scene: LightScene, ls, keep_height: float | None, lowest: float) -> np.ndarray:
    """The modules (sorted, unique) at which the cuts start: the first piece of wood above ``keep_height``
    m on every path up the tree, and the bases of the ``lowest`` share of the trunk's branches."""
    segs = scene.turtle.segments
    wood = WOOD[ls.sym[segs.module]]
    wood[:1] = False  # the trunk's base stays
    cuts = []
    if keep_height is not None:
        above = wood & (segs.end[:, 1] > keep_height * METRE)
        cuts.append(segs.module[above & ~np.concatenate([above, [False]])[segs.parent]])  # (no parent: -1)
    if lowest > 0:
        grown = (ls.sym[segs.module] == INTERNODE) & (ls.nparams[segs.module] >= 3)
        order = params_where(ls.params, grown, ls.offsets[segs.module] + 2, 1.0)
        base = np.flatnonzero(wood & ~segs.continues & (segs.parent >= 0) & (order == 1))
        count = math.floor(lowest * len(base) + 0.5)
        if count:
            cuts.append(segs.module[base[np.argsort(segs.start[base, 1], kind="stable")[:count]]])
    return np.unique(np.concatenate(cuts)) if cuts else np.zeros(0, np.int64)


def branches_cut(sym: np.ndarray, starts: np.ndarray) -> int:
    """How many separate branches the cuts at ``starts`` (sorted) take off: a cut inside a branch another
    cut already takes is not counted again."""
    ends = brackets.branch_ends(sym, starts)
    reach = np.maximum.accumulate(ends)
    inside = np.concatenate([[False], starts[1:] < reach[:-1]])
    return int(np.count_nonzero(~inside))


def keep_wood(ls, segs, const: dict[str, float]) -> None:
    """Keep as built the wood each grown internode shows now: its pipe area where that is more than the
    wood it has built since its last ring (wood never shrinks, so a cut trunk stays as thick as it was)."""
    grown = (ls.sym[segs.module] == INTERNODE) & (ls.nparams[segs.module] >= 5)
    at = ls.offsets[segs.module[grown]] + 4
    ls.params[at] = np.maximum(ls.params[at], pipe_area(ls, segs, const)[grown])


def remeasure(world: World) -> None:
    """The carbon budget's leaf area and sapwood from the tree as it stands now (after a cut), so upkeep is
    charged on what is left; the pool and the running totals are not touched."""
    tree = world.tree
    scene = tree.light_scene(world.clocks())
    segs, ls, const = scene.turtle.segments, tree.lstring, tree.geometry_constants
    grown = (ls.sym[segs.module] == INTERNODE) & (ls.nparams[segs.module] >= 5)
    pipes = pipe_area(ls, segs, const)[grown]
    length = np.linalg.norm(segs.end - segs.start, axis=1)[grown]
    measured = carbon.canopy(scene.leaf_area, np.ones(len(scene.leaf_area)), pipes, length)
    world.carbon.leaf_area, world.carbon.sapwood = measured.leaf_area, measured.sapwood
