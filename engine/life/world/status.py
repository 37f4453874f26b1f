"""What the HUD says about a tree: ONE ranking of its real state (issues 28 and 47).

:func:`tree_status` reads the simulation's state (the meters, wilt, drowning, the season, the sun, the
growth hold) and the tree (its fruit, the light its leaves catch) and returns the first that holds:

    dead (``dead_fruit`` when fruit still hang on it) > drowning > thirsty (water at or below the growth
    threshold) > starving / wilting / recovering (a wilting tree) > needs_light (only by day) > winter (every
    winter day: the tree is bare and rests, even while late winter blends into spring; and a deciduous tree
    already bare in late autumn) > starting (growth
    not earned yet) > resting (only under a dark sky) > needs_light (leaves in the shade, by day) > growing.

Beside it, the lines the HUD shows only while they are true: :func:`water_low` (the can's hint: the water
meter down to the need line, the can not pouring; :func:`water_due` says when it will be, for the line at
a player's return), :func:`sun_low` (the sun's hint, likewise) and
:func:`need_line` (where a thirst is worth a word: the guardian's stop and the warning it says are about water
below it, never above it). The HUD and the kiosk (which plays the game's HUD) both take their status from
here.
"""

from __future__ import annotations

import copy
import math
from typing import TYPE_CHECKING

from arbor.engine.life.plant import seasons
from arbor.engine.life.rules.rules import Rules

if TYPE_CHECKING:  # (the world module imports this one: no import of it at run time)
    from arbor.engine.life.world.world import World

WINTER = 3  # the season index of winter (engine/life/plant/seasons.py)
BARE = 0.15  # leaves kept (seasons.leaf_keep) under which a late-autumn tree is drawn bare and rests


def need_line(rules: Rules) -> float:
    """The water meter's need line: the growth threshold plus the guardian's margin (a share, 0..1)."""
    return rules.growth.threshold + rules.health.guard_margin


def fruit_count(world: World) -> int:
    """Fruit hanging on the tree now (its L-string's fruit modules)."""
    return world.tree.lstring.count("O")


def water_low(world: World) -> bool:
    """Whether the can's hint applies: a living tree whose water meter is down to the need line and whose
    can is not pouring."""
    s = world.sim.state
    return s.alive and not s.watering and s.water_meter <= need_line(world.rules)


def water_due(world: World, days: float = 3.0, steps: int = 2000) -> float | None:
    """Game seconds until the water meter falls to the need line if nobody waters (the simulation run ahead
    on a copy, in ``steps`` steps: the sun, the season and the showers as they will come), 0 when it is
    there already, None when not within ``days`` days of the sun (or the tree is dead)."""
    if not world.sim.state.alive:
        return None
    line = need_line(world.rules)
    if world.sim.state.water_meter <= line:
        return 0.0
    sim = copy.deepcopy(world.sim)
    sim.state.watering = False
    horizon = days * 2 * math.pi / max(sim.state.sun_speed, 1e-9)
    step = horizon / steps
    for k in range(1, steps + 1):
        sim.step(step)
        if sim.state.water_meter <= line:
            return k * step
    return None


def sun_low(world: World) -> bool:
    """Whether the sun's hint applies: a living tree whose sun meter is down to the need line."""
    s = world.sim.state
    return s.alive and s.sun_meter <= need_line(world.rules)


def _wilting(world: World) -> str:
    """A wilting tree's word: starving when its leaves cannot feed it, wilting while its sun is neglected,
    recovering once both meters are cared for again."""
    sim, rules = world.sim, world.rules
    if sim.starving > rules.carbon.starve_time:
        return "starving"
    return "wilting" if sim.state.sun_meter < rules.health.neglect_level else "recovering"


def _bare(world: World) -> bool:
    """Whether autumn has taken (nearly) all of a deciduous tree's leaves: it rests as in winter."""
    return (not seasons.evergreen(world.tree.system.constants)
            and seasons.leaf_keep(world.sim.state.sun_turns, world.rules) < BARE)


def tree_status(world: World, dark: bool | None = None) -> str:
    """The status word of ``world`` (see module docstring); ``dark``: whether the sky drawn is a night's
    (None: the sun is below the horizon)."""
    sim, rules = world.sim, world.rules
    s = sim.state
    if not s.alive:
        return "dead_fruit" if fruit_count(world) else "dead"
    if sim.drowned() or (s.water_meter > rules.water.drown_level and s.drowning > 0):
        return "drowning"
    if s.water_meter <= rules.growth.threshold:
        return "thirsty"
    if s.wilt > rules.health.wilt_shown:
        return _wilting(world)
    day = sim.sunshine() > 0
    if s.sun_meter <= rules.growth.threshold and day:
        return "needs_light"
    if rules.seasons.enabled and (sim.season().index == WINTER or _bare(world)):
        return "winter"
    if sim.settle_left() > 0:
        return "starting"
    if (not day) if dark is None else dark:
        return "resting"
    if day and world.tree.mean_light < world.tree.geometry_constants["SHQ"]:
        return "needs_light"
    return "growing"
