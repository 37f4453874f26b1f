"""The interpretation stage of the living tree: ages in the L-string turned into lengths, sizes and radii.

The living L-string stores birth times and states (see engine/life/plant/growth.py); this stage maps
them, at given clocks, to the lengths, leaf sizes and radii the turtle draws (L-Py's interpretation
step), and builds the turtle output and meshes from them. The plant uses it to see itself (light,
regions); the renderer uses it, through GrowthView, to draw.
"""

from __future__ import annotations

import functools
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from arbor.engine.base.assets import assets_dir
from arbor.engine.base.errors import LSysError
from arbor.engine.geometry.mesh import lod_level, tree_mesh
from arbor.engine.geometry.tree import TreeGeometry
from arbor.engine.geometry.turtle import (
    Leaves,
    Segments,
    TurtleConfig,
    TurtleResult,
    interpret,
    set_radii,
    subtree_sums,
)
from arbor.engine.life.form import shoot_units
from arbor.engine.lsystem import brackets
from arbor.engine.lsystem.lstring import LString, params_where, replace_modules
from arbor.engine.lsystem.lsys import load_lsystem

INTERNODE, LEAF, BLOSSOM, PITCH, APEX, BUD, FRUIT, LEAF_BUD = (ord(c) for c in "ILK&ADOV")
FRUIT_SIZE = 0.55  # a ripe fruit's diameter, in leaf lengths
# The constants the interpretation reads: named here, valued only in the species' .lsys #defines (the
# game's trees define them all; what an .lsys leaves out it takes from the reference species below).
# BHL: apical control of the Borchert-Honda vigour sharing (engine/life/plant/vigour.py); LAM0..LAM4: the
# modeler's lambda(s), growth points per scene unit at 0, 1/4, 1/2, 3/4, 1 of a drawn axis (Wakabayashi &
# Durikovic; engine/modeling/modeler.py ModelerSettings.for_species); P, MAXO, QG: the plastochron, the highest
# growing branch order and the light an apex needs, which the host reads too (new shoots, crown growth, carbon).
CONSTANT_NAMES = ("IL", "IO", "LS", "TIP", "GMAX", "GT", "TAU", "LFADE", "SHED", "SHQ", "PHOTO", "PHOTOB", "UPW",
                  "UPB", "RING", "STRAIGHT", "SUNW", "LIGHTW", "RIPEN", "BHL", "LAM0", "LAM1", "LAM2", "LAM3", "LAM4",
                  "P", "MAXO", "QG")
REFERENCE_SPECIES = "game_tree.lsys"  # in assets/lsystems: it defines every one of CONSTANT_NAMES


@functools.cache
def _reference() -> tuple[tuple[str, float], ...]:
    system = load_lsystem(assets_dir() / "lsystems" / REFERENCE_SPECIES)
    missing = [k for k in CONSTANT_NAMES if k not in system.constants]
    if missing:
        raise LSysError(f"the reference species must #define {', '.join(missing)} (engine/life/form/interpret.py "
                        "reads them)", system.file)
    return tuple((k, float(system.constants[k])) for k in CONSTANT_NAMES)


def reference_constants() -> dict[str, float]:
    """The interpretation constants of the reference species (its #defines of CONSTANT_NAMES), read once."""
    return dict(_reference())


def interpretation_constants(constants: Mapping[str, float]) -> dict[str, float]:
    """The interpretation constants a tree with these .lsys ``constants`` is drawn with: its own #defines,
    and the reference species' for any it leaves out (an imported .lsys, an old save's embedded source)."""
    return {k: float(constants.get(k, v)) for k, v in _reference()}


DROOP = 0.6  # branch and leaf angles grow by this fraction at full wilt
LEAF_ASPECT = 0.5  # leaf quads are half as wide as long (engine/geometry/mesh.py)
CLUSTER_ANGLES = (0.0, 38.0, -38.0)  # degrees the blades of one leaf cluster fan out
CLUSTER_SIZES = (1.0, 0.8, 0.8)
CLUSTER_AREA = sum(s * s for s in CLUSTER_SIZES)


@dataclass
class Clocks:
    """The tree's two growth clocks and its wilt, as the renderer sees them (possibly interpolated)."""

    length_time: float
    girth_time: float
    wilt: float = 0.0


