"""The fast-forward guardian: every tree of the garden watched, so time flying by never kills one.

At 10x and 100x a meter crosses a day's worth of drain in seconds. The game asks :meth:`Guardian.watch`
after each step; before a water meter reaches the need line (the growth threshold), before a sun meter
reaches the neglect level, when the roots start to drown or a tree starts to wilt, it names that tree
and its need, once, and the game drops back to 1x (like sleeping until morning in a farming game).
:meth:`Guardian.tend` is what "go on" does, and what the kiosk's autopilot does while nobody plays: the
watering can pours on each tree in need until its meter is comfortable, the one sun is raised to at
least its default height when a sun meter runs low, a drowning tree's can is let go.
The margins are rules (``health.guard_margin``, ``health.comfort``).

The :class:`Gardener` (the player's "the gardener cares while you skip", at 10x and 100x) does the
autopilot's tending every step, so water and light stay in the healthy band and no need stops time; it
stops only for what a player must decide (DECISIONS): ripe fruit to pick, a tree wilting despite the care
(or dead), the first day of a season.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from arbor.engine.life.rules.rules import Rules
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.garden import Garden
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lstring import LString

NEEDS = ("drown", "water", "sun", "wilt")  # in the order the guardian tells them
DECISIONS = ("died", "dying", "fruit", "season")  # what stops the gardener, in the order it tells them


@dataclass(frozen=True)
class Need:
    """One tree's need: ``index`` in the garden (tree number - 1) and what (one of NEEDS)."""

    index: int
    what: str


def needs_of(world: World, rules: Rules) -> list[str]:
    """What this tree needs now, in NEEDS order ([] for a dead tree: there is nothing to save)."""
    s = world.sim.state
    if not s.alive:
        return []
    margin = rules.health.guard_margin
    out = []
    if s.water_meter > rules.water.drown_level:
        out.append("drown")
    if s.water_meter < rules.growth.threshold + margin:
        out.append("water")
    if s.sun_meter < rules.health.neglect_level + margin:
        out.append("sun")
    if s.wilt > 0.0 and (world.sim.starving > rules.carbon.starve_time or min(s.sun_meter, s.water_meter)
                         < rules.health.neglect_level or world.sim.drowned()):
        out.append("wilt")
    return out


class Guardian:
    """Watches a garden for needs (told once each, until they pass) and tends it (see module docstring)."""

    def __init__(self, rules: Rules) -> None:
        self.rules = rules
        self.told: set[tuple[int, str]] = set()  # (id of the world, need) already told and not yet gone
        self.pouring: set[int] = set()  # ids of the worlds whose can the guardian holds

    def watch(self, garden: Garden) -> Need | None:
        """The first need not told yet (it is told now), or None; needs that passed are forgotten, so a
        thirst that comes back is told again."""
        now = {(id(w), what): (i, what) for i, w in enumerate(garden.worlds) for what in needs_of(w, self.rules)}
        self.told &= set(now)
        for key, (index, what) in now.items():
            if key not in self.told:
                self.told.add(key)
                return Need(index, what)
        return None

    def tend(self, garden: Garden) -> None:
        """Give every tree what it needs: the can pours on the thirsty until comfortable, a drowning tree's
        can is let go, and the sun is raised to at least its default height when a sun meter runs low."""
        low_sun = False
        for world in garden.worlds:
            needs = needs_of(world, self.rules)
            if "drown" in needs:
                self._release(world)
            elif "water" in needs and id(world) not in self.pouring:
                world.apply(Action.WATER, 1.0)
                self.pouring.add(id(world))
            low_sun = low_sun or "sun" in needs
        height = garden.world.sim.state.orbit_height
        if low_sun and height < self.rules.sun.orbit_height:
            garden.apply_sun(Action.ORBIT_HEIGHT, self.rules.sun.orbit_height)
        self.care(garden)

    def care(self, garden: Garden) -> None:
        """After each step: let go of the can of every tree the guardian waters once it is comfortable."""
        if not self.pouring:
            return
        for world in garden.worlds:
            if id(world) in self.pouring and (world.sim.state.water_meter >= self.rules.health.comfort
                                              or not world.sim.state.alive):
                self._release(world)
        self.pouring &= {id(w) for w in garden.worlds}

    def autopilot(self, garden: Garden) -> None:
        """The kiosk with nobody there: tend whatever needs it, every step (told or not)."""
        if any(needs_of(w, self.rules) for w in garden.worlds):
            self.tend(garden)
        else:
            self.care(garden)

    def _release(self, world: World) -> None:
        if id(world) in self.pouring or world.sim.state.watering:
            world.apply(Action.WATER, 0.0)
        self.pouring.discard(id(world))


