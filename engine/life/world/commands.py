"""Commands: every change a player, a tool, the kiosk, the lab or the garden makes to a :class:`World`.

A command is a small frozen value; :meth:`World.apply <arbor.engine.life.world.world.World.apply>` logs
it (engine/life/world/log.py) and runs it, and its ``run`` is the only code that changes the world for
it. Its result tells the screen and the sound what happened (a stroke's :class:`StrokeResult`, a crown's
:class:`CrownResult`, the modules an edit changed...). Commands carry what they need in the world's own
terms (scene units, module indices, regions), never screen pixels, so a log replays to the same tree.

The modeler's commands work on the world's edit session (:attr:`World.editor`, an
:class:`~arbor.engine.modeling.modeler.Modeler` holding the undo history): :class:`BeginEditing` starts
one on the tree as it is; each edit commits one undoable step and the tree takes its L-string. The
crown's lobes are part of the tree (:attr:`World.crown`, a :class:`CrownRecord`): :class:`Crown` sets
them, every step remembers the lobes that stood with its L-string, so undo and redo bring them back.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from arbor.engine.life.form.interpret import render_view
from arbor.engine.life.plant.growth import new_axis_text
from arbor.engine.life.world import prune
from arbor.engine.life.world.actions import Action
from arbor.engine.lsystem.lstring import LString
from arbor.engine.lsystem.lsys import LSystem
from arbor.engine.lsystem.text import format_number
from arbor.engine.modeling.bend import bend_region
from arbor.engine.modeling.crowned import CrownRecord, too_big
from arbor.engine.modeling.edits import apply_edit, prune_region
from arbor.engine.modeling.regions import prune as prune_branch
from arbor.engine.modeling.regions import seed_in_region
from arbor.engine.modeling.strokes import Stroke as StrokePoints

if TYPE_CHECKING:
    from arbor.engine.life.world.world import World
    from arbor.engine.modeling.crown_style import CrownStyle
    from arbor.engine.modeling.lobes import Lobe
    from arbor.engine.modeling.modeler import Modeler, StrokeResult

# (the modeler and the crown filler are imported when first used: they bring scipy, which a game that
# never models need not load at start)

GROW_STEPS = 20  # growth steps a region's "grow" edit keeps all of the tree's growth inside it
MAX_CROWN_STEPS = 96  # L-strings of an edit session whose crown lobes undo/redo can bring back


@dataclass(frozen=True)
class Water:
    """The can: held (True) or let go (False)."""

    held: bool

    def run(self, world: World) -> None:
        """Turn the can on or off."""
        world.sim.state.watering = bool(self.held)


@dataclass(frozen=True)
class TopUp:
    """Water poured to bring the water meter up to ``level`` (0..1) at once (a neighbour's round while the
    player is away); a fuller meter stays as it is."""

    level: float

    def run(self, world: World) -> None:
        """Pour."""
        state = world.sim.state
        state.water_meter = max(state.water_meter, min(max(float(self.level), 0.0), 1.0))


@dataclass(frozen=True)
class LightEvery:
    """Read the light every ``seconds`` of game time (None: at the rules' interval), e.g. fewer readings
    while a long time away is caught up."""

    seconds: float | None

    def run(self, world: World) -> None:
        """Set the interval."""
        world.light_every = None if self.seconds is None else float(self.seconds)


@dataclass(frozen=True)
class SunHeight:
    """The sun's orbit height slider (a simulation value; clamped by the rules)."""

    value: float

    def run(self, world: World) -> None:
        """Move the sun's orbit."""
        world.sim.set_orbit_height(self.value)


@dataclass(frozen=True)
class SunSpeed:
    """The sun's speed slider (a simulation value; clamped by the rules)."""

    value: float

    def run(self, world: World) -> None:
        """Change how fast the sun goes round."""
        world.sim.set_sun_speed(self.value)


@dataclass(frozen=True)
class SunAt:
    """The sun moved to ``angle`` (rad) of its day: a new game or a visitor starting at a time of day."""

    angle: float

    def run(self, world: World) -> None:
        """Move the sun."""
        world.sim.state.sun_angle = float(self.angle)


@dataclass(frozen=True)
class Replant:
    """A fresh sapling, of a new line of descent, in the tree's place; ``planted``: wall-clock seconds
    for its lineage (None: the game time's start)."""

    planted: float | None = None

    def run(self, world: World) -> None:
        """Replant (the world draws the new seedling's seed from its own generator)."""
        world.replant_now(self.planted)


@dataclass(frozen=True)
class Place:
    """Where a tree stands in a garden (x, z scene units) and the garden's one sun and calendar it joins:
    (orbit height, speed, angle, turns, weather seed); None keeps the tree's own."""

    position: tuple[float, float]
    sun: tuple[float, float, float, float, int] | None = None

    def run(self, world: World) -> None:
        """Stand the tree there, under that sun."""
        world.position = (float(self.position[0]), float(self.position[1]))
        if self.sun is None:
            return
        height, speed, angle, turns, weather = self.sun
        world.sim.set_orbit_height(height)
        world.sim.set_sun_speed(speed)
        state = world.sim.state
        state.sun_angle, state.sun_turns, state.weather_seed = angle, turns, weather


@dataclass(frozen=True)
class Prune:
    """Cut the tree back to ``keep_height`` metres and/or its ``lowest`` share of trunk branches
    (engine/life/world/prune.py). Result: the branches cut."""

    keep_height: float | None = None
    lowest: float = 0.0

    def run(self, world: World) -> int:
        """Cut (recorded in the journal)."""
        return prune.prune(world, self.keep_height, self.lowest)


@dataclass(frozen=True)
class Harvest:
    """Pick the ripe fruit that is module ``module``. Result: the fruit's birth time, None if there is
    no ripe fruit there."""

    module: int

    def run(self, world: World) -> float | None:
        """Take the fruit off the tree (the garden puts its seed in the bag)."""
        ls = world.tree.lstring
        k = self.module
        if not 0 <= k < len(ls) or ls.sym[k] != ord("O") or ls.nparams[k] < 1:
            return None
        born = float(ls.params[ls.offsets[k]])
        if world.sim.state.length_time - born < world.tree.geometry_constants["RIPEN"]:
            return None
        keep = np.ones(len(ls), bool)
        keep[k] = False
        world.tree.lstring = ls.select(keep)
        harvests = sum(1 for entry in world.journal.entries if entry[1] == "harvest")
        world.journal.write(world.sim.state.time, "harvest", float(harvests + 1))
        return born


@dataclass(frozen=True)
class BeginEditing:
    """A new edit session on the tree as it is now (earlier edits out of undo's reach)."""

    def run(self, world: World) -> Modeler:
        """Start it; the result is the session."""
        from arbor.engine.modeling.modeler import Modeler, ModelerSettings

        tree = world.tree  # drawn axes get the species' density of side shoots, lambda(s)
        world.editor = Modeler(lstring=tree.lstring, settings=ModelerSettings.for_species(tree.geometry_constants),
                               segments_of=world.drawn_segments)
        world.crown_steps = {}
        _remember_crown(world, tree.lstring)
        return world.editor


def _remember_crown(world: World, ls: LString) -> None:
    """The crown's lobes standing now stand with ``ls`` (undo and redo to it bring them back); bounded."""
    world.crown_steps[id(ls)] = (ls, world.crown)
    while len(world.crown_steps) > MAX_CROWN_STEPS:
        del world.crown_steps[next(iter(world.crown_steps))]


def _step_to(world: World, ls: LString) -> None:
    """Undo or redo reached ``ls``: the tree takes it, with the lobes that stood with it."""
    world.tree.lstring = ls
    kept = world.crown_steps.get(id(ls))
    if kept is not None and kept[0] is ls:
        world.crown = kept[1]


def _commit(world: World, new: LString) -> None:
    """One undoable edit: the session and the tree take ``new`` (the crown's lobes stand with it)."""
    world.editor.commit(new)
    world.tree.lstring = new
    _remember_crown(world, new)


@dataclass(frozen=True, eq=False)
class Stroke:
    """A drawn branch or trunk: its points (scene units) and their times (s). Result: the
    :class:`StrokeResult` (None when it would not fit the module budget: nothing is added)."""

    points: np.ndarray
    times: np.ndarray

    def run(self, world: World) -> StrokeResult | None:
        """Convert the stroke on the tree as edited and commit it (undoable)."""
        editor = world.editing()
        new, result = editor.convert(StrokePoints(np.asarray(self.points), np.asarray(self.times)))
        budget = world.tree.deriver.budget
        if budget is not None and len(new) > max(budget, len(editor.lstring)):
            return None
        if result.pieces:
            _commit(world, new)
        return result


@dataclass
class CrownResult:
    """What a crown regrowth did: the branch pieces added, whether the budget limited them, and why it was
    not grown at all (``refused``: a crown the tree could not keep in its save), None when it was."""

    added: int
    limited: bool
    refused: str | None = None


@dataclass(frozen=True, eq=False)
class Crown:
    """Regrow the crown from ``base`` (the tree before any crown) into ``lobes`` (Zhang et al.), within
    the module budget; one undoable step. ``only``: the one lobe an edit changed (its index): while the
    tree is as its crown grew, only that lobe's crown is regrown and the others' stay as they are
    (engine/modeling/crown_edit.py). ``style``: how it grows and its leaves (the crown panel's
    engine/modeling/crown_style.py). Result: a :class:`CrownResult`."""

    base: LString
    lobes: tuple[Lobe, ...]
    only: int | None = None
    style: CrownStyle | None = None  # how it grows (None: as the crown standing grew, else the defaults)

    def run(self, world: World) -> CrownResult:
        """Grow the crown and commit it."""
        from arbor.engine.life.form.crown_leaves import fit_crown_leaves
        from arbor.engine.modeling.crown_fill import MAX_CROWN_MODULES, grow_within
        from arbor.engine.modeling.crown_style import DEFAULT_STYLE

        editor = world.editing()
        if too_big(self.lobes):  # (a crown the tree could not keep in its save is not grown)
            return CrownResult(0, False, too_big(self.lobes))
        budget = world.tree.deriver.budget
        room = MAX_CROWN_MODULES if budget is None else budget - len(self.base)
        base, lobes = self.base, list(self.lobes)
        record = world.crown
        style = self.style or (record.style if record is not None and record.style is not None else DEFAULT_STYLE)
        if (self.only is not None and record is not None and record.base is not None and record.grown is editor.lstring
                and len(record.lobes) == len(lobes) and 0 <= self.only < len(lobes)):
            base, lobes, room = _one_lobe(world, record, lobes, self.only, room)
        born = format_number(world.born_visible())
        grown, added, limited = grow_within(base, lobes, room, int(editor.rng.integers(2**31)), world.drawn_segments,
                                            tip=style.tip(born), style=style)
        if added:  # each leaf as large as its lobe leaves room for (the foliage keeps to the outline)
            grown = fit_crown_leaves(grown, world.clocks(), world.tree.geometry_constants, list(self.lobes),
                                     float(born), style.leaf_size)
        world.crown = CrownRecord(tuple(self.lobes), self.base, grown, style) if self.lobes else None
        _commit(world, grown)
        return CrownResult(added, limited)


def _one_lobe(world: World, record: CrownRecord, lobes: list[Lobe], k: int, room: int):
    """What growing only lobe ``k`` again starts from: the tree without the wood its crown grew into the
    lobe before the edit, the edited lobe alone, and its room (its share of the crown's budget by volume,
    at most what the budget leaves)."""
    from arbor.engine.modeling.crown_edit import without_lobe_crown

    ls = world.editor.lstring
    stripped = without_lobe_crown(ls, record.base, world.drawn_segments(ls), list(record.lobes), k)
    share = lobes[k].volume / max(sum(lobe.volume for lobe in lobes), 1e-12)
    left = room - (len(stripped) - len(record.base))
    return stripped, [lobes[k]], max(min(int(room * share), left), 0)


@dataclass(frozen=True)
class Cut:
    """Cut the branch that module ``module`` starts and what grows from it (the modeler's prune tool).
    Result: the segments removed (0: it was the trunk's base, which stays)."""

    module: int

    def run(self, world: World) -> int:
        """Cut, one undoable step."""
        editor = world.editing()
        segs = world.drawn_segments(editor.lstring)
        before = len(segs)
        k = np.flatnonzero(segs.module == self.module)
        if len(k) == 0 or segs.parent[k[0]] < 0:
            return 0
        _commit(world, prune_branch(editor.lstring, self.module))
        return before - len(world.drawn_segments(editor.lstring))


@dataclass
class BranchResult:
    """What a branch edit did: the pieces of the branch, how many of them are drawn (only drawn wood takes
    a width or a length; engine/modeling/branch_edit.py), the amount applied (clipped to its limits) and
    the module the branch now starts at (0 pieces: no branch was there)."""

    pieces: int
    drawn: int = 0
    amount: float = 0.0
    module: int = -1


@dataclass(frozen=True)
class BranchEdit:
    """Change the width (a factor), the angle (degrees away from its parent's axis) or the length (a
    factor) of the branch that the segment drawn by module ``module`` lies on, all of it following
    rigidly; one undoable step (engine/modeling/branch_edit.py). Result: a :class:`BranchResult`."""

    module: int
    edit: str
    amount: float

    def run(self, world: World) -> BranchResult:
        """Edit the branch and commit it."""
        from arbor.engine.modeling.branch_edit import LIMITS, branch_of, branch_span, drawn_in, edited, refreshed

        editor = world.editing()
        ls = editor.lstring
        segs = world.drawn_segments(ls)
        k = np.flatnonzero(segs.module == self.module)
        if len(k) == 0 or self.edit not in LIMITS:
            return BranchResult(0)
        first = branch_of(segs, int(k[0]))
        start, end = branch_span(ls, segs, first)
        pieces = int(((segs.module >= start) & (segs.module < end)).sum())
        new = edited(ls, segs, first, self.edit, self.amount)
        new = refreshed(new, world.drawn_segments(new))
        _commit(world, new)
        amount = float(np.clip(self.amount, *LIMITS[self.edit]))
        return BranchResult(pieces, len(drawn_in(ls, start, end)), amount,
                            int(segs.module[first]) + len(new) - len(ls))


@dataclass(frozen=True)
class WidthBrush:
    """The width brush: every branch the brush passed over (``modules``: a piece of each) made ``factor``
    times as wide, one undoable step; a branch inside another brushed one is widened with it, once.
    Result: the branches widened."""

    modules: tuple[int, ...]
    factor: float

    def run(self, world: World) -> int:
        """Widen the branches and commit them."""
        from arbor.engine.modeling.branch_edit import branch_of, branch_span, edited, refreshed

        editor = world.editing()
        ls = editor.lstring
        segs = world.drawn_segments(ls)
        rows = np.flatnonzero(np.isin(segs.module, np.asarray(self.modules, np.int64)))
        firsts = sorted({branch_of(segs, int(k)) for k in rows}, key=lambda k: -int(segs.module[k]))
        spans = {k: branch_span(ls, segs, k) for k in firsts}
        outer = [k for k in firsts if not any(o != k and spans[o][0] <= spans[k][0] < spans[o][1] for o in firsts)]
        new = ls
        for k in outer:  # from the last in the string back: the earlier ones' modules stay where they are
            new = edited(new, segs, k, "width", self.factor)
        if outer:
            _commit(world, refreshed(new, world.drawn_segments(new)))
        return len(outer)


@dataclass
class EditResult:
    """What a region edit did: modules changed (negative: a new axis was started), modules the budget
    held back."""

    changed: int
    held: int


@dataclass(frozen=True, eq=False)
class RegionEdit:
    """An edit inside a region (engine/modeling/regions.py) with the production set ``system`` (None for
    the built-in prune and bend), as Onishi et al. 2003's region edits; "grow" also keeps the tree's
    next growth steps inside the region. Result: an :class:`EditResult`."""

    edit: str
    region: Any
    system: LSystem | None = None

    def run(self, world: World) -> EditResult:
        """Apply the edit to the modules inside the region (undoable when it changed any)."""
        editor, tree = world.editing(), world.tree
        ls, clocks = editor.lstring, world.clocks()
        now, const = clocks.length_time, tree.geometry_constants
        if self.edit == "prune":
            (new, changed), held = prune_region(ls, world.module_positions(ls), self.region), 0
        elif self.edit == "bend":
            (new, changed), held = bend_region(ls, render_view(ls, clocks, const), self.region), 0
        else:
            extern = {"T": world.born_visible(), "G": clocks.girth_time, "NOW": now,
                      **{name: const[name] for name in ("P", "IL", "IO", "MAXO")}}
            axis = new_axis_text(tree.system, now, clocks.girth_time) if self.edit == "grow" else None
            new, changed, held = apply_edit(ls, world.module_positions(ls), self.region, self.system, extern,
                                            new_axis=axis, budget=tree.deriver.budget)
            if axis is not None and changed == 0 and not held and len(ls) < (tree.deriver.budget or len(ls) + 1):
                # nothing in the region could grow (it was pruned bare): a new axis there, as in an empty
                # one, so Grow always shows and undoes (it did nothing and made no step)
                new, changed = seed_in_region(ls, axis, self.region.center), -1
        if changed:
            _commit(world, new)
        if self.edit == "grow":
            tree.confine, tree.confine_left = self.region, GROW_STEPS
        return EditResult(changed, held)


@dataclass(frozen=True)
class Undo:
    """Take back the last edit. Result: False when there was none."""

    def run(self, world: World) -> bool:
        """Step back in the edit session's history."""
        editor = world.editing()
        if not editor.undo():
            return False
        _step_to(world, editor.lstring)
        return True


@dataclass(frozen=True)
class Redo:
    """Put back the last undone edit. Result: False when there was none."""

    def run(self, world: World) -> bool:
        """Step forward in the edit session's history."""
        editor = world.editing()
        if not editor.redo():
            return False
        _step_to(world, editor.lstring)
        return True


WORLD_COMMANDS = {  # a world action (with its value) as the command it stands for
    Action.WATER: lambda value: Water(bool(value)),
    Action.ORBIT_HEIGHT: lambda value: SunHeight(float(value)),
    Action.SUN_SPEED: lambda value: SunSpeed(float(value)),
    Action.REPLANT: lambda value: Replant(),
}


def of_action(action: Action, value: float = 0.0):
    """The command a world action (:data:`~arbor.engine.life.world.actions.WORLD_ACTIONS`) with its value
    stands for; a ValueError for an action that is the game's, not the world's."""
    if action not in WORLD_COMMANDS:
        raise ValueError(f"not an action of the world: {action.value!r}")
    return WORLD_COMMANDS[action](value)
