"""The growing tree as instance records, updated frame by frame in time proportional to what grows.

A full build (turtle, radii, leaf clusters, records) happens when the L-string changes (a rewrite, a
light reading, an edit). Between builds only the young parts move: internodes still elongating (and
what grows from them, which is younger still), leaves still unfolding or withering. Turns never depend
on lengths, so each young segment keeps its heading and only its length changes: positions follow by
a few vectorised passes over the young forest, level by level. Old wood stays where it was built; its
pipe-model radius catches up at the next build (a fraction of a percent).
"""

from __future__ import annotations

import numpy as np

from arbor.engine.geometry.instances import LeafInstances, TubeInstances, leaf_instances, tube_instances
from arbor.engine.geometry.turtle import Leaves, interpret, set_radii
from arbor.engine.life.form.interpret import (
    FRUIT,
    INTERNODE,
    LEAF,
    LEAF_ASPECT,
    Clocks,
    add_unit_leaves,
    cluster_scales,
    leaf_birth,
    leaf_clusters,
    leaf_keep,
    leaf_sizes,
    radii,
    render_view,
    saturate,
    turtle_config,
)
from arbor.engine.life.form.shoot_units import is_unit
from arbor.engine.lsystem.lstring import LString, params_where

YOUNG = 3.5  # elongation time constants: a younger internode still visibly grows (97 % grown by then)


