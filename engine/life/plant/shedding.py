"""Crown rise: a branch that pays no more dies, stands bare for a while, then falls and leaves a scar.

A lateral branch whose base internode has spent SHED of physiological time in deep shade (its leaves catch too
little of the light its pieces need; GrowingTree counts it) dies: its leaves wither and fall, its apices, buds,
blossoms and fruit are gone and its shoot units lose their leaf sites, so it grows no more. Its bare wood stays
on the tree (dead twigs linger) until its base has counted the rule ``growth.dead_linger`` more of that time
(counted only while the crown is in leaf: a branch that dies in late summer stands through the winter), then
it falls; a limb of the trunk leaves a stub of its base internode, the scar where the limb was, kept as it is
(its shade set to :data:`SCAR`, so it never counts again; :data:`STUB` of an internode long).
"""

from __future__ import annotations

import numpy as np

from arbor.engine.life.form.interpret import APEX, BLOSSOM, BUD, FRUIT, INTERNODE, LEAF, LEAF_BUD
from arbor.engine.lsystem import brackets
from arbor.engine.lsystem.lstring import LString

SCAR = -1e6  # a stub's shade: it counts up by the time in deep shade, and never gets anywhere near the SHED
SITES, KEPT, PIECES = 6, 9, 5  # a shoot unit's leaf sites and share of them in leaf; a consolidated run's length
STUB = 0.25  # a stub's length, in internode lengths of its order


def _inside(n: int, base: np.ndarray, close: np.ndarray) -> np.ndarray:
    """Positions after each of ``base`` up to (not including) its branch's closing bracket ``close``."""
    delta = np.zeros(n + 1, dtype=np.int64)
    np.add.at(delta, base + 1, 1)
    np.add.at(delta, close, -1)
    return np.cumsum(delta[:-1]) > 0


def _closing(ls: LString, base: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The bases that stand in a bracket, and each one's closing bracket."""
    close = brackets.branch_ends(ls.sym, base)
    inside = close < len(ls)
    return base[inside], close[inside]


def strip(ls: LString, params: np.ndarray, dead: np.ndarray, now: float) -> LString:
    """The branches whose base internodes are at string positions ``dead`` die: their leaves start to fall (at
    ``now``), their apices, buds, leaf buds, blossoms and fruit go, their shoot units keep no leaf sites.
    ``params`` (the string's, changed in place) are the ones returned."""
    base, close = _closing(ls, np.asarray(dead, dtype=np.int64))
    if len(base) == 0:
        return LString(ls.sym, ls.nparams, ls.offsets, params)
    within = _inside(len(ls), base, close)
    sym, count, off = ls.sym, ls.nparams, ls.offsets
    leaf = within & (sym == LEAF) & (count >= 3)
    leaf &= params[np.where(leaf, off + 2, 0)] == 0  # (leaves already falling go on falling)
    params[off[leaf] + 2] = now
    unit = within & (sym == INTERNODE) & (count >= 13)
    params[off[unit] + SITES] = 0.0
    params[off[unit] + KEPT] = 0.0
    gone = within & (((sym == APEX) & (count == 6)) | (sym == BUD) | (sym == BLOSSOM) | (sym == FRUIT)
                     | (sym == LEAF_BUD))
    kept = LString(sym, count, off, params)
    return kept.select(~gone) if gone.any() else kept


def fall(ls: LString, params: np.ndarray, dead: np.ndarray) -> tuple[LString, np.ndarray, int]:
    """The dead branches whose base internodes are at string positions ``dead`` fall. A limb of the trunk (order 1)
    leaves a stub of its base (its shade :data:`SCAR`, :data:`STUB` of an internode long: a consolidated run of that
    many pieces); a twig of a limb goes whole. Returns the string, the positions removed (a mask over the string
    it was given) and how many branches fell (one inside another that fell is not counted). ``params`` are
    changed in place."""
    base, close = _closing(ls, np.asarray(dead, dtype=np.int64))
    limb = params[ls.offsets[base] + 2] == 1
    cover = np.zeros(len(ls) + 1, dtype=np.int64)  # how many falling branches hold each position
    np.add.at(cover, brackets.match(ls.sym)[close[~limb]], 1)  # a twig: its bracket, whole
    np.add.at(cover, close[~limb] + 1, -1)
    np.add.at(cover, base[limb] + 1, 1)  # a limb: what follows its base
    np.add.at(cover, close[limb], -1)
    cover = np.cumsum(cover[:-1])
    removed = cover > 0
    fell = int(np.count_nonzero(cover[base] == np.where(limb, 0, 1)))  # (not inside another that fell)
    base = base[limb]
    off = ls.offsets[base]
    params[off + 3] = SCAR
    run = ls.nparams[base] >= 6
    params[off[run] + PIECES] = STUB
    unit = ls.nparams[base] >= 13
    params[off[unit] + SITES] = 0.0
    params[off[unit] + KEPT] = 0.0
    node = base[~run]  # a node becomes a run of STUB pieces: I(birth, girth birth, order, shade, wood, STUB)
    nparams = ls.nparams.copy()
    nparams[node] += 1
    params = np.insert(params, ls.offsets[node] + PIECES, STUB)
    stubbed = LString.from_arrays(ls.sym, nparams, params)
    return stubbed.select(~removed), removed, fell
