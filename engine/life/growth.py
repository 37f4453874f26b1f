"""Smooth, bounded growth of the game tree (fixes seed 003's jumps, cones and twigs).

The L-string stores *birth times*, not sizes: internodes ``I(bT, bG, order)``, leaves ``L(bT)``,
apices and dormant buds. Sizes are continuous functions of the tree's clocks, evaluated for every frame:

* internode length = IL * IO^order * (1 - exp(-age / TAU)): zero at birth, saturating (no F(l*k) cones);
* radius from the pipe model: wood area = TIP^2 * (leaves carried above) * (1 + rings), where each
  internode's leaf counts in proportion to its own growth, so new shoots thicken their parents
  continuously (never a jump when a tip stops being a tip), and rings = GMAX * (1 - exp(-girth age / GT))
  is secondary growth driven by the water clock: older wood is thicker, by at most (1 + GMAX) in area;
* leaf size = LS * (1 - exp(-age / TAU)), shrinking away as the tree wilts (leaf fall), and branches
  droop with wilt.

New modules are born at zero size, so topology changes (rewrites) never make geometry jump.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from engine.geometry.mesh import LOD_LEVELS, tree_mesh
from engine.geometry.tree import TreeGeometry
from engine.geometry.turtle import TurtleConfig, interpret, set_radii, subtree_sums
from engine.lsystem.derive import Deriver, StepReport
from engine.lsystem.lstring import LString, replace_modules
from engine.lsystem.lsys import LSystem

INTERNODE, LEAF, BLOSSOM, PITCH = ord("I"), ord("L"), ord("K"), ord("&")
GEOMETRY_DEFAULTS = {"IL": 1.0, "IO": 0.72, "LS": 1.2, "TIP": 0.012, "GMAX": 3.0, "GT": 200.0, "TAU": 4.0}
DROOP = 0.6  # branch and leaf angles grow by this fraction at full wilt


@dataclass
class Clocks:
    """The tree's two growth clocks and its wilt, as the renderer sees them (possibly interpolated)."""

    length_time: float
    girth_time: float
    wilt: float = 0.0


class GrowingTree:
    """An L-string that grows by rewrites driven by the simulation's clocks, inside a module budget."""

    def __init__(self, system: LSystem, seed: int | None = None, lstring: LString | None = None,
                 budget: int | None = None) -> None:
        self.system = system
        self.deriver = Deriver(system, seed=seed, budget=budget)
        self.lstring = system.axiom if lstring is None else lstring
        self.last_rewrite_T = 0.0
        self.last_report: StepReport | None = None
        self.geometry_constants = {k: system.constants.get(k, v) for k, v in GEOMETRY_DEFAULTS.items()}

    @property
    def budget_hit(self) -> bool:
        """True when the last rewrite was held back by the module budget."""
        return bool(self.last_report and self.last_report.budget_hit)

    def rewrite(self, length_time: float, girth_time: float, resources: float) -> StepReport:
        """One derivation step at the given clocks (new modules are born now)."""
        extern = {"T": length_time, "G": girth_time, "DT": length_time - self.last_rewrite_T, "R": resources}
        self.lstring, self.last_report = self.deriver.step(self.lstring, extern)
        self.last_rewrite_T = length_time
        return self.last_report

    def render_view(self, clocks: Clocks) -> LString:
        """The L-string the turtle draws at these clocks: ages turned into lengths and leaf sizes."""
        return render_view(self.lstring, clocks, self.geometry_constants)

    def geometry(self, clocks: Clocks, lod: int = 0) -> TreeGeometry:
        """Turtle output and meshes of the tree at these clocks."""
        return grow_geometry(self.lstring, clocks, self.geometry_constants, lod)


def _saturate(age: np.ndarray, tau: float) -> np.ndarray:
    return 1.0 - np.exp(-np.maximum(age, 0.0) / tau)


def _leaf_keep(birth: np.ndarray, wilt: float) -> np.ndarray:
    """1 for leaves still on the tree; falls continuously to 0 as wilt passes each leaf's own threshold."""
    h = np.modf(np.abs(np.sin(birth * 12.9898 + 1.0) * 43758.5453))[0]
    return np.clip((h + 0.1 - 1.1 * wilt) / 0.1, 0.0, 1.0)