def leaf_clusters(leaves: Leaves) -> Leaves:
    """Every leaf module as a small cluster of blades fanned around its stalk (denser, more natural
    foliage for the same modules), each blade a little different in size and angle."""
    k = len(leaves)
    if k == 0:
        return leaves
    jitter = _cluster_jitter(leaves.module)
    h, lft = leaves.frame[:, :, 0], leaves.frame[:, :, 1]
    frames = []
    for angle in CLUSTER_ANGLES:
        a = np.radians(angle * (1.0 + 0.4 * jitter))[:, None]
        frame = leaves.frame.copy()
        frame[:, :, 0] = h * np.cos(a) + lft * np.sin(a)
        frame[:, :, 1] = lft * np.cos(a) - h * np.sin(a)
        frames.append(frame)
    n = len(CLUSTER_ANGLES)
    return Leaves(np.tile(leaves.position, (n, 1)), np.concatenate(frames),
                  np.tile(leaves.size, n) * cluster_scales(leaves.module), np.tile(leaves.module, n))


def cluster_scales(modules: np.ndarray) -> np.ndarray:
    """Size factor of every blade :func:`leaf_clusters` makes from leaves ``modules`` (same order)."""
    jitter = _cluster_jitter(modules)
    return np.concatenate([scale * (1.0 + 0.25 * jitter) for scale in CLUSTER_SIZES])


def _cluster_jitter(modules: np.ndarray) -> np.ndarray:
    return np.modf(np.abs(np.sin(modules * 78.233 + 0.5) * 43758.5453))[0] - 0.5  # -0.5..0.5


def turtle_config(const: dict[str, float]) -> TurtleConfig:
    """The turtle settings the living tree is drawn with: radii come from :func:`radii`, leaves are modules."""
    return TurtleConfig(pipe_model=False, leaves_at_tips=0, leaf_size=const["LS"], width=0.0)


def saturate(age: np.ndarray, tau: float) -> np.ndarray:
    """Share of its full size a part of this age has reached: 0 at birth, 1 - 1/e after ``tau``, never 1."""
    return 1.0 - np.exp(-np.maximum(age, 0.0) / tau)


def leaf_keep(birth: np.ndarray, wilt: float) -> np.ndarray:
    """1 for leaves still on the tree; falls continuously to 0 as wilt passes each leaf's own threshold."""
    h = np.modf(np.abs(np.sin(birth * 12.9898 + 1.0) * 43758.5453))[0]
    return np.clip((h + 0.1 - 1.1 * wilt) / 0.1, 0.0, 1.0)


def leaf_sizes(ls: LString, idx: np.ndarray, now: float, const: dict[str, float]) -> np.ndarray:
    """Leaf length without wilt: unfolding from zero, times its vigour, withering once it falls. For a shoot
    unit among ``idx`` (its leaves' module), the length of the leaves it bears (engine/life/form/shoot_units.py)."""
    off, count = ls.offsets[idx], ls.nparams[idx]
    unit = shoot_units.is_unit(ls, idx)
    birth = ls.params[np.where(unit, off + shoot_units.LEAF_BIRTH, off)] if len(idx) else np.zeros(0)
    vigour_at = np.where(unit, off + shoot_units.LEAF_SIZE, np.where(count >= 2, off + 1, off))
    vigour = np.where(unit | (count >= 2), ls.params[vigour_at] if len(idx) else 0.0, 1.0)
    falling = np.where(~unit & (count >= 3), ls.params[np.where(count >= 3, off + 2, off)] if len(idx) else 0.0, 0.0)
    wither = np.where(falling > 0, np.clip(1.0 - (now - falling) / const["LFADE"], 0.0, 1.0), 1.0)
    return const["LS"] * vigour * saturate(now - birth, const["TAU"]) * wither


def leaf_birth(ls: LString, idx: np.ndarray) -> np.ndarray:
    """When each leaf of modules ``idx`` (leaf modules or shoot units) last unfolded."""
    unit = shoot_units.is_unit(ls, idx)
    if len(ls.params) == 0:
        return np.zeros(len(idx))
    at = np.where(unit, ls.offsets[idx] + shoot_units.LEAF_BIRTH, ls.offsets[idx])
    return ls.params[np.minimum(at, len(ls.params) - 1)]


