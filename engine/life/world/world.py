"""The game's world: simulation + growing tree + the player's actions, stepped deterministically.

Given the same seed, rules, L-system and the same commands at the same steps, two worlds produce
identical trees and meters. The world is the only writer of its own state: the game, the tools, the
kiosk, the lab and the garden change it through :meth:`World.apply` with a command
(engine/life/world/commands.py), which is logged with the steps between (engine/life/world/log.py),
so a world's life replays from its log (:func:`~arbor.engine.life.world.log.replay`). Every running
world (the game, a garden, time away, the lab and sweeps) steps through one loop, :func:`step_together`.
"""

from __future__ import annotations

import math
from dataclasses import InitVar, dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from arbor.engine.geometry.turtle import TurtleConfig, module_positions
from arbor.engine.life.form.interpret import Clocks, grow_geometry, render_view
from arbor.engine.life.lineage.lineage import Lineage, new_lineage, species_of
from arbor.engine.life.plant import carbon, collide, genome, photosynthesis, seasons
from arbor.engine.life.plant.carbon import CarbonBudget, Economy
from arbor.engine.life.plant.collide import Obstacles
from arbor.engine.life.plant.growth import GrowingTree
from arbor.engine.life.plant.journal import Journal
from arbor.engine.life.plant.light import exposure
from arbor.engine.life.plant.roots import Roots
from arbor.engine.life.plant.sim import Rules, SimState, Simulation
from arbor.engine.life.rules.rules import species_trait
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.commands import BeginEditing, of_action
from arbor.engine.life.world.log import Log, snapshot
from arbor.engine.life.world.status import tree_status
from arbor.engine.lsystem.lsys import LSystem

if TYPE_CHECKING:
    from arbor.engine.modeling.crowned import CrownRecord
    from arbor.engine.modeling.modeler import Modeler

MAX_CATCH_UP_STEPS = 20_000  # a catch-up never takes more steps than this, whatever the rules say


@dataclass
class Parts:
    """A tree's parts as a save holds them, for :class:`World` to be built from once (loading)."""

    sim: Simulation
    tree: GrowingTree
    genome: dict[str, float]
    roots: Roots
    carbon: CarbonBudget
    journal: Journal
    lineage: Lineage
    rng: np.random.Generator
    steps: int = 0
    last_light: float = float("-inf")
    dropped_lineage: int = 0
    crown: CrownRecord | None = None


