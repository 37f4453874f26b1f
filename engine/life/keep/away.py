"""Time away: the garden lives on while the player is gone, quickly, and tells what happened.

On load the real time since the save (at most ``away.cap_days``; none when the clock went backwards or
the save's clock cannot be read) is lived with the same rules, in at most MAX_CATCH_UP_STEPS coarse steps
and with a few light readings a day (``away.fast_light``) instead of the dozens of play: fourteen days
take well under a second for a tree at its budget. The summary says what a player wants to know:
how much the tree grew, what it shed, whether it flowered or fruited, whether it went thirsty or died.

With the player's Away setting (``watered``: a neighbour looks after the garden) every tree whose water
meter comes down to the need line (``growth.threshold`` + ``health.guard_margin``, where fast-forward
stops) is watered back to comfortable (``health.comfort``) between two steps, whatever their length;
rain, sun, seasons and everything else stay as they are. Without it the outcome stays the honest one.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from arbor.engine.life.plant.journal import METRE
from arbor.engine.life.world.commands import LightEvery, TopUp
from arbor.engine.life.world.garden import Garden
from arbor.engine.life.world.world import MAX_CATCH_UP_STEPS, catch_up_steps

SAMPLES = 40  # times the garden is looked at while it catches up (for blossoms, fruit, thirst)


@dataclass
class AwaySummary:
    """What happened to the cared-for tree while the player was away."""

    seconds: float = 0.0
    days: float = 0.0  # days of the sun that passed
    grown: float = 0.0  # metres of height gained
    shed: int = 0
    blossoms: int = 0  # most blossoms seen at once
    fruit: int = 0  # most fruit seen at once
    thirsty: bool = False  # the water meter fell below the neglect level at some point
    wilted: bool = False
    died: bool = False
    waterings: int = 0  # times the Away setting's neighbour watered a tree
    seasons: list[str] = field(default_factory=list)  # seasons passed through, in order

    @property
    def anything(self) -> bool:
        """True when the absence was long enough to tell about."""
        return self.seconds >= 60.0


def away_seconds(now: float, saved_at: float, cap_days: float) -> float:
    """Real seconds to live: 0 for a clock that went backwards or cannot be read, at most the cap."""
    if not (math.isfinite(now) and math.isfinite(saved_at)) or saved_at > now:
        return 0.0
    return min(now - saved_at, cap_days * 86400.0)


def tree_height(world) -> float:
    """Height of the top of a world's wood (scene units): engine.geometry.tree.tree_height, the definition
    the HUD, the postcard and exports share."""
    from arbor.engine.geometry.tree import tree_height as top_of_wood

    return top_of_wood(world.tree.geometry(world.clocks(), lod=3))


def live_away(garden: Garden, seconds: float, watered: bool = False) -> AwaySummary:
    """Let ``garden`` live ``seconds`` of game time unattended, or watered while away (see module
    docstring)."""
    summary = AwaySummary(seconds=seconds)
    if seconds <= 0:
        return summary
    world = garden.world
    rules = world.rules
    day = 2 * math.pi / max(world.sim.state.sun_speed, 1e-9)
    for w in garden.worlds:  # fewer light readings while catching up (back to the rules' below)
        w.apply(LightEvery(max(w.rules.light.interval, day / rules.away.fast_light)))
    turns0, height0, shed0 = world.sim.state.sun_turns, tree_height(world), world.tree.shed_total
    steps, dt = catch_up_steps(seconds, 1.0, MAX_CATCH_UP_STEPS)
    marks = set(np.linspace(0, steps - 1, min(SAMPLES, steps)).astype(int).tolist()) if steps else set()
    try:
        for i in range(steps):
            garden.step(dt)
            if watered:
                summary.waterings += water_away(garden)
            if i in marks:
                _look(world, summary)
    finally:
        for w in garden.worlds:
            w.apply(LightEvery(None))
    summary.days = world.sim.state.sun_turns - turns0
    summary.grown = (tree_height(world) - height0) / METRE
    summary.shed = world.tree.shed_total - shed0
    summary.died = not world.sim.state.alive
    return summary


def water_away(garden: Garden) -> int:
    """The neighbour's round: every living tree at or under the need line is watered to comfortable.
    Returns the trees watered."""
    watered = 0
    for world in garden.worlds:
        s, rules = world.sim.state, world.rules
        if s.alive and s.water_meter <= rules.growth.threshold + rules.health.guard_margin:
            world.apply(TopUp(rules.health.comfort))
            watered += 1
    return watered


def _look(world, summary: AwaySummary) -> None:
    """Note what the tree shows right now."""
    s = world.sim.state
    ls = world.tree.lstring
    summary.blossoms = max(summary.blossoms, ls.count("K"))
    summary.fruit = max(summary.fruit, ls.count("O"))
    summary.thirsty |= s.water_meter < world.rules.health.neglect_level
    summary.wilted |= s.wilt > 0.5
    season = world.sim.season().name
    if not summary.seasons or summary.seasons[-1] != season:
        summary.seasons.append(season)
