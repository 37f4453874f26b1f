"""A garden: up to six trees under one sun, one of them the tree the player is caring for.

Planting spirals outwards by the golden angle so trees never crowd; every tree steps with the same
time step; sun sliders act on every tree (there is one sun).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from arbor.engine.life.lineage.breed import cross
from arbor.engine.life.lineage.lineage import Family, new_lineage, species_of
from arbor.engine.life.plant import collide
from arbor.engine.life.rules.rules import Rules
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.commands import Harvest, Place
from arbor.engine.life.world.world import MAX_CATCH_UP_STEPS, World, live, step_together
from arbor.engine.lsystem.lsys import LSystem

MAX_GARDEN = 6  # trees in one garden
MAX_SEEDS = 50  # seeds kept in the seed bag
MAX_ROCKS = 20
GARDEN_SPACING = 7.0  # scene units between neighbouring trees


@dataclass(frozen=True)
class Seed:
    """A harvested seed: which tree it came from (its seed and its L-system's hash) and its own number."""

    parent_seed: int
    parent_sha: str
    number: int


class Garden:
    """The trees of one garden and which one is cared for."""

    def __init__(self, worlds: list[World], current: int = 0, seeds: list[Seed] | None = None,
                 family: Family | None = None) -> None:
        if not worlds:
            raise ValueError("a garden has at least one tree")
        self.worlds = list(worlds)
        self.current = min(max(current, 0), len(self.worlds) - 1)
        self.seeds: list[Seed] = list(seeds or [])  # harvested, waiting to be planted
        self.family = family or Family()  # every tree this garden has known
        self.rocks: list[tuple[float, float, float, float]] = []  # (x, y, z, radius): shoots grow around them
        for world in self.worlds:
            self.family.add(world.lineage)

    @property
    def world(self) -> World:
        """The tree the player is caring for."""
        return self.worlds[self.current]

    @world.setter
    def world(self, world: World) -> None:
        self.worlds[self.current] = world

    @property
    def others(self) -> list[World]:
        """Every tree but the cared-for one, in planting order."""
        return [w for i, w in enumerate(self.worlds) if i != self.current]

    @property
    def full(self) -> bool:
        """True when no more trees fit."""
        return len(self.worlds) >= MAX_GARDEN

    def plant(self, system: LSystem, rules: Rules, seed: int | None = None, now: float = 0.0,
              parents: tuple[World, ...] = (), species: str | None = None) -> World:
        """A new sapling beside the others, under the same sun; it becomes the cared-for tree. ``now``
        (wall-clock seconds) and ``parents`` go into its lineage."""
        if self.full:
            raise ValueError(f"a garden holds at most {MAX_GARDEN} trees")
        k = len(self.worlds)
        seed = (self.world.seed * 7919 + k * 104729) % 2**31 if seed is None else seed
        lineage = new_lineage(seed, now, species or species_of(system.file), tuple(p.lineage for p in parents))
        world = World(system, rules, seed=seed, lineage=lineage, replanted=True)
        self._place(world)
        world.journal.write(world.sim.state.time, "planted", float(world.seed))
        self.family.add(world.lineage)
        self.worlds.append(world)
        self.current = len(self.worlds) - 1
        return world

    def adopt(self, world: World) -> World:
        """Plant a grown tree from elsewhere (a shared card) beside the others, under this garden's sun and
        calendar; it keeps its own growth, lineage and meters and becomes the cared-for tree."""
        if self.full:
            raise ValueError(f"a garden holds at most {MAX_GARDEN} trees")
        self._place(world)
        self.family.add(world.lineage)
        self.worlds.append(world)
        self.current = len(self.worlds) - 1
        return world

    def _place(self, world: World) -> None:
        """Put a newcomer at the garden's next free spot, under the one sun the others see."""
        k = len(self.worlds)
        angle = k * 2.39996  # golden angle: the garden spirals outwards without crowding
        radius = GARDEN_SPACING * math.sqrt(k)
        sun = self.world.sim.state  # one sun, one calendar, one weather: the new tree sees them as the others do
        world.apply(Place((radius * math.cos(angle), radius * math.sin(angle)),
                          (sun.orbit_height, sun.sun_speed, sun.sun_angle, sun.sun_turns, sun.weather_seed)))

    def harvest(self, world: World, fruit_module: int) -> Seed | None:
        """Pick the fruit that is module ``fruit_module`` of ``world``'s tree: it leaves the tree and its
        seed (which knows its parent) goes into the seed bag. None when that is not a ripe fruit."""
        born = world.apply(Harvest(fruit_module))
        if born is None:
            return None
        seed = Seed(parent_seed=world.seed, parent_sha=world.system.sha256, number=int(born * 1000) % 2**31)
        if len(self.seeds) < MAX_SEEDS:
            self.seeds.append(seed)
        return seed

    def plant_seed(self, rules: Rules, fallback: LSystem, now: float = 0.0) -> World | None:
        """Plant the oldest seed from the bag. The wind brought it pollen from another tree of the garden
        (chosen by the seed), so the sapling is a cross of its parent and that tree; alone in the garden,
        the parent pollinates itself (a mutated copy of its L-system)."""
        if not self.seeds or self.full:
            return None
        seed = self.seeds.pop(0)
        parent = next((w for w in self.worlds if w.system.sha256 == seed.parent_sha
                       and w.seed == seed.parent_seed), None)
        parent = parent or next((w for w in self.worlds if w.system.sha256 == seed.parent_sha), None)
        child_seed = (seed.parent_seed * 31 + seed.number) % 2**31
        if parent is None:
            return self.plant(fallback, rules, seed=child_seed, now=now)
        others = [w for w in self.worlds if w is not parent]
        pollen = others[seed.number % len(others)] if others else parent
        return self.breed(parent, pollen, child_seed, rules, now)

    def breed(self, mother: World, father: World, seed: int, rules: Rules, now: float = 0.0) -> World:
        """Cross two trees into a sapling planted in this garden (see engine/life/lineage/breed.py)."""
        child = cross(mother.system, father.system, seed, name=f"{mother.lineage.species} x {father.lineage.species}")
        species = mother.lineage.species if mother.lineage.species == father.lineage.species else "cross"
        return self.plant(child.system, rules, seed=seed, now=now, parents=(mother, father), species=species)

    def next(self) -> World:
        """Care for the next tree (round the garden in planting order)."""
        self.current = (self.current + 1) % len(self.worlds)
        return self.world

    def apply_sun(self, action: Action, value: float) -> None:
        """A sun slider: one sun shines on the whole garden."""
        if not action.on_sun:
            raise ValueError(f"not a sun action: {action.value!r}")
        for world in self.worlds:
            world.apply(action, value)

    def step(self, dt: float) -> None:
        """Advance every tree by ``dt`` through the one step loop (neighbours shade each other)."""
        step_together(self.worlds, dt, collide.rocks(self.rocks))

    def catch_up(self, seconds: float, dt: float = 1.0, max_steps: int = MAX_CATCH_UP_STEPS) -> int:
        """Every tree lives ``seconds`` of game time unattended, under one sun, in at most ``max_steps``
        steps. Returns the steps taken."""
        return live(self.worlds, seconds, dt, max_steps, collide.rocks(self.rocks))
