"""A drawn crown's leaves held within its lobes (issue 48): every leaf a crown grows at a branch tip is
sized to the room its lobe leaves it, so the foliage, which is what an artist sees, keeps to the drawn
outline (a game leaf is 1.2 units long, a drawn lobe often 1.5 units across: at full size the leaf
cards stood up to 56 % of the outline's size outside it).

A leaf is drawn as a cluster of blades (:func:`~arbor.engine.life.form.interpret.leaf_clusters`); its
size is the largest of :data:`SCALES` at which every corner of every blade, fully grown, lies inside a
lobe, turned off its twig by the first of :data:`PITCHES` that gives it that size (a tip near the lobe's
surface points outward: its leaf turned back along the twig keeps more of its size). The size is the
leaf's vigour, its second parameter (``L(birth, vigour)``), which the game's interpretation already
multiplies its length by.
"""

from __future__ import annotations

import numpy as np

from arbor.engine.geometry.turtle import Leaves, interpret
from arbor.engine.life.form.interpret import (
    LEAF_ASPECT,
    Clocks,
    leaf_clusters,
    render_view,
    turtle_config,
)
from arbor.engine.lsystem.lstring import LString, replace_modules
from arbor.engine.modeling.lobes import Crossings, Lobe

LEAF, PITCH = ord("L"), ord("&")
PITCHES = (45.0, 80.0, 115.0, 150.0)  # degrees off its twig a crown leaf is turned, tried in this order
SCALES = (1.0, 0.85, 0.7, 0.55, 0.42, 0.32, 0.24, 0.18, 0.12)  # leaf sizes tried, largest first
SMALLEST = min(SCALES)  # a leaf with no room at all (its tip outside every lobe) is this small


def blade_corners(leaves: Leaves, length: float) -> tuple[np.ndarray, np.ndarray]:
    """For leaves fully grown to ``length``: each blade's base and its four corners' offsets from it
    (blades, 4, 3), and the leaf module of each blade (the quads of engine/geometry/mesh.py leaf_mesh)."""
    full = Leaves(leaves.position, leaves.frame, np.full(len(leaves), float(length)), leaves.module)
    blades = leaf_clusters(full)
    h, lft = blades.frame[:, :, 0], blades.frame[:, :, 1]
    s = blades.size[:, None]
    half = lft * s * LEAF_ASPECT * 0.5
    offsets = np.stack([-half, half, half + h * s, -half + h * s], axis=1)
    return np.broadcast_to(blades.position[:, None], offsets.shape), offsets, blades.module


def room_scales(bases: np.ndarray, offsets: np.ndarray, owner: np.ndarray, count: int,
                crossings: Crossings) -> np.ndarray:
    """For ``count`` leaves (``owner``: the leaf of each blade), the largest of SCALES at which all corners
    ``bases + scale * offsets`` of all its blades lie inside a lobe of ``crossings`` (SMALLEST when none
    fits): a binary search over SCALES, all leaves at once (a leaf's room shrinks as it grows)."""
    grid = np.sort(np.asarray(SCALES))
    lo, hi = np.full(count, -1), np.full(count, len(grid))
    while (hi - lo > 1).any():
        mid = (lo + hi) // 2
        searching = hi - lo > 1
        scale = grid[np.clip(mid, 0, len(grid) - 1)][owner][:, None, None]
        points = (bases + scale * offsets).reshape(-1, 3)
        inside = (crossings.inside(points) >= 0).reshape(len(bases), -1).all(axis=1)
        fits = np.ones(count, bool)
        np.logical_and.at(fits, owner, inside)
        lo = np.where(searching & fits, mid, lo)
        hi = np.where(searching & ~fits, mid, hi)
    return grid[np.maximum(lo, 0)]


def fit_crown_leaves(ls: LString, clocks: Clocks, const: dict[str, float], lobes: list[Lobe],
                     birth: float, size: float = 1.0) -> LString:
    """``ls`` with the leaves a crown just grew (one parameter, ``L(birth)``, after a pitch ``&``) as
    ``L(birth, size)``, each turned (one of PITCHES off its twig) and sized so that it is as large as its
    lobes leave room for when fully grown, at most ``size`` times the species' leaf (see module docstring)."""
    idx = np.flatnonzero((ls.sym == LEAF) & (ls.nparams == 1))
    idx = idx[np.isclose(ls.params[ls.offsets[idx]], birth, rtol=1e-12, atol=1e-9)]
    idx = idx[(idx > 0) & (ls.sym[idx - 1] == PITCH) & (ls.nparams[idx - 1] == 1)]
    if len(idx) == 0 or not lobes:
        return ls
    view = render_view(ls, clocks, const)
    config = turtle_config(const)
    scale, pitch = np.zeros(len(idx)), np.full(len(idx), PITCHES[0])
    crossings = Crossings(lobes)
    for angle in PITCHES:
        view.params[view.offsets[idx - 1]] = angle
        found = interpret(view, config).leaves
        at = np.minimum(np.searchsorted(idx, found.module), len(idx) - 1)
        ours = idx[at] == found.module
        leaves = Leaves(found.position[ours], found.frame[ours], found.size[ours], found.module[ours])
        bases, offsets, module = blade_corners(leaves, const["LS"] * size)
        fit = room_scales(bases, offsets, np.searchsorted(idx, module), len(idx), crossings)
        better = fit > scale + 1e-9
        scale[better], pitch[better] = fit[better], angle
    out = replace_modules(ls, idx, LEAF, np.column_stack([np.full(len(idx), birth), scale * size]))
    out.params[out.offsets[idx - 1]] = pitch
    return out
