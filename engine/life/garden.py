"""A garden: up to six trees under one sun, one of them the tree the player is caring for.

Planting spirals outwards by the golden angle so trees never crowd; every tree steps with the same
time step; sun sliders act on every tree (there is one sun).
"""

from __future__ import annotations

import math

from engine.life.sim import Rules
from engine.life.world import MAX_CATCH_UP_STEPS, World, catch_up_steps, sense_light
from engine.lsystem.lsys import LSystem

MAX_GARDEN = 6  # trees in one garden
GARDEN_SPACING = 7.0  # scene units between neighbouring trees
SUN_ACTIONS = ("orbit_height", "sun_speed")


class Garden:
    """The trees of one garden and which one is cared for."""

    def __init__(self, worlds: list[World], current: int = 0) -> None:
        if not worlds:
            raise ValueError("a garden has at least one tree")
        self.worlds = list(worlds)
        self.current = min(max(current, 0), len(self.worlds) - 1)

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

    def plant(self, system: LSystem, rules: Rules) -> World:
        """A new sapling beside the others, under the same sun; it becomes the cared-for tree."""
        if self.full:
            raise ValueError(f"a garden holds at most {MAX_GARDEN} trees")
        k = len(self.worlds)
        angle = k * 2.39996  # golden angle: the garden spirals outwards without crowding
        radius = GARDEN_SPACING * math.sqrt(k)
        seed = (self.world.seed * 7919 + k * 104729) % 2**31
        world = World(system, rules, seed=seed)
        world.apply("replant", 1.0)
        sun = self.world.sim.state
        world.apply("orbit_height", sun.orbit_height)
        world.apply("sun_speed", sun.sun_speed)
        world.sim.state.sun_angle = sun.sun_angle  # one sun: the new tree sees it where the others do
        world.position = (radius * math.cos(angle), radius * math.sin(angle))
        self.worlds.append(world)
        self.current = len(self.worlds) - 1
        return world

    def next(self) -> World:
        """Care for the next tree (round the garden in planting order)."""
        self.current = (self.current + 1) % len(self.worlds)
        return self.world

    def apply_sun(self, action: str, value: float) -> None:
        """A sun slider: one sun shines on the whole garden."""
        if action not in SUN_ACTIONS:
            raise ValueError(f"not a sun action: {action!r}")
        for world in self.worlds:
            world.apply(action, value)

    def step(self, dt: float) -> None:
        """Advance every tree by ``dt``; one light reading for the whole garden when it is due, so
        neighbours shade each other."""
        for world in self.worlds:
            world.advance(dt)
        due = [w for w in self.worlds if w.light_due()]
        if due:
            sense_light(self.worlds)
        for world in self.worlds:
            world.grow()

    def catch_up(self, seconds: float, dt: float = 1.0, max_steps: int = MAX_CATCH_UP_STEPS) -> int:
        """Every tree lives ``seconds`` of game time unattended, under one sun, in at most ``max_steps``
        steps. Returns the steps taken."""
        steps, dt = catch_up_steps(seconds, dt, max_steps)
        for _ in range(steps):
            self.step(dt)
        return steps
