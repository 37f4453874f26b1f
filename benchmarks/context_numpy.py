"""The best whole-array numpy version of context neighbours (O(n): sorts of small integers and running
scans), kept as the peer that engine/lsystem/context.py's compiled loop is measured against.

Modules are listed branch by branch: sorted by nesting level, then position, every branch's own
modules form one run that starts with its '[' and ends with its ']'. Each bracket is also listed a
second time, as a marker, in its parent's run, so a run holds exactly the modules along one axis
with its side branches reduced to markers. Along a run, the right neighbour is the next good module
(not a bracket, not ignored) and the left neighbour the previous one; a run with no good module before
a position continues in the parent's run before the branch's '[' (resolved level by level).
"""

from __future__ import annotations

from itertools import pairwise

import numpy as np

from arbor.engine.lsystem.brackets import CLOSE, OPEN, depths


def neighbours(sym: np.ndarray, skip: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Left and right context neighbour of every module (-1 where there is none).

    Left: the previous module on the path to the root, skipping whole branches ``[...]`` to the left
    and passing out of the enclosing branch at its '['. Right: the next module on the same axis,
    skipping whole branches; the axis ends at the ']' closing its branch. Symbols in ``skip`` (a
    boolean table indexed by symbol: the #ignore set) are passed over.
    """
    n = len(sym)
    if n == 0:
        return np.zeros(0, np.int64), np.zeros(0, np.int64)
    runs = _Runs(sym, skip)
    return runs.left(), runs.right()


class _Runs:
    """The branch-by-branch listing of a string (see module docstring) and its scans."""

    def __init__(self, sym: np.ndarray, skip: np.ndarray) -> None:
        n = len(sym)
        bracket = (sym == OPEN) | (sym == CLOSE)
        level = depths(sym).astype(np.int16)
        copies = 1 + bracket  # brackets are listed twice: marker in the parent, then in their own run
        pos = np.repeat(np.arange(n, dtype=np.int32), copies)
        first = np.cumsum(copies, dtype=np.int32) - copies  # the first copy of each module in ``pos``
        lvl = np.repeat(level, copies)
        lvl[first[bracket]] -= 1  # the marker copy lives one level up
        order = np.argsort(lvl, kind="stable").astype(np.int32)  # radix sort: by level, then position
        self.pos = pos[order]
        where = np.empty(len(order), np.int32)
        where[order] = np.arange(len(order), dtype=np.int32)
        self.own = where[first + bracket]  # each module's place in its own run
        self.marker = where[first]  # a bracket's marker in its parent's run (== own for the rest)
        kind = sym[self.pos]
        self.run = np.zeros(len(order), np.int32)  # run number of every entry; 0 is the main axis
        own_opens = self.own[sym == OPEN]
        rank = np.argsort(own_opens)
        self.opener = own_opens[rank]  # run r >= 1 starts at entry opener[r - 1]
        self.opener_marker = self.marker[sym == OPEN][rank]
        self.run[self.opener] = 1
        np.cumsum(self.run, out=self.run)
        self.good = ~(skip[kind] | (kind == OPEN) | (kind == CLOSE))
        self.level = lvl[order]
        self.sym = sym

    def right(self) -> np.ndarray:
        """Right neighbours: the next good entry in the same run, after each module's own entry
        (a ']' looks on along its parent's axis, after its marker)."""
        m = len(self.pos)
        idx = np.where(self.good, np.arange(m, dtype=np.int32), m)
        nxt = np.minimum.accumulate(idx[::-1])[::-1]
        after = np.append(nxt[1:], m)  # first good entry strictly after each entry
        start = np.where(self.sym == CLOSE, self.marker, self.own)
        found = after[start]
        ok = found < m
        ok[ok] = self.run[found[ok]] == self.run[start[ok]]
        return np.where(ok, self.pos[np.minimum(found, m - 1)], -1).astype(np.int64)

    def left(self) -> np.ndarray:
        """Left neighbours: the previous good entry in the same run, before each module's own entry
        (a '[' looks back along its parent's axis, before its marker); a run with none there takes
        the left neighbour of its '['."""
        m = len(self.pos)
        idx = np.where(self.good, np.arange(m, dtype=np.int32), -1)
        before = np.append(-1, np.maximum.accumulate(idx)[:-1])  # last good entry strictly before
        start = np.where(self.sym == OPEN, self.marker, self.own)
        inherited = self._inherited(before)
        found = before[start]
        ok = found >= 0
        ok[ok] = self.run[found[ok]] == self.run[start[ok]]
        return np.where(ok, self.pos[np.maximum(found, 0)], inherited[self.run[start]]).astype(np.int64)

    def _inherited(self, before: np.ndarray) -> np.ndarray:
        """For every run, the left neighbour of its '[': found before the marker in the parent run, or
        inherited from the parent run in turn (runs are resolved level by level, parents first)."""
        runs = len(self.opener) + 1
        out = np.full(runs, -1, np.int64)
        if runs == 1:
            return out
        found = before[self.opener_marker]
        parent = self.run[self.opener_marker]
        ok = found >= 0
        ok[ok] = self.run[found[ok]] == parent[ok]
        cand = np.where(ok, self.pos[np.maximum(found, 0)], -1)
        lv = self.level[self.opener]
        order = np.argsort(lv, kind="stable")
        bounds = np.searchsorted(lv[order], np.arange(int(lv.max()) + 2))
        for a, b in pairwise(bounds):  # one pass per nesting level
            r = order[a:b]
            out[r + 1] = np.where(cand[r] >= 0, cand[r], out[parent[r]])
        return out
