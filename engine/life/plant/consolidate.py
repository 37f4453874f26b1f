"""Old wood consolidated: straight, bare runs of old internodes merged into one piece, so the module
budget goes to the living crown and never decides the form.

A node of the living tree costs a few modules even when its leaf and bud are long gone: the internode
and the turns before it (``+(h)^(u)/(roll)I(...)`` on the trunk, ``+(h)^(u)I(...)`` on a branch). Once a
run of internodes on one axis is old (fully grown: ``OLD_TAUS`` elongation time constants) and bare (no
bracket between them: nothing grows from it any more), and the turns between them are small, the run
becomes one internode that counts its pieces (the 6th parameter ``n``: its length is ``n`` internodes'),
keeps the oldest birth (its age), the base's wood (its girth) and shade (what sheds the branch), and
carries the rolls of the pieces it swallowed in its own roll (a roll turns about the heading, so it moves
past a straight piece exactly). Only the small pitches and yaws between pieces are lost (at most
``STRAIGHT_DEG`` each). Vectorised: one pass of numpy over the string.
"""

from __future__ import annotations

import numpy as np

from arbor.engine.life.form.interpret import INTERNODE
from arbor.engine.lsystem.lstring import LString, params_where

OLD_TAUS = 6.0  # an internode this many elongation time constants old is fully grown (99.75 %)
STRAIGHT_DEG = 1.0  # turns between two pieces at most this large (degrees) count as a straight run
MAX_PIECES = 12.0  # a consolidated internode holds at most this many pieces
YAW, PITCH, ROLL = ord("+"), ord("^"), ord("/")


def consolidated(ls: LString, now: float, tau: float) -> tuple[LString, int]:
    """``ls`` with its old straight bare runs merged (see the module docstring); returns the new string
    and how many modules it saved."""
    node = np.flatnonzero((ls.sym == INTERNODE) & (ls.nparams >= 5) & (ls.nparams <= 6))  # (not shoot units)
    if len(node) < 2:
        return ls, 0
    params, off = ls.params, ls.offsets
    pieces = params_where(params, ls.nparams[node] >= 6, off[node] + 5, 1.0)
    can, rolled = _joins(ls, node, now - params[off[node]] > OLD_TAUS * tau)
    own_roll = (node >= 1) & (ls.sym[np.maximum(node - 1, 0)] == ROLL) & (ls.nparams[np.maximum(node - 1, 0)] == 1)
    joins = _rolls_landed(can, rolled, own_roll)
    head = _heads(joins)
    total = np.cumsum(pieces)
    in_run = total - (total[head] - pieces[head])
    joins &= in_run <= MAX_PIECES  # longer runs keep their taper in pieces of at most MAX_PIECES
    if not joins.any():
        return ls, 0
    return _merged(ls, node, joins, _heads(joins), pieces)


def _joins(ls: LString, node: np.ndarray, old: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per internode: whether it may join the one before it (both old, same order, nothing but small turns
    between), and whether a roll stands between them."""
    sym, npar, off, params = ls.sym, ls.nparams, ls.offsets, ls.params
    prev = np.concatenate([[node[0]], node[:-1]])
    gap = node - prev - 1  # modules between the two internodes
    order = params[off[node] + 2]
    ok = old & np.concatenate([[False], old[:-1]]) & ((gap == 2) | (gap == 3))
    ok &= np.concatenate([[False], order[1:] == order[:-1]])
    last = len(ls) - 1  # (a saved string may end in internodes: no turn after the last one)
    yaw, pitch, roll = prev + 1, np.minimum(prev + 2, last), np.minimum(prev + 3, last)
    ok &= (sym[yaw] == YAW) & (sym[pitch] == PITCH) & (npar[yaw] == 1) & (npar[pitch] == 1)
    ok &= (np.abs(params_where(params, ok, off[yaw])) <= STRAIGHT_DEG)
    ok &= (np.abs(params_where(params, ok, off[pitch])) <= STRAIGHT_DEG)
    rolled = gap == 3
    ok &= ~rolled | ((sym[roll] == ROLL) & (npar[roll] == 1))
    ok[0] = False
    return ok, rolled & ok


def _rolls_landed(can: np.ndarray, rolled: np.ndarray, own_roll: np.ndarray) -> np.ndarray:
    """The joins kept so that every swallowed roll lands in the roll before its run's head (a piece whose
    run has no roll to take its own starts a run of its own); a few passes settle it."""
    joins = can
    for _ in range(8):
        settled = can & (~rolled | own_roll[np.concatenate([[0], _heads(joins)[:-1]])])
        if np.array_equal(settled, joins):
            break
        joins = settled
    return joins & (~rolled | own_roll[np.concatenate([[0], _heads(joins)[:-1]])])


def _heads(joins: np.ndarray) -> np.ndarray:
    """For every internode, the index (in the internode list) of the first piece of its run."""
    return np.maximum.accumulate(np.where(~joins, np.arange(len(joins)), 0))


def _merged(ls: LString, node: np.ndarray, joins: np.ndarray, head: np.ndarray,
            pieces: np.ndarray) -> tuple[LString, int]:
    """Drop the joined pieces and the turns before them; heads get their run's piece count and rolls."""
    sym, off = ls.sym, ls.offsets
    params = ls.params.copy()
    joined = np.flatnonzero(joins)
    first = np.unique(head[joined])  # heads of merged runs
    prev = node[joined - 1]
    drop = np.zeros(len(ls), bool)
    drop[node[joined]] = True
    for k in (1, 2, 3):  # the turns between a joined piece and the piece before it
        at = prev + k
        drop[at[at < node[joined]]] = True
    roll_at = prev + 3
    has_roll = roll_at < node[joined]
    rolls = np.bincount(head[joined][has_roll], params[off[roll_at[has_roll]]], minlength=len(node))
    head_roll = node[first] - 1
    with_roll = (head_roll >= 0) & (sym[np.maximum(head_roll, 0)] == ROLL)
    params[off[head_roll[with_roll]]] += rolls[first[with_roll]]
    total = np.bincount(head, pieces, minlength=len(node))
    keep = ~drop
    out = LString(ls.sym, ls.nparams, ls.offsets, params).select(keep)
    heads_new = np.cumsum(keep)[node[first]] - 1
    return _with_pieces(out, heads_new, total[first]), int(drop.sum())


def _with_pieces(ls: LString, idx: np.ndarray, count: np.ndarray) -> LString:
    """``ls`` with internodes ``idx`` given ``n = count`` as their 6th parameter (appended where they have 5)."""
    npar = ls.nparams.astype(np.int64)
    params = ls.params.copy()
    six = npar[idx] >= 6
    params[ls.offsets[idx[six]] + 5] = count[six]
    if six.all():
        return LString(ls.sym, ls.nparams, ls.offsets, params)
    grow = idx[~six]
    merged = np.insert(params, ls.offsets[grow] + 5, count[~six])
    npar[grow] = 6
    return LString.from_arrays(ls.sym, npar.astype(ls.nparams.dtype), merged)
