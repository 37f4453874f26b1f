"""What the game tells a player besides the meters: first-run hints, gentle reminders, the journal.

Hints teach the three things a new player must find (water, sun, turning the view), one at a time,
each shown only while it applies (the water meter or the sun meter down to the need line, the tree alive)
and gone once the player has done it. Reminders are one calm line about what is worth doing now (rain, ripe fruit,
seeds to sow, another tree in need). New journal entries of any tree are announced as they happen;
the menu's journal page lists the cared-for tree's milestones by day.
"""

from __future__ import annotations

import math

from arbor.engine.life.world.status import fruit_count, sun_low, water_low
from arbor.engine.life.world.world import World
from arbor.game.screens.state import GameState
from arbor.game.strings import text

HINTS = ("water", "sun", "turn")
# statuses worth a reminder
ATTENTION = ("dead", "dead_fruit", "wilting", "starving", "drowning", "thirsty", "needs_light")
JOURNAL_SHOWN = 12  # latest milestones listed on the journal page


class Coach:
    """Hints, reminders and journal announcements for one game (see module docstring)."""

    def __init__(self, state: GameState, views: dict) -> None:
        self.state = state
        self.views = views  # the view's records of the trees (world id -> key, records, ...): ripe fruit shows
        self.hints: list[str] = []
        self.seen: dict[int, int] = {}  # world id -> journal entries already announced
        self.start_yaw = state.control.yaw

    def first_run(self) -> None:
        """Show the hints from the first (a new player, or the kiosk's next visitor)."""
        self.hints = list(HINTS)
        self.start_yaw = self.state.control.yaw

    def done(self, what: str) -> None:
        """The player did ``what`` (one of HINTS): its hint goes."""
        if what in self.hints:
            self.hints.remove(what)

    def hint(self) -> str:
        """The first hint not yet done that applies now ('' when none)."""
        turned = abs(self.state.control.yaw - self.start_yaw) % 360.0
        if "turn" in self.hints and min(turned, 360.0 - turned) > 20:
            self.done("turn")
        shown = next((what for what in self.hints if self.applies(what)), None)
        return text(f"hints.{shown}") if shown else ""

    def applies(self, what: str) -> bool:
        """Whether hint ``what`` fits the cared-for tree now: water while its meter is down to the need line
        and the can is not pouring, sun while the sun meter is down to the need line; none on a dead tree."""
        if not self.state.world.sim.state.alive:
            return False
        if what == "water":  # (only when the water is low: engine/life/world/status.py)
            return water_low(self.state.world)
        if what == "sun":
            return sun_low(self.state.world)
        return True

    def watch(self) -> None:
        """Announce milestones written since the last look (every tree of the garden)."""
        for world in self.state.garden.worlds:
            entries = world.journal.entries
            first = self.seen.setdefault(id(world), len(entries))
            fresh = [e for e in entries[first:] if e[1] != "planted"]
            self.seen[id(world)] = len(entries)
            if fresh:
                kind, value = fresh[-1][1:]
                size = world.journal.sizes.get(value) if kind == "season" else None
                self.state.say(text("journal.announce", what=describe(kind, value, size)), 6)

    def reminder(self) -> str:
        """One line about what is worth doing now, or ''."""
        state = self.state
        world = state.world
        if world.sim.raining() and world.sim.state.alive:
            return text("reminders.rain")
        view = self.views.get(id(world))
        ripe = view is not None and len(view[1].fruits.data) and (view[1].fruits.data[:, 10] >= 1.0).any()
        if ripe and world.sim.state.alive:  # (no fruit prompt on a dead tree)
            return text("reminders.fruit")
        garden = state.garden
        if garden.seeds and not garden.full:
            return text("reminders.sow", count=len(garden.seeds))
        for number, other in enumerate(garden.worlds, 1):
            status = other.status()
            if other is not world and status in ATTENTION:
                said = text(f"status.{status}", fruit=fruit_count(other))
                return text("reminders.other", number=number, status=said.split(":")[0])
        return ""

    def journal_lines(self) -> list[str]:
        """The cared-for tree's latest milestones, oldest first, by day of its life."""
        world = self.state.world
        entries = world.journal.entries[-JOURNAL_SHOWN:]
        if not entries:
            return [text("journal.empty")]
        return [text("journal.line", day=day_of(world, t),
                     what=describe(kind, value, world.journal.sizes.get(value) if kind == "season" else None))
                for t, kind, value in entries]


def describe(kind: str, value: float, size: tuple[float, float] | None = None) -> str:
    """A milestone in words (a birthday with the tree's ``size``, height and crown width in m, when kept)."""
    if kind == "season" and size is not None:
        return text("journal.birthday", value=value, height=size[0], width=size[1])
    return text(f"journal.{kind}", value=value)


def day_of(world: World, time: float) -> int:
    """The day of the tree's life (1 = the day it was planted) at game time ``time``."""
    day = 2 * math.pi / max(world.sim.state.sun_speed, 1e-9)
    return int(max(time, 0.0) // day) + 1
