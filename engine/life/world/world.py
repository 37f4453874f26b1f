"""The game's world: simulation + growing tree + the player's actions, stepped deterministically.

Given the same seed, rules, L-system and the same actions at the same steps, two worlds produce
identical trees and meters (tests rely on it; every world's input log makes its life replayable).
"""

from __future__ import annotations

import math
from dataclasses import InitVar, dataclass, field

import numpy as np

from arbor.engine.life.form.interpret import Clocks
from arbor.engine.life.lineage.lineage import Lineage, new_lineage, species_of
from arbor.engine.life.plant import carbon, collide, genome, seasons
from arbor.engine.life.plant.carbon import CarbonBudget, Economy
from arbor.engine.life.plant.collide import Obstacles
from arbor.engine.life.plant.growth import GrowingTree
from arbor.engine.life.plant.journal import Journal
from arbor.engine.life.plant.light import exposure
from arbor.engine.life.plant.roots import Roots
from arbor.engine.life.plant.sim import Rules, SimState, Simulation
from arbor.engine.life.world import prune
from arbor.engine.life.world.actions import Action
from arbor.engine.lsystem.lsys import LSystem

MAX_CATCH_UP_STEPS = 20_000  # a catch-up never takes more steps than this, whatever the rules say
InputLog = list[tuple[int, Action, float]]  # (step, action, value): what was applied before which step


