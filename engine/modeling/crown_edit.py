"""A lobe edit regrows only that lobe's crown (issue 48): the wood a crown grew into the lobe before the
edit is taken off the tree, and the crown grows into the edited lobe alone, so the other lobes keep
their branches and leaves exactly (a whole regrowth, with every lobe's attractors drawn anew, changed
every lobe's crown when one was moved).

The crown's wood is told from the tree's own by its pieces: drawn ``F`` pieces of the tree as it grew
that the tree before the crown does not have. A lobe's wood is every crown piece inside it, with the
crown pieces outside every lobe that lead only to it (the axis bridging to it); a branch is taken off
from its first piece on (the pieces' own turn, pitch and width modules included), never a piece that
carries wood of another lobe or of the tree itself.
"""

from __future__ import annotations

import numpy as np

from arbor.engine.geometry.turtle import Segments, subtree_sums
from arbor.engine.lsystem import brackets
from arbor.engine.lsystem.lstring import LString
from arbor.engine.modeling.lobes import Crossings, Lobe
from arbor.engine.modeling.modeler import DRAWN, F_PARAMS

_PIECE = np.frombuffer(b"+&!", np.uint8)  # a crown piece's modules before its F (engine/modeling/skeleton.py)
_OPEN, _CLOSE = ord("["), ord("]")


def _pieces(ls: LString, modules: np.ndarray) -> np.ndarray:
    """The parameters of the drawn pieces ``modules``, one row of bytes each (to compare them)."""
    rows = ls.params[ls.offsets[modules][:, None] + np.arange(F_PARAMS)]
    return np.ascontiguousarray(rows).view(np.dtype((np.void, 8 * F_PARAMS))).ravel()


def crown_pieces(ls: LString, base: LString, segs: Segments) -> np.ndarray:
    """True for the segments of ``ls`` that a crown grown on ``base`` added (drawn pieces ``base`` lacks)."""
    drawn = (ls.sym[segs.module] == DRAWN) & (ls.nparams[segs.module] == F_PARAMS)
    own = np.flatnonzero((base.sym == DRAWN) & (base.nparams == F_PARAMS))
    out = np.zeros(len(segs), bool)
    out[drawn] = ~np.isin(_pieces(ls, segs.module[drawn]), _pieces(base, own))
    return out


def without_lobe_crown(ls: LString, base: LString, segs: Segments, lobes: list[Lobe], k: int) -> LString:
    """``ls`` (a crown grown on ``base`` into ``lobes``; ``segs`` its segments) without the wood its crown
    grew into lobe ``k`` (see module docstring)."""
    crown = crown_pieces(ls, base, segs)
    middle = 0.5 * (segs.start + segs.end)
    which = Crossings(lobes).inside(middle)
    in_k = crown & lobes[k].contains(middle)
    own = crown & (in_k | (which < 0))  # pieces that may go: the lobe's, and crown pieces between lobes
    bad = subtree_sums(ls, segs, (~own).astype(float))
    ours = subtree_sums(ls, segs, in_k.astype(float))
    removable = (bad < 0.5) & (ours > 0.5)
    roots = np.flatnonzero(removable & ~np.where(segs.parent >= 0, removable[np.maximum(segs.parent, 0)], False))
    if len(roots) == 0:
        return ls
    at = segs.module[roots]
    ends = brackets.branch_ends(ls.sym, at)
    keep = np.ones(len(ls) + 1, bool)
    for start, end in zip(at.tolist(), ends.tolist(), strict=True):
        while start > 0 and ls.sym[start - 1] in _PIECE and ls.nparams[start - 1] == 1:
            start -= 1
        keep[start:end] = False
    out = ls.select(keep[:-1])
    return _without_empty_brackets(out)


def _without_empty_brackets(ls: LString) -> LString:
    """``ls`` without '[' ']' pairs that hold nothing (left where a whole side branch was taken off)."""
    while True:
        empty = np.flatnonzero((ls.sym[:-1] == _OPEN) & (ls.sym[1:] == _CLOSE))
        if len(empty) == 0:
            return ls
        keep = np.ones(len(ls), bool)
        keep[empty] = keep[empty + 1] = False
        ls = ls.select(keep)