def leaf_area(ls: LString, now: float, const: dict[str, float]) -> float:
    """Area (scene units²) of the leaf clusters of ``ls`` at length time ``now``, wilt ignored (no turtle needed):
    its leaf modules' and the leaves its shoot units bear."""
    idx = np.flatnonzero((ls.sym == LEAF) & (ls.nparams >= 1))
    units = shoot_units.unit_modules(ls)
    row, _, bears = shoot_units.sites(ls, units)
    borne = np.bincount(row[bears], minlength=len(units))
    sizes = np.concatenate([leaf_sizes(ls, idx, now, const), np.repeat(leaf_sizes(ls, units, now, const), borne)])
    return float((CLUSTER_AREA * LEAF_ASPECT * sizes ** 2).sum())


def add_unit_leaves(ls: LString, turtle: TurtleResult, clocks: Clocks, const: dict[str, float]) -> TurtleResult:
    """``turtle`` (of ``ls``'s view) with the leaves its shoot units bear, sized as leaf modules of theirs
    would be at these clocks (wilt included)."""
    units = turtle.segments.module[shoot_units.is_unit(ls, turtle.segments.module)]
    if len(units) == 0:
        return turtle
    sizes = leaf_sizes(ls, units, clocks.length_time, const) * leaf_keep(leaf_birth(ls, units), clocks.wilt)
    return shoot_units.with_unit_leaves(ls, turtle, sizes)


def render_view(ls: LString, clocks: Clocks, const: dict[str, float]) -> LString:
    """Map I -> F(length), L(...) -> L(size), K(birth) -> K(size) and O(birth) -> O(size) at the given
    clocks; droop pitch angles with wilt."""
    now = clocks.length_time
    idx = np.flatnonzero((ls.sym == INTERNODE) & (ls.nparams >= 3))
    birth, order = ls.params[ls.offsets[idx]], ls.params[ls.offsets[idx] + 2]
    pieces = params_where(ls.params, ls.nparams[idx] >= 6, ls.offsets[idx] + 5, 1.0)  # consolidated runs
    length = const["IL"] * const["IO"] ** order * saturate(now - birth, const["TAU"]) * pieces
    leaves = np.flatnonzero((ls.sym == LEAF) & (ls.nparams >= 1))
    size = leaf_sizes(ls, leaves, now, const) * leaf_keep(ls.params[ls.offsets[leaves]], clocks.wilt)
    symbols = np.concatenate([np.full(len(idx), ord("F"), ls.sym.dtype), np.full(len(leaves), LEAF, ls.sym.dtype)])
    view = replace_modules(ls, np.concatenate([idx, leaves]), symbols, np.concatenate([length, size])[:, None])
    blossoms = np.flatnonzero((view.sym == BLOSSOM) & (view.nparams == 1))  # K(birth) from region edits
    kb = view.params[view.offsets[blossoms]]
    opened = saturate(now - kb, const["TAU"]) * leaf_keep(kb, clocks.wilt)
    view.params[view.offsets[blossoms]] = 0.4 * const["LS"] * opened
    fruits = np.flatnonzero((view.sym == FRUIT) & (view.nparams == 1))  # O(birth): swelling to full size
    view.params[view.offsets[fruits]] = FRUIT_SIZE * const["LS"] * saturate(now - view.params[view.offsets[fruits]],
                                                                              const["RIPEN"] / 3)
    if clocks.wilt > 0:
        view.params[view.offsets[droop_angles(view)]] *= 1.0 + DROOP * clocks.wilt
    return view


def pipe_area(ls: LString, segs: Segments, const: dict[str, float], ends: np.ndarray | None = None) -> np.ndarray:
    """Pipe-model cross-section of every segment: TIP^2 per leaf carried, each internode counting one
    leaf as far as it has grown; a drawn tip (a stroke's or a crown's) feeds one leaf's pipes. ``ends``:
    the segments' subtree ends when the caller has them (engine/geometry/turtle.py subtree_ends)."""
    grown = (ls.sym[segs.module] == INTERNODE) & (ls.nparams[segs.module] >= 3)
    offsets = ls.offsets[segs.module]
    seg_len = np.linalg.norm(segs.end - segs.start, axis=1)
    order = params_where(ls.params, grown, offsets + 2)
    full = const["IL"] * const["IO"] ** order
    weight = np.divide(seg_len, full, out=np.zeros(len(seg_len)), where=grown & (full > 0))  # (IL, IO 0: hostile)
    drawn = ~grown & (ls.sym[segs.module] == ord("F")) & (ls.nparams[segs.module] == 11)
    drawn_below = np.bincount(segs.parent[drawn & (segs.parent >= 0)], minlength=len(segs)) > 0
    weight[drawn & ~drawn_below] = 1.0
    return const["TIP"] ** 2 * np.maximum(subtree_sums(ls, segs, weight, ends), 1e-6)