def fruit_births(ls: LString) -> np.ndarray:
    """The births of the fruit ``O(birth)`` on ``ls``, earliest first."""
    fruit = np.flatnonzero((ls.sym == ord("O")) & (ls.nparams >= 1))
    return np.sort(ls.params[ls.offsets[fruit]])


def ripe_fruit(world: World, births: np.ndarray | None = None) -> int:
    """Ripe fruit on the tree now (fruit older than the species' RIPEN on the tree's clock); ``births``:
    :func:`fruit_births` of its L-string, when known."""
    births = fruit_births(world.tree.lstring) if births is None else births
    ripe_before = world.sim.state.length_time - world.tree.geometry_constants["RIPEN"]
    return int(np.searchsorted(births, ripe_before, side="right"))


def decisions_of(world: World) -> list[str]:
    """What this tree asks of its player now: died, or dying (ripe fruit and the season are the garden's)."""
    s = world.sim.state
    if not s.alive:
        return ["died"]
    return ["dying"] if s.wilt > world.rules.health.wilt_shown else []


class Gardener:
    """Fast-forward with the gardener (see module docstring): :meth:`care` after each step tends the
    garden as the kiosk's autopilot does and returns the first decision not told yet, or None."""

    def __init__(self, guardian: Guardian) -> None:
        self.guardian = guardian
        self.told: set[tuple[int, str]] = set()  # (id of the world, decision) told and not yet gone
        self.season: tuple[int, int] | None = None  # (year, season) last seen
        self.births: dict[int, tuple[LString, np.ndarray]] = {}  # id of the world -> (its L-string, fruit_births)

    def care(self, garden: Garden) -> Need | None:
        """Tend every tree (water and light kept in the healthy band), then a decision to stop for."""
        self.guardian.autopilot(garden)
        return self.decide(garden)

    def decide(self, garden: Garden) -> Need | None:
        """The first decision not told yet (told now): a tree died or wilts despite the care, ripe fruit on
        any tree (told once until no tree has any), then a season's first day; decisions that passed are
        forgotten, so they are told again later."""
        now = {(id(w), what): (i, what) for i, w in enumerate(garden.worlds) for what in decisions_of(w)}
        if len(self.births) > len(garden.worlds):  # (trees replanted or gone: forget theirs)
            self.births = {id(w): self.births[id(w)] for w in garden.worlds if id(w) in self.births}
        ripe = next((i for i, w in enumerate(garden.worlds) if w.sim.state.alive and self._ripe(w)), None)
        if ripe is not None:  # (the garden's: one stop while any tree has ripe fruit, not one a tree)
            now[(id(garden), "fruit")] = (ripe, "fruit")
        self.told &= set(now)
        for key, (index, what) in now.items():
            if key not in self.told:
                self.told.add(key)
                return Need(index, what)
        season = garden.world.sim.season()
        seen, self.season = self.season, (season.year, season.index)
        if seen is not None and seen != self.season:
            return Need(garden.current, "season")
        return None

    def _ripe(self, world: World) -> int:
        """:func:`ripe_fruit`, the fruit found again only when the tree's L-string changed (a rewrite, a
        pick: every step at 100x scanned every tree's modules)."""
        ls, kept = world.tree.lstring, self.births.get(id(world))
        if kept is None or kept[0] is not ls:
            kept = self.births[id(world)] = (ls, fruit_births(ls))
        return ripe_fruit(world, kept[1])