@dataclass
class World:
    """Everything that evolves in the tamagotchi game, advanced with a fixed time step."""

    system: LSystem
    rules: Rules
    seed: int = 0
    sim: Simulation = field(init=False)
    tree: GrowingTree = field(init=False)
    rng: np.random.Generator = field(init=False)
    steps: int = 0
    position: tuple[float, float] = (0.0, 0.0)  # where the tree stands in a garden (x, z)
    last_light: float = float("-inf")  # game time of the last light reading
    journal: Journal = field(default_factory=Journal)
    input_log: InputLog = field(default_factory=list)  # every applied action, for :func:`replay`
    bare_at: float = -1.0  # the day of the sun winter last stripped the leaves
    lineage: Lineage = field(init=False)  # parents, generation, planting (engine/life/lineage.py)
    roots: Roots = field(init=False)  # grown below ground on water (engine/life/roots.py)
    carbon: CarbonBudget = field(init=False)  # the sugar its leaves fix and its growth spends (plant/carbon.py)
    genome: dict[str, float] = field(init=False)  # its own values of the species' varying defines (plant/genome.py)
    # 1 when the save this tree was read from held a lineage that could not be trusted (so it starts a
    # line of its own): told to the player by the loader, never written back
    dropped_lineage: int = field(default=0, init=False)

    plant: InitVar[bool] = True  # False: an empty tree, for a save to fill in (loading plants nothing)

    def __post_init__(self, plant: bool) -> None:
        self.sim = Simulation(self.rules)
        self.sim.state.weather_seed = self.seed
        self.rng = np.random.Generator(np.random.PCG64(self.seed))
        self.genome = genome.draw(self.system, self.seed)
        self.tree = self._plant(self.seed) if plant else GrowingTree(self.expressed(), seed=self.seed)
        self.lineage = new_lineage(self.seed, 0.0, species_of(self.system.file))
        self.roots = Roots(seed=self.seed)
        self.carbon = CarbonBudget.for_seedling(self.rules)

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
        """Advance the simulation by ``dt``: read the light when due, rewrite the L-string each time T
        passed one rewrite step."""
        self.advance(dt)
        if self.light_due():
            sense_light([self])
        self.grow()

    def advance(self, dt: float) -> None:
        """The simulation's part of a step (meters, clocks, health)."""
        self.sim.leaf_light = self.tree.mean_light  # (the sun meter fills with the light the leaves catch)
        self.sim.step(dt)
        self.steps += 1

    def light_due(self) -> bool:
        """True when the rules' light interval has passed since the last light reading."""
        return self.sim.state.time - self.last_light >= self.rules.light.interval

    def grow(self) -> None:
        """Rewrite the L-string if T has passed one rewrite step since the last rewrite; in the first half
        of winter the leaves still on the tree fall (looked at once a day)."""
        s = self.sim.state
        season = self.sim.season()
        if season.index == 3 and season.progress < 0.5 and self.bare_at != s.sun_turns // 1:
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
        demand = carbon.shoot_demand(tree.lstring, s.length_time - tree.last_rewrite_T, const, rules, density)
        vigour = self.carbon.share(rules, demand)
        self.carbon.vigour = vigour
        tree.rewrite(s.length_time, s.girth_time, self.sim.resources(), self.sim.leaf_vigour(),
                     {**self.sim.season_externs(s.length_time), "LG": self.sim.light_growth()}, vigour)
        self.carbon.spend(carbon.built_cost(tree.lstring, s.length_time, const, rules, density))

    def economy(self, seconds: float, shine: float) -> Economy:
        """This tree's dealings with its carbon budget for a light reading ``seconds`` after the last."""
        s, rules = self.sim.state, self.rules
        drowned = s.drowning > rules.water.drown_time
        activity = min(max(seasons.growth_factor(s.sun_turns, rules), rules.carbon.dormant), 1.0)
        return Economy(self.carbon, rules, seconds, shine, carbon.stomata(self.sim.drought(), drowned), activity,
                       carbon.wood_density(self.tree.system.constants, rules), seasons.leafy(s.sun_turns, rules),
                       self.sim.light_growth())

    def settle(self, seconds: float) -> None:
        """After a reading: the roots get their share of the pool (more in drought: a functional balance)
        and the simulation hears whether the tree is starving."""
        rules = self.rules
        boost = 1.0 + rules.carbon.root_drought * self.sim.drought()
        demand = rules.carbon.root_cost * boost * seconds
        paid = self.carbon.fund(rules, demand)
        self.carbon.roots_built += paid * demand
        self.sim.root_vigour = paid * boost
        self.sim.starving = self.carbon.starving
        self.sim.remember_light(self.light_caught(), seconds)

    def light_caught(self) -> float:
        """The light the leaves fixed sugar with at the last reading, 0..1 of what fully lit, open leaves of
        the same area would fix (0 at night); a bare tree counts the light its leaves last had."""
        area, rules = self.carbon.leaf_area, self.rules
        if area > 0:
            return min(self.carbon.last_fixed_rate / (rules.carbon.assimilation * area), 1.0)
        drowned = self.sim.state.drowning > rules.water.drown_time
        return self.sim.sunshine() * carbon.stomata(self.sim.drought(), drowned) * self.tree.mean_light

    def prune(self, keep_height: float | None = None, lowest: float = 0.0) -> int:
        """Cut the tree back to ``keep_height`` metres and/or cut the ``lowest`` share of its trunk's
        branches (engine/life/world/prune.py); recorded in the journal. Returns the branches cut."""
        return prune.prune(self, keep_height, lowest)

    def sync_roots(self) -> None:
        """Tell the simulation how big the roots are (they spare water)."""
        self.sim.root_share = self.roots.share(self.rules.roots.full_length)

    def status(self, dark: bool | None = None) -> str:
        """What the HUD says about this tree (see :meth:`Simulation.status`; ``dark``: the sky drawn is a
        night's); a tree that grows by day but whose leaves get little light says it needs light."""
        status = self.sim.status(dark)
        shaded = self.tree.mean_light < self.tree.geometry_constants["SHQ"]
        if status == "growing" and self.sim.sunshine() > 0 and shaded:
            return "needs_light"
        return status

    def apply(self, action: Action, value: float = 0.0) -> None:
        """A world action (:data:`~arbor.engine.life.world.actions.WORLD_ACTIONS`): water (1 = can held,
        0 = released), the sun's sliders (simulation values) or replant; logged against the step."""
        if not action.on_world:
            raise ValueError(f"not an action of the world: {action.value!r}")
        self.input_log.append((self.steps, action, value))
        if action is Action.WATER:
            self.sim.state.watering = bool(value)
        elif action is Action.ORBIT_HEIGHT:
            self.sim.set_orbit_height(value)
        elif action is Action.SUN_SPEED:
            self.sim.set_sun_speed(value)
        else:
            self._replant()

    def _replant(self) -> None:
        """A fresh sapling (and a fresh line of descent) in this tree's place."""
        self.sim.replant(self.rng)
        seed = int(self.rng.integers(2**31))
        self.genome = genome.draw(self.system, seed)  # a new seedling: its own traits
        self.tree = self._plant(seed)
        self.lineage = new_lineage(seed, self.lineage.planted, self.lineage.species)  # a new line starts
        self.roots = Roots(seed=seed)
        self.carbon = CarbonBudget.for_seedling(self.rules)
        self.last_light = float("-inf")  # (the new sim's clock starts at 0: its light is read at once)
        self.sync_roots()

    def catch_up(self, seconds: float, dt: float = 1.0, max_steps: int = MAX_CATCH_UP_STEPS) -> int:
        """Let the tree live ``seconds`` of game time unattended (offline growth), in coarse steps:
        never more than ``max_steps`` (longer times take longer steps). Returns the steps taken."""
        steps, dt = catch_up_steps(seconds, dt, max_steps)
        for _ in range(steps):
            self.step(dt)
        return steps

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


def sense_light(worlds: list[World], rocks: Obstacles | None = None) -> None:
    """One light reading for trees that share a sun (a garden): every tree's leaves shade every tree;
    every tree's shoots bend away from the others' wood and from ``rocks`` (engine/life/collide.py)."""
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


def replay(system: LSystem, rules: Rules, seed: int, log: InputLog, steps: int, dt: float) -> World:
    """A new world run for ``steps`` fixed steps, applying each logged action before its step."""
    world = World(system, rules, seed=seed)
    pending = sorted(log, key=lambda entry: entry[0])
    k = 0
    for i in range(steps):
        while k < len(pending) and pending[k][0] <= i:
            world.apply(pending[k][1], pending[k][2])
            k += 1
        world.step(dt)
    return world