@dataclass
class World:
    """Everything that evolves in the tamagotchi game, advanced with a fixed time step.

    Built once in one of three ways: ``World(system, rules, seed)`` plants the seed's sapling (meters
    full); with ``replanted=True`` the sapling of a new line (meters at a random 25-100 %, the seedling's
    seed drawn from the world's generator: a garden's newcomer, a new game); with ``parts`` a saved tree.
    """

    system: LSystem
    rules: Rules
    seed: int = 0
    position: tuple[float, float] = (0.0, 0.0)  # where the tree stands in a garden (x, z)
    lineage: Lineage | None = None  # parents, generation, planting (None: a line of its own starts)
    sim: Simulation = field(init=False)
    tree: GrowingTree = field(init=False)
    rng: np.random.Generator = field(init=False)
    steps: int = field(default=0, init=False)
    last_light: float = field(default=float("-inf"), init=False)  # game time of the last light reading
    journal: Journal = field(default_factory=Journal, init=False)
    log: Log = field(default_factory=Log, init=False)  # a checkpoint and every step and command since
    bare_at: float = field(default=-1.0, init=False)  # the day of the sun winter last stripped the leaves
    roots: Roots = field(init=False)  # grown below ground on water (engine/life/plant/roots.py)
    carbon: CarbonBudget = field(init=False)  # the sugar its leaves fix and its growth spends (plant/carbon.py)
    genome: dict[str, float] = field(init=False)  # its own values of the species' varying defines (plant/genome.py)
    editor: Modeler | None = field(default=None, init=False)  # the modeler's edit session (commands.py)
    crown: CrownRecord | None = field(default=None, init=False)  # the crown's lobes, part of the tree (saved)
    crown_steps: dict = field(default_factory=dict, init=False, repr=False)  # id(L-string) -> (it, its lobes)
    light_every: float | None = field(default=None, init=False)  # s between light readings, if not the rules'
    _segments: tuple | None = field(default=None, init=False, repr=False)  # (key, L-string, its drawn segments)
    last_economy: Economy | None = field(default=None, init=False, repr=False, compare=False)  # the last reading's
    # 1 when the save this tree was read from held a lineage that could not be trusted (so it starts a
    # line of its own): told to the player by the loader, never written back
    dropped_lineage: int = field(default=0, init=False)

    replanted: InitVar[bool] = False
    planted: InitVar[float] = 0.0  # wall-clock seconds of the planting, for a new lineage
    parts: InitVar[Parts | None] = None

    def __post_init__(self, replanted: bool, planted: float, parts: Parts | None) -> None:
        if parts is not None:
            self._take(parts)
        else:
            self.sim = Simulation(self.rules)
            self.sim.state.weather_seed = self.seed
            self.rng = np.random.Generator(np.random.PCG64(self.seed))
            given, self.lineage = self.lineage, self.lineage or new_lineage(self.seed, planted,
                                                                            species_of(self.system.file))
            if replanted:
                self._replant(planted, given)
            else:
                self.genome = genome.draw(self.system, self.seed)
                self.tree = self._plant(self.seed)
                self.roots = Roots(seed=self.seed)
                self.carbon = CarbonBudget.for_seedling(self.rules)
        self._species_traits()
        self.log.origin = snapshot(self)

    def _species_traits(self) -> None:
        """What the simulation takes from this tree's species (its .lsys, kept within the rules' ranges)."""
        self.sim.flood_tolerance = species_trait(self.tree.system.constants, "FLOOD", "water.flood_tolerance",
                                                 self.rules.water.flood_tolerance)
        self.tree.apical_fade = species_trait(self.tree.system.constants, "BHF", "growth.apical_fade",
                                              self.rules.growth.apical_fade)
        self.tree.dead_linger = self.rules.growth.dead_linger

    def _take(self, parts: Parts) -> None:
        """A saved tree's parts as this world's."""
        self.sim, self.tree, self.genome, self.roots = parts.sim, parts.tree, parts.genome, parts.roots
        self.carbon, self.journal, self.rng, self.steps = parts.carbon, parts.journal, parts.rng, parts.steps
        self.last_light, self.dropped_lineage, self.lineage = parts.last_light, parts.dropped_lineage, parts.lineage
        self.crown = parts.crown
        self.sync_roots()

    def expressed(self) -> LSystem:
        """The species' L-system with this tree's own genome (engine/life/plant/genome.py)."""
        return genome.expressed(self.system, self.genome)

    def _plant(self, seed: int) -> GrowingTree:
        """A sapling: the axiom grown to the rules' sapling age (its leader only, no side shoots)."""
        tree = GrowingTree(self.expressed(), seed=seed)
        age = self.rules.growth.sapling_age
        step = self.rules.growth.rewrite_step
        for k in range(1, int(age / step) + 1):
            tree.rewrite(k * step, k * step, 0.0)
        self.sim.state.length_time = self.sim.state.girth_time = tree.last_rewrite_T
        return tree

    def step(self, dt: float) -> None:
        """Advance the simulation by ``dt`` (see :func:`step_together`)."""
        step_together([self], dt)

    def advance(self, dt: float) -> None:
        """The simulation's part of a step (meters, clocks, health)."""
        self.sim.leaf_light = self.tree.mean_light  # (the sun meter fills with the light the leaves catch)
        self.sim.step(dt)
        self.steps += 1
        self.log.ran(dt)

    def light_due(self) -> bool:
        """True when the light interval (the rules', or a longer one while catching up: ``light_every``)
        has passed since the last light reading."""
        every = self.rules.light.interval if self.light_every is None else self.light_every
        return self.sim.state.time - self.last_light >= every

    def grow(self) -> None:
        """Rewrite the L-string if T has passed one rewrite step since the last rewrite; in the first part
        of winter (the rule seasons.leaf_drop) the leaves still on the tree fall (looked at once a day), unless
        its .lsys is EVERGREEN."""
        s = self.sim.state
        season = self.sim.season()
        if season.index == 3 and season.progress < self.rules.seasons.leaf_drop and self.bare_at != s.sun_turns // 1 \
                and not seasons.evergreen(self.tree.system.constants):  # (an evergreen keeps its needles)
            self.bare_at = s.sun_turns // 1  # (looked at once a day of the sun)
            self.tree.drop_leaves()
        if self.roots.grow(s.root_time, self.rules.roots.step):
            self.sync_roots()
        if s.length_time - self.tree.last_rewrite_T >= self.rules.growth.rewrite_step:
            self._rewrite()

    def _rewrite(self) -> None:
        """One rewrite at the sim's clocks, the shoots' growth paid for by the carbon pool: the pool funds
        a share of what the apices would build at full speed (extern C), and what was built is taken out."""
        s, tree, rules = self.sim.state, self.tree, self.rules
        const = {**tree.system.constants, **tree.geometry_constants}
        density = carbon.wood_density(tree.system.constants, rules)
        light = self.leaf_light()  # (shade leaves are thinner: carbon.leaf_mass)
        demand = carbon.shoot_demand(tree.lstring, s.length_time - tree.last_rewrite_T, const, rules, density, light)
        vigour = self.carbon.shoots_share(rules, demand, self._roots_due())
        self.carbon.vigour = vigour
        tree.rewrite(s.length_time, s.girth_time, self.sim.resources(), self.sim.leaf_vigour(),
                     {**self.sim.season_externs(s.length_time), "LG": self.sim.light_growth()}, vigour)
        self.carbon.spend(rules, carbon.built_cost(tree.lstring, s.length_time, const, rules, light))

    def _roots_due(self) -> float:
        """Dry mass (g) the roots are due by the functional balance until the next light reading (kept from the
        shoots: the roots are paid first, so a drier soil or a brighter crown gets more roots)."""
        return carbon.root_demand(self.carbon, self.rules, self.rules.light.interval, self.carbon.root_balance)

    def economy(self, seconds: float, shine: float) -> Economy:
        """This tree's dealings with its carbon budget for a light reading ``seconds`` after the last."""
        s, rules = self.sim.state, self.rules
        roots = self.sim.root_health()
        activity = min(max(seasons.growth_factor(s.sun_turns, rules), rules.carbon.dormant), 1.0)
        self.carbon.stored = rules.carbon.winter_keep * seasons.stores(s.sun_turns, rules)
        supply = carbon.stomata(s.water_meter, 1.0, rules)  # (what moist soil gives each root; drowning aside)
        need = self.sim.light_growth() / max(supply, 0.05)  # the crown's water need: its light on open leaves
        self.last_economy = Economy(
            self.carbon, rules, seconds, shine, carbon.stomata(s.water_meter, roots, rules), activity,
            carbon.wood_density(self.tree.system.constants, rules), seasons.leafy(s.sun_turns, rules),
            self.sim.light_growth(), photosynthesis.leaf_traits(self.tree.system.constants, rules),
            carbon.root_balance(need, supply, rules))
        self.carbon.root_balance = self.last_economy.root_balance  # (kept in the save: a loaded tree goes on alike)
        return self.last_economy

    def settle(self, seconds: float) -> None:
        """After a reading: the roots grow as far as the pool paid their due at it (a functional balance,
        carbon.root_demand: more in drought and in bright light, less in shade; Economy books it) and the
        simulation hears whether the tree is starving."""
        e = self.last_economy
        self.sim.state.root_vigour = e.root_paid * e.root_balance if e is not None else 0.0  # (<= carbon.root_most)
        self.sim.starving = self.carbon.starving
        self.sim.remember_light(self.light_caught(), seconds)

    def leaf_light(self) -> float:
        """The share of the open sky's light on the leaves: their mean light under the crowns (the last light
        reading) less the rules' shade."""
        return (1.0 - self.rules.sun.shade) * self.tree.mean_light

    def light_caught(self) -> float:
        """The light the leaves fixed sugar with at the last reading, 0..1 of what fully lit, open leaves of
        the same area would fix (0 at night); a bare tree counts the light its leaves last had."""
        if self.carbon.leaf_area > 0 and self.carbon.full_rate > 0:
            return self.carbon.caught()
        return self.sim.sunshine() * self.sim.uptake() * self.tree.mean_light

    def sync_roots(self) -> None:
        """Tell the simulation how big the roots are (they spare water)."""
        self.sim.root_share = self.roots.share(self.rules.roots.full_length)

    def status(self, dark: bool | None = None) -> str:
        """What the HUD says about this tree, from the one ranking of its real state
        (engine/life/world/status.py; ``dark``: the sky drawn is a night's)."""
        return tree_status(self, dark)

    def apply(self, command: Any, value: float = 0.0) -> Any:
        """Carry out a command (engine/life/world/commands.py; a world
        :class:`~arbor.engine.life.world.actions.Action` with its value stands for one), logged against the
        step; returns the command's result (what happened, for the screen and the sound)."""
        if isinstance(command, Action):
            command = of_action(command, value)
        self.log.applied(self, command)
        return command.run(self)

    def editing(self) -> Modeler:
        """The edit session the modeler's commands work on (a new one when there is none)."""
        return self.editor if self.editor is not None else BeginEditing().run(self)

    def drawn_segments(self, ls):
        """The segments of ``ls`` as the tree draws now (the modeler's view of its geometry; cached per
        L-string and clock: a stroke's every pointer move asks for them)."""
        key = (id(ls), len(ls), self.sim.state.length_time)
        cached = self._segments
        if cached is None or cached[0] != key or cached[1] is not ls:
            segs = grow_geometry(ls, self.clocks(), self.tree.geometry_constants).turtle.segments
            self._segments = cached = (key, ls, segs)
        return cached[2]

    def module_positions(self, ls) -> np.ndarray:
        """The turtle position of every module of ``ls`` as the tree draws now (for region edits)."""
        view = render_view(ls, self.clocks(), self.tree.geometry_constants)
        return module_positions(view, TurtleConfig(pipe_model=False, leaves_at_tips=0))

    def born_visible(self) -> float:
        """A birth time for leaves and blossoms added by an edit while time stands still: one growth time
        constant ago, so they show at once (63 % grown) and finish growing when time runs again."""
        return self.clocks().length_time - self.tree.geometry_constants["TAU"]

    def replant_now(self, planted: float | None = None) -> None:
        """A fresh sapling (and a fresh line of descent) in this tree's place (the :class:`Replant` command)."""
        self._replant(self.lineage.planted if planted is None else planted)
        self.editor, self.crown = None, None  # (the old tree's edits and lobes are gone with it)

    def _replant(self, planted: float, lineage: Lineage | None = None) -> None:
        """The sapling of a new seed drawn from the world's generator, meters at the rules' random refill;
        ``lineage``: its line (default: a new one, planted at ``planted``)."""
        self.sim.replant(self.rng)
        seed = int(self.rng.integers(2**31))
        self.genome = genome.draw(self.system, seed)  # a new seedling: its own traits
        self.tree = self._plant(seed)
        self.lineage = lineage or new_lineage(seed, planted, self.lineage.species)  # a new line starts
        self.roots = Roots(seed=seed)
        self.carbon = CarbonBudget.for_seedling(self.rules)
        self.last_light = float("-inf")  # (the new sim's clock starts at 0: its light is read at once)
        self.sync_roots()
        self._species_traits()

    def catch_up(self, seconds: float, dt: float = 1.0, max_steps: int = MAX_CATCH_UP_STEPS) -> int:
        """Let the tree live ``seconds`` of game time unattended (offline growth; see :func:`live`)."""
        return live([self], seconds, dt, max_steps)

    def clocks(self, previous: SimState | None = None, alpha: float = 1.0) -> Clocks:
        """The clocks to draw, interpolated between the previous and the current sim state."""
        s = self.sim.state
        if previous is None or alpha >= 1.0:
            return Clocks(s.length_time, s.girth_time, s.wilt)
        lerp = lambda a, b: a + (b - a) * alpha  # noqa: E731
        return Clocks(lerp(previous.length_time, s.length_time), lerp(previous.girth_time, s.girth_time),
                      lerp(previous.wilt, s.wilt))


