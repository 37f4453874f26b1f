"""The living game tree: smooth growth in small steps, steered and pruned by the light it receives.

The L-string stores *birth times and states*, not sizes (module layout in assets/lsystems/game_tree.lsys):
internodes ``I(bT, bG, order, shade, wood)``, apices ``A(progress, order, nodes, light, yaw, pitch)``,
buds ``D(birth, order, light)`` and leaves ``L(birth, vigour, falling since)``. Sizes are continuous
functions of the tree's clocks, evaluated for every frame:

* internode length = IL * IO^order * (1 - exp(-age / TAU)): zero at birth, saturating (no cones);
* wood: the pipe model (TIP^2 per leaf carried, each leaf counted as far as its internode has grown)
  or, when larger, the cross-section the internode has built (``wood``, grown with the water clock by
  :meth:`GrowingTree.sense` and never shrinking: a trunk stays as thick when branches are shed);
* leaves unfold from zero, wither before they fall (``falling since``), and shrink away as the tree wilts;
  branches droop with wilt.

Between rewrites :meth:`GrowingTree.sense` takes a light reading (engine/life/plant/light.py) and writes it into
the string: buds and apices remember their light (shaded buds stay asleep, shaded apices stop), apices
turn toward the mean light direction (phototropism), every internode counts the time its leaves spend in
deep shade, and lateral branches that stayed in deep shade for SHED are shed (cut from the string; the
pieces are kept in :attr:`GrowingTree.fallen` for a short visible fall).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from arbor.engine.base.units import METRE
from arbor.engine.geometry.tree import TreeGeometry
from arbor.engine.geometry.turtle import (
    Leaves,
    Segments,
    TurtleConfig,
    TurtleResult,
    interpret,
    module_positions,
    subtree_ends,
    subtree_sums,
)
from arbor.engine.life.form import shoot_units
from arbor.engine.life.form.interpret import (
    APEX,
    BUD,
    CLUSTER_AREA,
    INTERNODE,
    LEAF,
    LEAF_ASPECT,
    LEAF_BUD,
    Clocks,
    add_unit_leaves,
    grow_geometry,
    interpretation_constants,
    leaf_area,
    pipe_area,
    render_view,
    turtle_config,
)
from arbor.engine.life.plant import carbon, shedding
from arbor.engine.life.plant.carbon import Economy
from arbor.engine.life.plant.collide import Obstacles, avoidance
from arbor.engine.life.plant.consolidate import consolidated
from arbor.engine.life.plant.light import memory_weight
from arbor.engine.life.plant.units import form_units
from arbor.engine.life.plant.vigour import apical_control, borchert_honda
from arbor.engine.life.rules.schema import find_rule
from arbor.engine.lsystem import brackets
from arbor.engine.lsystem.derive import Deriver, StepReport
from arbor.engine.lsystem.lstring import LString, params_where
from arbor.engine.lsystem.lsys import LSystem

CONSOLIDATE_AT = 0.5  # share of the module budget in use from which old wood is consolidated
GROWTH_PER_LIGHT = 0.2  # apex vigour (fully lit apices' worth) one fully lit leaf cluster's light sustains
FREE_VIGOUR = 2.0  # ... beyond which the apices share this much whatever the leaves catch (a seedling's leader grows)
UNITS_EVERY = 2.0  # elongation time constants between makings of one-site shoot units in the growing season
FALL_KEEP = 40.0  # physiological time a shed branch stays in `fallen` for the game to show its fall
# A branch's light counts in sugar: x (remembered daylight / the norm) to this power (1: all of the day's
# strength; 0.5 keeps a weak light's young tree from shedding every branch that is not in the sun)
SHADE_EARNING = 0.5
AROUND = np.array([[1.0, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]])  # light probes
GRADIENT_REACH = 1.5  # internode lengths from an apex to its light probes
AVOID_WEIGHT, AVOID_TURN = 4.0, 35.0  # how hard an obstacle ahead pushes, and the turn it allows (degrees)
_TURNLIKE = np.zeros(256, bool)
_TURNLIKE[[ord(c) for c in "+-&^/\\|$!'T%"]] = True




@dataclass
class Fallen:
    """Pieces of a shed branch, as they were when it fell (for the game's falling animation)."""

    at: float  # length time T of the fall
    segments: Segments
    leaves: Leaves


@dataclass
class LightScene:
    """One tree as the light sees it: leaf areas that cast shade and the points that receive light."""

    turtle: TurtleResult
    leaf_idx: np.ndarray  # modules of the leaves (occluders and receivers, in this order)
    leaf_center: np.ndarray  # (k, 3)
    leaf_area: np.ndarray  # (k,) nominal area (wilt ignored: a wilting leaf still counts as a leaf)
    probe_idx: np.ndarray  # apices and buds that receive light
    around: np.ndarray  # (6 a, 3) points around every apex: where is there more light?

    @property
    def queries(self) -> np.ndarray:
        """Receiver positions: the leaf centres, the apices and buds, the points around the apices."""
        return np.concatenate([self.leaf_center, self.turtle.probes.position, self.around])


@dataclass
class SenseReport:
    """What one light reading changed."""

    shed: int = 0  # branches shed
    mean_light: float = 1.0  # mean light of the leaves (area-weighted)


@dataclass
class GrowingTree:
    """An L-string grown by rewrites driven by the simulation's clocks and the light, inside a budget."""

    system: LSystem
    seed: int | None = None
    lstring: LString | None = None
    budget: int | None = None
    last_rewrite_T: float = 0.0  # noqa: N815 (the save format names it so)
    last_sense_length: float | None = None
    last_sense_girth: float | None = None
    light_dir: np.ndarray = field(default_factory=lambda: np.array([0.0, 1.0, 0.0]))
    mean_light: float = 1.0
    height: float = 0.0  # top of the wood at the last light reading (scene units)
    shed_total: int = 0
    fallen: list[Fallen] = field(default_factory=list)
    last_report: StepReport | None = None
    confine: object | None = None  # a region (engine/modeling/regions.py): rewrites only inside it ...
    confine_left: int = 0  # ... for this many more rewrites (Onishi et al. 2003 Fig. 11's region-limited growth)
    apical_fade: float = find_rule("growth.apical_fade").default  # m: the species' (World sets it from its rules)
    dead_linger: float = find_rule("growth.dead_linger").default  # a dead branch stands this long (World: its rules')

    def __post_init__(self) -> None:
        self.deriver = Deriver(self.system, seed=self.seed, budget=self.budget)
        if self.lstring is None:
            self.lstring = self.system.axiom
        self.geometry_constants = interpretation_constants(self.system.constants)

    @property
    def budget_hit(self) -> bool:
        """True when the last rewrite was held back by the module budget."""
        return bool(self.last_report and self.last_report.budget_hit)

    @property
    def budget_used(self) -> float:
        """Share of the module budget in use (0..1)."""
        budget = self.deriver.budget
        return min(len(self.lstring) / budget, 1.0) if budget else 0.0

    def rewrite(self, length_time: float, girth_time: float, resources: float, leaf_vigour: float = 1.0,
                season: dict[str, float] | None = None, vigour: float = 1.0) -> StepReport:
        """One derivation step at the given clocks (new modules are born now), then empty brackets go.
        ``season``: the season's externs (SF, AF, SP, SL; see Simulation.season_externs) and LG (how fast
        T runs for the light caught: Simulation.light_growth); ``vigour`` (0..1,
        extern C): the share of its shoots' growth the carbon pool pays for (engine/life/plant/carbon.py).
        While a region confines growth (``confine``, for ``confine_left`` more rewrites) only modules
        inside it change."""
        extern = {"T": length_time, "G": girth_time, "DT": length_time - self.last_rewrite_T, "R": resources,
                  "B": self.budget_used, "WL": leaf_vigour, "C": vigour,
                  "SF": 1.0, "AF": 0.0, "SP": 0.0, "SL": 0.0, "LG": 1.0,  # (none given: an endless summer)
                  **(season or {})}
        only = None
        if self.confine is not None and self.confine_left > 0:
            view = render_view(self.lstring, Clocks(length_time, girth_time, 0.0), self.geometry_constants)
            only = self.confine.contains(module_positions(view, TurtleConfig(pipe_model=False, leaves_at_tips=0)))
            self.confine_left -= 1
        elif self.confine is not None:
            self.confine = None
        new, self.last_report = self.deriver.step(self.lstring, extern, only=only)
        self.lstring = remove_empty_branches(new)
        if self.budget_used > CONSOLIDATE_AT:  # old wood merged so the budget goes to the living crown
            self.lstring, _ = consolidated(self.lstring, length_time, self.geometry_constants["TAU"])
        every = UNITS_EVERY * self.geometry_constants["TAU"]  # old leafy nodes as units, at whole multiples of
        if length_time // every > self.last_rewrite_T // every:  # this period of T (a saved tree continues alike)
            self.lstring, _ = form_units(self.lstring, length_time, self.geometry_constants, runs=False)
        self.last_rewrite_T = length_time
        return self.last_report

    def drop_leaves(self) -> int:
        """Winter: every leaf still on the tree falls (the renderer has faded them out through autumn)
        and leaves a leaf bud V where it was, which the spring flush opens again. Returns how many fell."""
        ls, fell = shoot_units.bare(self.lstring)
        leaves = ls.sym == LEAF
        count = int(leaves.sum()) + fell
        self.lstring = ls
        if leaves.any():
            sym = np.where(leaves, LEAF_BUD, ls.sym).astype(ls.sym.dtype)
            self.lstring = LString.from_arrays(sym, np.where(leaves, 0, ls.nparams), ls.params[~np.repeat(leaves,
                                                                                                         ls.nparams)])
        self.lstring, _ = form_units(self.lstring, self.last_rewrite_T, self.geometry_constants)  # (all bare now)
        return count

    def leaf_area(self, now: float) -> float:
        """Area (scene units²) of the leaf clusters on the tree at length time ``now``, counted from the string."""
        return leaf_area(self.lstring, now, self.geometry_constants)

    def render_view(self, clocks: Clocks) -> LString:
        """The L-string the turtle draws at these clocks: ages turned into lengths and leaf sizes."""
        return render_view(self.lstring, clocks, self.geometry_constants)

    def geometry(self, clocks: Clocks, lod: int = 0) -> TreeGeometry:
        """Turtle output and meshes of the tree at these clocks."""
        return grow_geometry(self.lstring, clocks, self.geometry_constants, lod)

    def light_scene(self, clocks: Clocks) -> LightScene:
        """The tree as the light sees it now (one turtle pass, probing apices and buds)."""
        ls, const = self.lstring, self.geometry_constants
        view = render_view(ls, Clocks(clocks.length_time, clocks.girth_time, 0.0), const)
        probes = np.flatnonzero(((ls.sym == APEX) & (ls.nparams == 6)) | ((ls.sym == BUD) & (ls.nparams == 3)))
        turtle = add_unit_leaves(ls, interpret(view, turtle_config(const), probes=probes), clocks, const)
        ends = turtle.segments.end
        self.height = float(ends[:, 1].max()) if len(ends) else 0.0
        leaves = turtle.leaves
        heading = leaves.frame[:, :, 0] if len(leaves) else np.zeros((0, 3))
        center = leaves.position + heading * (0.5 * leaves.size)[:, None]
        apex = turtle.probes.position[ls.sym[probes] == APEX]
        around = (apex[:, None, :] + AROUND[None] * (GRADIENT_REACH * const["IL"])).reshape(-1, 3)
        return LightScene(turtle, leaves.module, center, CLUSTER_AREA * LEAF_ASPECT * leaves.size**2, probes,
                          around)

    def sense(self, scene: LightScene, light: np.ndarray, clocks: Clocks, shine: float, sun: np.ndarray,
              memory: float, drought: float = 0.0, leafy: bool = True,
              obstacles: Obstacles | None = None, economy: Economy | None = None) -> SenseReport:
        """Write a light reading (``light``: one value per ``scene.queries``) into the string.

        ``shine`` (0..1) is the sun's strength: buds and apices remember light x shine (a low sun feeds
        less), readings count by it (no sun, no learning); ``sun`` is the direction toward the
        sun, ``memory`` the physiological time over which light is remembered, ``drought`` (0..1) makes
        shade kill faster. See the module docstring for what changes.
        ``leafy`` is False while a deciduous crown is bare or
        half bare (leaf fall, winter, the first days of spring): shade is not counted then, or every
        branch would starve for want of leaves it does not grow yet. ``obstacles`` (in this tree's
        frame: neighbours' wood, rocks) turn apices away or stop them (engine/life/plant/collide.py).
        ``economy`` books the reading in the tree's carbon budget and pays for the wood (plant/carbon.py).
        """
        now, girth = clocks.length_time, clocks.girth_time
        dt = 0.0 if self.last_sense_length is None else max(now - self.last_sense_length, 0.0)
        dg = 0.0 if self.last_sense_girth is None else max(girth - self.last_sense_girth, 0.0)
        self.last_sense_length, self.last_sense_girth = now, girth
        weight = memory_weight(dt, shine, memory)
        ls = self.lstring
        params = ls.params.copy()
        k, m = len(scene.leaf_idx), len(scene.probe_idx)
        leaf_light, probe_light, around = light[:k], light[k:k + m], light[k + m:]
        if weight > 0:  # buds and apices remember the light they really got: a low sun gives less
            income = float((leaf_light * scene.leaf_area).sum()) / (CLUSTER_AREA * LEAF_ASPECT
                                                                     * self.geometry_constants["LS"] ** 2)
            lam = apical_control(self.geometry_constants["BHL"], self.height / METRE, self.apical_fade)
            remember_light(ls, params, scene, probe_light * min(shine, 1.0), weight, lam, income)
            mean = np.asarray(sun, float) / max(float(np.linalg.norm(sun)), 1e-12)
            self.light_dir = _unit(self.light_dir + weight * (mean - self.light_dir))
            self._turn_apices(ls, params, scene, around, memory_weight(dt, shine, memory / 4), obstacles)
        area = float(scene.leaf_area.sum())
        if area > 0 and weight > 0:
            self.mean_light = float((leaf_light * scene.leaf_area).sum() / area)
        grown = self._grow_wood_and_count_shade(ls, params, scene, leaf_light, dt, dg, drought,
                                                count=weight > 0 and leafy, economy=economy)
        self.lstring = LString(ls.sym, ls.nparams, ls.offsets, params)
        shed = self._shed(scene, grown, params, now)
        return SenseReport(shed, self.mean_light)

    def _turn_apices(self, ls: LString, params: np.ndarray, scene: LightScene, around: np.ndarray,
                     weight: float, obstacles: Obstacles | None = None) -> None:
        """Yaw and pitch (degrees) that turn each apex's next internode toward its target direction:
        its own heading, up (negative gravitropism), the mean sun direction and the side where the
        light around it is brighter (Palubicki's optimal growth direction), at most PHOTO degrees; and
        away from an obstacle ahead (up to AVOID_TURN degrees), or no further if it touches one."""
        const = self.geometry_constants
        apex = ls.sym[scene.probe_idx] == APEX
        idx = scene.probe_idx[apex]
        if len(idx) == 0:
            return
        frames = scene.turtle.probes.frame[apex]
        order = params[ls.offsets[idx] + 1]
        seen = around.reshape(len(idx), len(AROUND))
        brighter = seen @ AROUND / np.maximum(seen.sum(axis=1), 1e-9)[:, None]
        sun = np.broadcast_to(self.light_dir, brighter.shape).copy()
        branch = order > 0
        brighter[branch, 1] = sun[branch] = 0.0  # branches seek the light around them sideways (not the sun's mean
        up_weight = np.where(branch, const["UPB"], const["UPW"])[:, None]  # bearing: a crown all to one side)
        target = (const["STRAIGHT"] * frames[:, :, 0] + up_weight * np.array([0.0, 1.0, 0.0])
                  + const["SUNW"] * sun + const["LIGHTW"] * brighter)
        push, touching = avoidance(scene.turtle.probes.position[apex], frames,
                                   self.geometry_constants["IL"] * self.geometry_constants["IO"] ** order,
                                   self.geometry_constants["IL"], obstacles)
        params[ls.offsets[idx[touching]] + 3] = 0.0  # the light it remembers: an apex without light rests
        target += AVOID_WEIGHT * push
        target /= np.maximum(np.linalg.norm(target, axis=1, keepdims=True), 1e-12)
        local = np.einsum("kij,ki->kj", frames, target)  # target in each apex's (H, L, U)
        angle = np.degrees(np.arccos(np.clip(local[:, 0], -1.0, 1.0)))
        limit = np.where(order == 0, const["PHOTO"], const["PHOTOB"])
        limit = np.where(np.linalg.norm(push, axis=1) > 0, np.maximum(limit, AVOID_TURN), limit)
        scale = np.minimum(1.0, limit / np.maximum(angle, 1e-9))
        yaw = np.degrees(np.arctan2(local[:, 1], local[:, 0])) * scale  # "+" turns H toward L
        pitch = np.degrees(np.arctan2(local[:, 2], np.hypot(local[:, 0], local[:, 1]))) * scale
        at = ls.offsets[idx]
        params[at + 4] += weight * (yaw - params[at + 4])
        params[at + 5] += weight * (pitch - params[at + 5])

    def _grow_wood_and_count_shade(self, ls: LString, params: np.ndarray, scene: LightScene, leaf_light: np.ndarray,
                                   dt: float, dg: float, drought: float, count: bool,
                                   economy: Economy | None = None) -> np.ndarray:
        """Secondary growth (wood never shrinks; rings as far as the carbon pool pays) and each internode's
        time in deep shade. Returns, per segment, whether it is a grown internode with the full layout."""
        const = self.geometry_constants
        segs = scene.turtle.segments
        if len(segs) == 0:
            return np.zeros(0, bool)
        grown = (ls.sym[segs.module] == INTERNODE) & (ls.nparams[segs.module] >= 5)
        off = ls.offsets[segs.module[grown]]
        ends = subtree_ends(ls, segs)  # (one bracket pass for the pipes and the shade sums below)
        pipes = pipe_area(ls, segs, const, ends)[grown]
        rings = const["RING"] * dg * pipes
        if economy is not None:
            length = np.linalg.norm(segs.end - segs.start, axis=1)[grown]
            economy.book(carbon.canopy(scene.leaf_area, leaf_light, pipes, length))
            economy.pay_pipes(float((np.maximum(pipes - params[off + 4], 0.0) * length).sum()))
            rings = rings * economy.wood_share(float((rings * length).sum()))
        params[off + 4] = np.maximum(params[off + 4], pipes) + rings
        if count and dt > 0:
            carrier = scene.turtle.carriers(scene.leaf_idx)
            ok = carrier >= 0
            got = np.bincount(carrier[ok], (leaf_light * scene.leaf_area)[ok], minlength=len(segs))
            got_above = subtree_sums(ls, segs, got, ends)  # the view keeps the string's module positions
            # Light income against what the branch must feed: a full leaf cluster's area per internode
            # it carries. A long branch with a few lit leaves at its tip starves like a shaded one.
            pieces = params_where(params, grown & (ls.nparams[segs.module] >= 6), ls.offsets[segs.module] + 5, 1.0)
            need = np.where(grown, CLUSTER_AREA * LEAF_ASPECT * const["LS"] ** 2 * pieces, 0.0)
            need_above = subtree_sums(ls, segs, need, ends)
            # In sugar, not in shares of the sky: the same share of a weak day's light earns less.
            earns = economy.daylight ** SHADE_EARNING if economy is not None else 1.0
            ratio = (earns * got_above / np.maximum(need_above, 1e-12))[grown]
            shade = params[off + 3]
            deep = ratio < const["SHQ"]
            params[off + 3] = np.where(deep, shade + dt * (1.0 + 2.0 * drought), np.maximum(shade - dt, 0.0))
        return grown

    def _shed(self, scene: LightScene, grown: np.ndarray, params: np.ndarray, now: float) -> int:
        """Lateral branches whose base internode has been in deep shade for longer than SHED die and stand bare;
        after ``dead_linger`` more they fall, leaving a stub (engine/life/plant/shedding.py). Returns how many fell."""
        ls = self.lstring
        segs = scene.turtle.segments
        self.fallen = [f for f in self.fallen if now - f.at < FALL_KEEP]
        if len(segs) == 0:
            return 0
        module = segs.module
        off = ls.offsets[module]
        shade = params_where(params, grown, off + 3)
        base = grown & ~segs.continues & (segs.parent >= 0) & (params_where(params, grown, off + 2) >= 1)
        dead = base & (shade > self.geometry_constants["SHED"])  # (the trunk is never shed; a stub's shade is < 0)
        falls = dead & (shade > self.geometry_constants["SHED"] + self.dead_linger)
        fell, dying = 0, module[dead & ~falls]
        if falls.any():
            ls, removed, fell = shedding.fall(ls, params, module[falls])
            self.fallen.append(fallen_pieces(scene, removed, now))
            dying = (np.cumsum(~removed) - 1)[dying[~removed[dying]]]  # (their places once the fallen are gone)
        self.lstring = shedding.strip(ls, ls.params, dying, now) if len(dying) else ls
        self.shed_total += fell
        return fell








def remember_light(ls: LString, params: np.ndarray, scene: LightScene, light: np.ndarray, weight: float,
                   bhl: float, income: float = np.inf) -> None:
    """Buds remember the light they catch; apices the vigour the Borchert-Honda sharing gives them from
    the whole tree's light (plant/vigour.py: at the species' BHL 0.5 that is their own light), all of
    them together no more than the tree's light ``income`` (fully lit leaf clusters' worth) sustains:
    GROWTH_PER_LIGHT each, and FREE_VIGOUR more (Palubicki et al. 2009: the resource the base collects is
    what the buds share, so a crown grows with the light it catches, not with the number of its buds)."""
    apex = ls.sym[scene.probe_idx] == APEX
    light = light.copy()
    light[apex] = borchert_honda(ls.sym, scene.probe_idx[apex], light[apex], bhl)
    total, cap = float(light[apex].sum()), GROWTH_PER_LIGHT * income + FREE_VIGOUR
    if total > cap:
        light[apex] *= cap / total
    at = ls.offsets[scene.probe_idx] + np.where(apex, 3, 2)
    params[at] += weight * (light - params[at])


def fallen_pieces(scene: LightScene, removed: np.ndarray, now: float) -> Fallen:
    """The segments and leaves of a branch just shed (``removed``: the modules cut), as they were when it fell."""
    turtle = scene.turtle
    segs, leaves = turtle.segments, turtle.leaves
    s = removed[segs.module]
    lv = removed[leaves.module]
    index = np.full(len(segs) + 1, -1, dtype=np.int64)
    index[np.flatnonzero(s)] = np.arange(int(s.sum()))
    parent = index[segs.parent[s]]  # -1 (the last entry) for a parent that stays on the tree
    pieces = Segments(segs.start[s], segs.end[s], segs.radius[s], segs.radius_end[s], segs.frame[s],
                      segs.order[s], segs.module[s], parent, segs.continues[s] & (parent >= 0), segs.colour[s])
    return Fallen(now, pieces, Leaves(leaves.position[lv], leaves.frame[lv], leaves.size[lv], leaves.module[lv]))


def new_axis_text(system: LSystem, now: float, girth: float) -> str:
    """A new first-order shoot (an internode and an apex that is due at once) in the layout of
    ``system``'s own modules: the living tree's, or the three-parameter one of older saves."""
    axiom = system.axiom
    apex = np.flatnonzero(axiom.sym == APEX)
    plastochron = interpretation_constants(system.constants)["P"]
    if len(apex) and axiom.nparams[apex[0]] == 6:
        return f"I({now:g},{girth:g},1,0,0)A({plastochron:g},1,0,1,0,0)"
    return f"I({now:g},{girth:g},1)A({now - plastochron:g},1,0)"


def _unit(v: np.ndarray) -> np.ndarray:
    n = float(np.linalg.norm(v))
    return v / n if n > 1e-12 else np.array([0.0, 1.0, 0.0])


















def remove_empty_branches(ls: LString) -> LString:
    """Drop brackets that hold nothing but turns (what erased leaves and buds leave behind)."""
    sym = ls.sym
    opens = np.flatnonzero(sym == brackets.OPEN)
    if len(opens) == 0:
        return ls
    content = ~_TURNLIKE[sym] & (sym != brackets.OPEN) & (sym != brackets.CLOSE)
    cum = np.concatenate([[0], np.cumsum(content)])
    closes = brackets.match(sym)[opens]
    empty = cum[closes] - cum[opens] == 0
    if not empty.any():
        return ls
    delta = np.zeros(len(ls) + 1, dtype=np.int64)
    np.add.at(delta, opens[empty], 1)
    np.add.at(delta, closes[empty] + 1, -1)
    return ls.select(np.cumsum(delta[:-1]) == 0)




def falling_pieces(tree: GrowingTree, now: float, seconds: float) -> list[tuple[Fallen, float]]:
    """Shed branches still falling, each with its fall progress 0..1 (``seconds``: physiological time a
    fall lasts)."""
    return [(f, min(max((now - f.at) / seconds, 0.0), 1.0)) for f in tree.fallen if now - f.at < seconds]
