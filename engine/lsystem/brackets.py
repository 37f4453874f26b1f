"""Vectorised bracket structure of an L-string: depth, matching brackets, parents, context neighbours.

All functions are O(n log n) numpy at most, with no Python loop over modules, so the derivation and
the simulation can use them on million-module strings (context neighbours are in context.py, O(n)).
"""

from __future__ import annotations

import numpy as np

OPEN = ord("[")
CLOSE = ord("]")


class BracketError(ValueError):
    """The string's brackets do not balance; ``index`` is the first offending module."""

    def __init__(self, message: str, index: int) -> None:
        super().__init__(message)
        self.index = index


def depths(sym: np.ndarray) -> np.ndarray:
    """Nesting depth of every module; a bracket has the depth of the branch it opens or closes."""
    step = (sym == OPEN).astype(np.int32) - (sym == CLOSE).astype(np.int32)
    after = np.cumsum(step, dtype=np.int32)
    return np.where(sym == CLOSE, after + 1, after)


def check_balanced(sym: np.ndarray, d: np.ndarray | None = None) -> np.ndarray:
    """Raise :class:`BracketError` if brackets do not balance; else return the depths (``d`` if given)."""
    d = depths(sym) if d is None else d
    is_close = sym == CLOSE
    bad = np.flatnonzero(is_close & (d <= 0))
    if len(bad):
        raise BracketError("']' without a matching '['", int(bad[0]))
    final = int(np.count_nonzero(sym == OPEN)) - int(np.count_nonzero(is_close))
    if final:
        opens = np.flatnonzero(sym == OPEN)
        raise BracketError("'[' is never closed", int(opens[-1]) if len(opens) else 0)
    return d


def _by_depth(idx: np.ndarray, d: np.ndarray) -> np.ndarray:
    """``idx`` (ascending) reordered by depth, keeping position order within a depth.

    A stable sort of small integers is a radix sort in numpy: ~10x faster than sorting int64 keys.
    """
    small = np.int16 if len(d) == 0 or int(d.max(initial=0)) < 32767 else np.int64
    return idx[np.argsort(d[idx].astype(small), kind="stable")]


def match(sym: np.ndarray, d: np.ndarray | None = None) -> np.ndarray:
    """For every bracket, the index of its partner; -1 for other modules. Assumes balance."""
    n = len(sym)
    out = np.full(n, -1, dtype=np.int64)
    opens = np.flatnonzero(sym == OPEN)
    if len(opens) == 0:
        return out
    closes = np.flatnonzero(sym == CLOSE)
    d = depths(sym) if d is None else d
    # brackets of one depth alternate open, close, open, close... in position order
    opens_sorted = _by_depth(opens, d)
    closes_sorted = _by_depth(closes, d)
    out[opens_sorted] = closes_sorted
    out[closes_sorted] = opens_sorted
    return out


def branch_ends(sym: np.ndarray, idx: np.ndarray, d: np.ndarray | None = None,
                depth: np.ndarray | None = None) -> np.ndarray:
    """For the modules ``idx``, the index of the ']' that closes the branch each lies in (``len(sym)``
    on the main axis): the module and everything after it up to there grows from it.

    A bracket itself counts as lying in the branch it opens/closes. ``depth`` (one per module of
    ``idx``) asks instead for the end of the enclosing branch at that depth (0: the main axis).
    """
    n = len(sym)
    d = depths(sym) if d is None else d
    closes = _by_depth(np.flatnonzero(sym == CLOSE), d)
    key = d[closes].astype(np.int64) * (n + 1) + closes
    depth = (d[idx] if depth is None else depth).astype(np.int64)
    pos = np.searchsorted(key, depth * (n + 1) + idx)
    found = np.minimum(pos, len(closes) - 1) if len(closes) else pos
    end = closes[found] if len(closes) else np.full(len(idx), n)
    return np.where(depth > 0, end, n)


def rest_of_branches(sym: np.ndarray, starts: np.ndarray) -> np.ndarray:
    """Mask of the modules from each of ``starts`` up to the ']' closing its branch (the end of the
    string on the main axis): what a cut at those modules removes."""
    delta = np.zeros(len(sym) + 1, dtype=np.int64)
    np.add.at(delta, starts, 1)
    np.add.at(delta, branch_ends(sym, starts), -1)
    return np.cumsum(delta[:-1]) > 0