def catch_up_steps(seconds: float, dt: float, max_steps: int) -> tuple[int, float]:
    """How many steps of which length live ``seconds`` (0 for a time that is not a positive number)."""
    if not seconds > 0 or not seconds < float("inf"):
        return 0, dt
    wanted = seconds / dt
    if wanted <= max_steps:
        return int(wanted), dt
    return max_steps, seconds / max_steps


def step_together(worlds: list[World], dt: float, rocks: Obstacles | None = None) -> None:
    """The one step loop: advance every tree of a plot or garden by ``dt`` (meters, clocks, health), one
    light reading for all of them when it is due (neighbours shade each other; shoots grow round
    ``rocks``), then each tree rewrites its L-string if T has passed one rewrite step."""
    for world in worlds:
        world.advance(dt)
    if any(world.light_due() for world in worlds):
        sense_light(worlds, rocks)
    for world in worlds:
        world.grow()


def live(worlds: list[World], seconds: float, dt: float = 1.0, max_steps: int = MAX_CATCH_UP_STEPS,
         rocks: Obstacles | None = None) -> int:
    """``worlds`` live ``seconds`` of game time unattended under one sun, in coarse steps: never more than
    ``max_steps`` (longer times take longer steps). Returns the steps taken."""
    steps, dt = catch_up_steps(seconds, dt, max_steps)
    for _ in range(steps):
        step_together(worlds, dt, rocks)
    return steps