def radii(ls: LString, segs: Segments, clocks: Clocks, const: dict[str, float]) -> np.ndarray:
    """Radii: the built wood or the pipe area, whichever is larger; drawn pieces (the modeler's strokes
    and crowns) are as wide as drawn or as the pipe model needs for what they carry, whichever is larger
    (a drawn width is a floor, not a cap: a trunk drawn thin under a big crown thickens as a tree's
    would). Internodes from before the living tree (three parameters) thicken with age instead."""
    module = segs.module
    count = ls.nparams[module]
    grown = (ls.sym[module] == INTERNODE) & (count >= 3)
    pipes = pipe_area(ls, segs, const)
    offsets = ls.offsets[module]
    wood = params_where(ls.params, grown & (count >= 5), offsets + 4)
    girth_birth = params_where(ls.params, grown, offsets + 1)
    legacy = grown & (count < 5)
    rings = np.where(legacy, const["GMAX"] * saturate(clocks.girth_time - girth_birth, const["GT"]), 0.0)
    radius = np.sqrt(np.maximum(pipes * (1.0 + rings), wood))
    drawn = (ls.sym[module] == ord("F")) & (count == 11)  # modeler pieces: as drawn, or the pipes' width
    out = np.where(grown, radius, np.maximum(np.where(drawn, np.sqrt(pipes), radius), segs.radius))
    return _capped_by_drawn(ls, segs, out, grown, drawn)


def _capped_by_drawn(ls: LString, segs: Segments, radius: np.ndarray, grown: np.ndarray,
                     drawn: np.ndarray) -> np.ndarray:
    """Wood grown on a drawn piece (the sapling above a trunk drawn from its foot, branches from a
    stroke's growth points) no wider than the piece where it starts (as wide as drawn, or as its pipes
    need: :func:`radii`): each such grown sub-tree is scaled as a whole (the pipe law holds within it).
    The innermost grown sub-tree's own scale wins."""
    parent = segs.parent
    roots = np.flatnonzero(grown & (parent >= 0) & drawn[np.maximum(parent, 0)])
    if len(roots) == 0:
        return radius
    below = parent[roots]
    cap = radius[below]
    scale = np.minimum(1.0, cap / np.maximum(radius[roots], 1e-12))
    stops = np.searchsorted(segs.module, brackets.branch_ends(ls.sym, segs.module[roots]))
    factor = np.ones(len(radius))
    for root, stop, k in zip(roots.tolist(), stops.tolist(), scale.tolist(), strict=True):  # outer first
        factor[root:stop] = k
    return np.where(grown, radius * factor, radius)


def droop_angles(ls: LString) -> np.ndarray:
    """The branch and leaf angles that droop with wilt: a '&' right before a bud, a leaf or a grown
    apex. Drawn (modeler) geometry keeps its shape."""
    pitch = np.flatnonzero((ls.sym[:-1] == PITCH) & (ls.nparams[:-1] == 1))
    nxt = pitch + 1
    carried = (ls.sym[nxt] == BUD) | (ls.sym[nxt] == LEAF) | ((ls.sym[nxt] == APEX) & (ls.nparams[nxt] != 5))
    return pitch[carried]


def grown_turtle(ls: LString, clocks: Clocks, const: dict[str, float]) -> TurtleResult:
    """The growing tree's segments (with their continuous radii) and leaf clusters, without meshes: what
    measuring a tree needs (the lab samples it), for a fraction of the cost of :func:`grow_geometry`."""
    view = render_view(ls, clocks, const)
    turtle = add_unit_leaves(ls, interpret(view, turtle_config(const)), clocks, const)
    segs = turtle.segments
    if len(segs):
        set_radii(segs, radii(ls, segs, clocks, const))
    turtle.leaves = leaf_clusters(turtle.leaves)
    return turtle


def grow_geometry(ls: LString, clocks: Clocks, const: dict[str, float], lod: int = 0) -> TreeGeometry:
    """Turtle and meshes of the growing tree, with continuous radii (see module docstring)."""
    turtle = grown_turtle(ls, clocks, const)
    return TreeGeometry(turtle, tree_mesh(turtle, lod_level(lod)))