def render_view(ls: LString, clocks: Clocks, const: dict[str, float]) -> LString:
    """Map I -> F(length), L(birth) -> L(size) and K(birth) -> K(size) at the given clocks; droop pitch
    angles with wilt."""
    now = clocks.length_time
    idx = np.flatnonzero((ls.sym == INTERNODE) & (ls.nparams == 3))
    birth, order = ls.params[ls.offsets[idx]], ls.params[ls.offsets[idx] + 2]
    length = const["IL"] * const["IO"] ** order * _saturate(now - birth, const["TAU"])
    view = replace_modules(ls, idx, ord("F"), length[:, None])
    leaves = np.flatnonzero((view.sym == LEAF) & (view.nparams == 1))
    lb = view.params[view.offsets[leaves]]
    view.params[view.offsets[leaves]] = const["LS"] * _saturate(now - lb, const["TAU"]) * _leaf_keep(lb, clocks.wilt)
    blossoms = np.flatnonzero((view.sym == BLOSSOM) & (view.nparams == 1))  # K(birth) from region edits
    kb = view.params[view.offsets[blossoms]]
    opened = _saturate(now - kb, const["TAU"]) * _leaf_keep(kb, clocks.wilt)
    view.params[view.offsets[blossoms]] = 0.4 * const["LS"] * opened
    if clocks.wilt > 0:
        view.params[view.offsets[_droop_angles(ls)]] *= 1.0 + DROOP * clocks.wilt
    return view


def _radii(ls: LString, view: LString, segs, clocks: Clocks, const: dict[str, float]) -> np.ndarray:
    """Pipe-model radii for grown internodes; drawn pieces (modeler F) keep at least their drawn width."""
    grown = (ls.sym[segs.module] == INTERNODE) & (ls.nparams[segs.module] == 3)
    offsets = ls.offsets[segs.module]
    seg_len = np.linalg.norm(segs.end - segs.start, axis=1)
    order = np.where(grown, ls.params[np.where(grown, offsets + 2, 0)], 0.0)
    girth_birth = np.where(grown, ls.params[np.where(grown, offsets + 1, 0)], 0.0)
    full = const["IL"] * const["IO"] ** order
    weight = np.where(grown, seg_len / full, 0.0)  # each internode feeds one leaf, as far as it has grown
    drawn = ~grown & (ls.sym[segs.module] == ord("F")) & (ls.nparams[segs.module] == 11)
    drawn_below = np.bincount(segs.parent[drawn & (segs.parent >= 0)], minlength=len(segs)) > 0
    weight[drawn & ~drawn_below] = 1.0  # a drawn tip (a stroke's or a crown's) feeds one leaf's pipes
    pipes = const["TIP"] ** 2 * np.maximum(subtree_sums(view, segs, weight), 1e-6)
    rings = const["GMAX"] * _saturate(clocks.girth_time - girth_birth, const["GT"])
    radius = np.sqrt(pipes * (1.0 + rings))
    return np.where(grown, radius, np.maximum(radius, segs.radius))


def _droop_angles(ls: LString) -> np.ndarray:
    """The branch and leaf angles that droop with wilt: a '&' right before a bud, a leaf or a grown
    apex. Drawn (modeler) geometry keeps its shape."""
    pitch = np.flatnonzero((ls.sym[:-1] == PITCH) & (ls.nparams[:-1] == 1))
    nxt = pitch + 1
    carried = (ls.sym[nxt] == ord("D")) | (ls.sym[nxt] == LEAF) | ((ls.sym[nxt] == ord("A")) & (ls.nparams[nxt] == 3))
    return pitch[carried]


def grow_geometry(ls: LString, clocks: Clocks, const: dict[str, float], lod: int = 0) -> TreeGeometry:
    """Turtle and meshes of the growing tree, with continuous pipe-model radii (see module docstring)."""
    view = render_view(ls, clocks, const)
    turtle = interpret(view, TurtleConfig(pipe_model=False, leaves_at_tips=0, leaf_size=const["LS"], width=0.0))
    segs = turtle.segments
    if len(segs):
        set_radii(segs, _radii(ls, view, segs, clocks, const))
    level = LOD_LEVELS[max(0, min(lod, len(LOD_LEVELS) - 1))]
    return TreeGeometry(turtle, tree_mesh(turtle, level))