class GrowthView:
    """Instance records of one tree (see module docstring): ``tubes``, ``leaves``, ``blossoms``, ``fruits``
    (a fruit's record keeps its ripeness 0..1 where a leaf keeps its width; ``fruit_module`` names it)."""

    def __init__(self, ls: LString, clocks: Clocks, const: dict[str, float]) -> None:
        self.lstring, self.const, self.wilt = ls, const, clocks.wilt
        self._built_T = clocks.length_time
        view = render_view(ls, clocks, const)
        turtle = add_unit_leaves(ls, interpret(view, turtle_config(const)), clocks, const)
        segs = turtle.segments
        if len(segs):
            set_radii(segs, radii(ls, segs, clocks, const))
        self.tubes: TubeInstances = tube_instances(segs)
        flex = self.tubes.data[:, 23] if len(segs) else np.zeros(0)
        leaves = leaf_clusters(turtle.leaves)
        self.leaves = self._leaf_records(turtle, leaves, flex)
        self.blossoms = self._leaf_records(turtle, turtle.blossoms, flex, aspect=1.0)
        self.fruits, self.fruit_module = self._fruit_records(ls, turtle, flex, clocks.length_time)
        self.stones = LeafInstances.empty()  # (rocks are the garden's, drawn apart)
        self.lo, self.hi = turtle.bounds()
        if len(self.leaves.data):  # the leaves' tips too: what is drawn, not just where leaves start
            tips = self.leaves.data[:, 0:3] + self.leaves.data[:, 3:6] * self.leaves.data[:, 9:10]
            self.lo, self.hi = np.minimum(self.lo, tips.min(axis=0)), np.maximum(self.hi, tips.max(axis=0))
        self._young_setup(ls, segs, clocks)
        self._leaf_setup(ls, turtle, leaves, segs)
        self._young_last()

    @staticmethod
    def _leaf_records(turtle, leaves: Leaves, flex: np.ndarray, aspect: float = LEAF_ASPECT) -> LeafInstances:
        carrier = turtle.carriers(leaves.module) if len(leaves) else np.zeros(0, np.int64)
        leaf_flex = np.where(carrier >= 0, flex[np.maximum(carrier, 0)], 0.0) if len(flex) else np.zeros(len(leaves))
        return leaf_instances(leaves, leaf_flex, aspect)

    def _fruit_records(self, ls: LString, turtle, flex: np.ndarray, now: float) -> tuple[LeafInstances, np.ndarray]:
        """Fruit hanging below the node that bears it, sized by the view, with its ripeness."""
        fruits = turtle.fruits
        if fruits is None or len(fruits) == 0:
            return LeafInstances.empty(), np.zeros(0, np.int64)
        records = self._leaf_records(turtle, fruits, flex, aspect=1.0)
        module = fruits.module
        born = np.where((ls.sym[module] == FRUIT) & (ls.nparams[module] >= 1), ls.params[ls.offsets[module]], now)
        records.data[:, 10] = np.clip((now - born) / self.const["RIPEN"], 0.0, 1.0)
        records.data[:, 1] -= 0.5 * records.data[:, 9]  # it hangs
        return records, module

    def _young_setup(self, ls: LString, segs, clocks: Clocks) -> None:
        """Which segments still grow, in levels (parents first), with what they need to move."""
        const, m = self.const, len(segs)
        self.parent = segs.parent.copy()
        module = segs.module
        grown = (ls.sym[module] == INTERNODE) & (ls.nparams[module] >= 3)
        off = ls.offsets[module]
        self.birth = params_where(ls.params, grown, off, -np.inf)
        self.order = params_where(ls.params, grown, off + 2)
        # (an internode split where a stroke joined it, or a run of several, is that many pieces long, as
        # render_view draws it: without it a young half grew to a whole internode, and a branch drawn
        # from it stood above where it was pressed)
        self.pieces = params_where(ls.params, grown & (ls.nparams[module] >= 6), off + 5, 1.0)
        young = grown & (clocks.length_time - self.birth < YOUNG * const["TAU"])
        level = np.full(m, -1, dtype=np.int64)
        frontier = np.flatnonzero(young & ((self.parent < 0) | ~young[np.maximum(self.parent, 0)]))
        depth = 0
        while len(frontier):  # the young and everything that grows from them, parents first
            level[frontier] = depth
            frontier = _children_of(self.parent, frontier, m)
            depth += 1
        self.levels = [np.flatnonzero(level == d) for d in range(depth)]
        self.young = np.flatnonzero(level >= 0)
        self.grown = grown
        direction = segs.end - segs.start
        length = np.linalg.norm(direction, axis=1)
        self.built_length = length
        self.heading = np.where((length > 1e-12)[:, None], direction / np.maximum(length, 1e-12)[:, None],
                                segs.frame[:, :, 0])
        self.start, self.end = segs.start.copy(), segs.end.copy()
        self.offset = self.start - np.where((self.parent >= 0)[:, None], self.end[np.maximum(self.parent, 0)], 0.0)

    def _leaf_setup(self, ls: LString, turtle, leaves: Leaves, segs) -> None:
        """For every leaf record: its module, its twig and where it sits on it, and its cluster scale."""
        self.leaf_module = leaves.module
        self.leaf_carrier = turtle.carriers(leaves.module) if len(leaves) else np.zeros(0, np.int64)
        ends = self.end[np.maximum(self.leaf_carrier, 0)] if len(segs) else np.zeros((len(leaves), 3))
        self.leaf_offset = leaves.position - np.where((self.leaf_carrier >= 0)[:, None], ends, 0.0)
        is_leaf = (ls.sym[leaves.module] == LEAF) & (ls.nparams[leaves.module] >= 1)
        self.leaf_birth = np.where(is_leaf | is_unit(ls, leaves.module), leaf_birth(ls, leaves.module), 0.0)
        count = len(turtle.leaves)
        self.leaf_scale = cluster_scales(turtle.leaves.module) if count else np.zeros(0)
        on_young = np.zeros(len(segs), bool)
        on_young[self.young] = True
        self.young_leaves = np.flatnonzero((self.leaf_carrier >= 0) & on_young[np.maximum(self.leaf_carrier, 0)])

    def _young_last(self) -> None:
        """Reorder the records so what moves is one block at the end of each buffer (one small write
        a frame): tubes ``young_row:``, leaves ``young_leaf_row:``."""
        m = len(self.tubes.data)
        moving = np.zeros(m, bool)
        moving[self.young] = True
        order = np.concatenate([np.flatnonzero(~moving), self.young])
        self.tubes.data, self.tubes.module = self.tubes.data[order], self.tubes.module[order]
        self.young_row = m - len(self.young)
        now = self._built_T
        k = len(self.leaf_module)
        dynamic = np.zeros(k, bool)
        dynamic[self.young_leaves] = True
        if k:
            ls, off = self.lstring, self.lstring.offsets[self.leaf_module]
            falling = np.where((self.lstring.nparams[self.leaf_module] >= 3) & ~is_unit(ls, self.leaf_module),
                               ls.params[np.minimum(off + 2, len(ls.params) - 1)], 0.0)
            dynamic |= (now - self.leaf_birth < YOUNG * self.const["TAU"]) | (falling > 0)
        leaf_order = np.concatenate([np.flatnonzero(~dynamic), np.flatnonzero(dynamic)])
        self.leaves.data = self.leaves.data[leaf_order]
        for name in ("leaf_module", "leaf_carrier", "leaf_offset", "leaf_birth", "leaf_scale"):
            setattr(self, name, getattr(self, name)[leaf_order])
        self.young_leaf_row = k - int(dynamic.sum())
        on_young = np.zeros(m, bool)
        on_young[self.young] = True
        rows = np.arange(self.young_leaf_row, k)
        carrier = self.leaf_carrier[rows]
        self.young_leaves = rows[(carrier >= 0) & on_young[np.maximum(carrier, 0)]]

    def update(self, clocks: Clocks) -> None:
        """Move the young segments and leaves to ``clocks`` (no-op for a tree that has stopped growing)."""
        const, now = self.const, clocks.length_time
        data = self.tubes.data
        if len(self.young):
            full = const["IL"] * const["IO"] ** self.order * self.pieces
            for level in self.levels:
                par = self.parent[level]
                base = np.where((par >= 0)[:, None], self.end[np.maximum(par, 0)], 0.0)
                self.start[level] = base + self.offset[level]
                length = np.where(self.grown[level], full[level] * saturate(now - self.birth[level], const["TAU"]),
                                  self.built_length[level])  # drawn pieces do not grow
                self.end[level] = self.start[level] + self.heading[level] * length[:, None]
            data[self.young_row:, 0:3] = self.start[self.young]
            data[self.young_row:, 9:12] = self.end[self.young]
        k0 = self.young_leaf_row
        if len(self.leaf_module) > k0:
            lv = self.leaves.data
            moved = self.young_leaves
            lv[moved, 0:3] = self.end[self.leaf_carrier[moved]] + self.leaf_offset[moved]
            size = (leaf_sizes(self.lstring, self.leaf_module[k0:], now, const)
                    * leaf_keep(self.leaf_birth[k0:], clocks.wilt) * self.leaf_scale[k0:])
            lv[k0:, 9] = size
            lv[k0:, 10] = size * LEAF_ASPECT


def _children_of(parent: np.ndarray, frontier: np.ndarray, m: int) -> np.ndarray:
    """All children of the segments in ``frontier`` (vectorised, for a large frontier)."""
    mark = np.zeros(m, bool)
    mark[frontier] = True
    return np.flatnonzero((parent >= 0) & mark[np.maximum(parent, 0)])