def sense_light(worlds: list[World], rocks: Obstacles | None = None) -> None:
    """One light reading for trees that share a sun (a garden): every tree's leaves shade every tree;
    every tree's shoots bend away from the others' wood and from ``rocks`` (engine/life/plant/collide.py)."""
    if not worlds:
        return
    sim = worlds[0].sim
    sun, shine = sim.sun_direction(), sim.sunshine()
    rules = worlds[0].rules.light
    seconds = []
    for world in worlds:
        since = world.sim.state.time - world.last_light
        seconds.append(since if math.isfinite(since) else 0.0)  # (the first reading books nothing)
        world.last_light = world.sim.state.time
    if shine <= 0:  # night: nothing to read or remember; wood grown meanwhile is added at the next reading
        for world, since in zip(worlds, seconds, strict=True):
            world.economy(since, 0.0).rest(world.tree.leaf_area(world.sim.state.length_time))  # (no turtle at night)
            world.settle(since)
            if world.tree.last_sense_length is not None:
                world.tree.last_sense_length = world.sim.state.length_time
        return
    scenes = [world.tree.light_scene(world.clocks()) for world in worlds]
    offsets = [np.array([world.position[0], 0.0, world.position[1]]) for world in worlds]
    queries = [scene.queries + offset for scene, offset in zip(scenes, offsets, strict=True)]
    occluders = np.concatenate([s.leaf_center + o for s, o in zip(scenes, offsets, strict=True)])
    area = np.concatenate([s.leaf_area for s in scenes])
    self_index, first = [], 0
    for scene, q in zip(scenes, queries, strict=True):
        k = len(scene.leaf_idx)
        self_index.append(np.concatenate([first + np.arange(k), np.full(len(q) - k, -1)]))
        first += k
    light = exposure(occluders, area, np.concatenate(queries), sun, rules, np.concatenate(self_index))
    start = 0
    for world, scene, q, since in zip(worlds, scenes, queries, seconds, strict=True):
        part = light[start:start + len(q)]
        start += len(q)
        leafy = seasons.leafy(world.sim.state.sun_turns, world.rules)
        world.tree.sense(scene, part, world.clocks(), shine, sun, rules.memory, world.sim.drought(), leafy,
                         _obstacles(world, worlds, scenes, offsets, rocks), world.economy(since, shine))
        world.settle(since)
        world.journal.observe(world, world.tree.height)


def _obstacles(world: World, worlds: list[World], scenes: list, offsets: list[np.ndarray],
               rocks: Obstacles | None) -> Obstacles:
    """What ``world``'s shoots must avoid, in its own frame: the other trees' wood and the rocks."""
    here = np.array([world.position[0], 0.0, world.position[1]])
    parts = [collide.wood(scene.turtle.segments, offset - here)
             for other, scene, offset in zip(worlds, scenes, offsets, strict=True) if other is not world]
    if rocks is not None:
        parts.append(rocks.moved(-here))
    return collide.Obstacles.join(parts)
