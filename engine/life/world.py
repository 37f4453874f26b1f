"""The game's world: simulation + growing tree + the player's actions, stepped deterministically.

Given the same seed, rules, L-system and the same actions at the same steps, two worlds produce
identical trees and meters (tests rely on it; the input log makes bug reports replayable).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from engine.life.growth import Clocks, GrowingTree
from engine.life.sim import Rules, SimState, Simulation
from engine.lsystem.lsys import LSystem

ACTIONS = ("water", "orbit_height", "sun_speed", "replant")
InputLog = list[tuple[int, str, float]]


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

    def __post_init__(self) -> None:
        self.sim = Simulation(self.rules)
        self.rng = np.random.Generator(np.random.PCG64(self.seed))
        self.tree = self._plant(self.seed)

    def _plant(self, seed: int) -> GrowingTree:
        """A sapling: the axiom grown to the rules' sapling age (its leader only, no side shoots)."""
        tree = GrowingTree(self.system, seed=seed)
        age = self.rules.growth.sapling_age
        step = self.rules.growth.rewrite_step
        for k in range(1, int(age / step) + 1):
            tree.rewrite(k * step, k * step, 0.0)
        self.sim.state.length_time = self.sim.state.girth_time = tree.last_rewrite_T
        return tree

    def step(self, dt: float) -> None:
        """Advance the simulation by ``dt``; rewrite the L-string each time T passed one rewrite step."""
        self.sim.step(dt)
        self.steps += 1
        s = self.sim.state
        if s.length_time - self.tree.last_rewrite_T >= self.rules.growth.rewrite_step:
            self.tree.rewrite(s.length_time, s.girth_time, self.sim.resources())

    def apply(self, action: str, value: float = 0.0) -> None:
        """A player action: 'water' (1 = can held, 0 = released), slider values, or 'replant'."""
        if action == "water":
            self.sim.state.watering = bool(value)
        elif action == "orbit_height":
            self.sim.set_orbit_height(value)
        elif action == "sun_speed":
            self.sim.set_sun_speed(value)
        elif action == "replant":
            self.sim.replant(self.rng)
            self.tree = self._plant(int(self.rng.integers(2**31)))
        else:
            raise ValueError(f"unknown action {action!r}")

    def catch_up(self, seconds: float, dt: float = 1.0) -> None:
        """Let the tree live ``seconds`` of game time unattended (offline growth), in coarse steps."""
        for _ in range(int(seconds / dt)):
            self.step(dt)

    def clocks(self, previous: SimState | None = None, alpha: float = 1.0) -> Clocks:
        """The clocks to draw, interpolated between the previous and the current sim state."""
        s = self.sim.state
        if previous is None or alpha >= 1.0:
            return Clocks(s.length_time, s.girth_time, s.wilt)
        lerp = lambda a, b: a + (b - a) * alpha  # noqa: E731
        return Clocks(lerp(previous.length_time, s.length_time), lerp(previous.girth_time, s.girth_time),
                      lerp(previous.wilt, s.wilt))


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
