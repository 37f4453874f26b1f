"""A world's log: a checkpoint of the world and everything that happened to it since, so its life replays.

The log holds the commands applied (engine/life/world/commands.py) and the runs of steps between them
(:class:`Run`: a time step and how many steps of it; consecutive runs of one step length are one entry).
It is bounded: when it holds :data:`MAX_ENTRIES` entries, the world as it is then becomes the new
checkpoint and the entries start again, so a game left running all day keeps a log of a few hundred
entries. :func:`replay` runs a copy of the checkpoint through the entries and gives the same world:
the same tree, meters and modeler edits (a tree alone; in a garden the neighbours' shade is not in one
tree's log).
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from arbor.engine.life.world.world import World

MAX_ENTRIES = 512  # entries kept before the checkpoint moves to the world as it is


@dataclass
class Run:
    """``count`` steps of ``dt`` seconds each."""

    dt: float
    count: int = 1


@dataclass
class Log:
    """A checkpoint (a copy of the world, None until one is taken) and the entries since it."""

    origin: World | None = None
    entries: list[Any] = field(default_factory=list)

    def ran(self, dt: float) -> None:
        """One step of ``dt`` was taken."""
        last = self.entries[-1] if self.entries else None
        if isinstance(last, Run) and last.dt == dt:
            last.count += 1
        else:
            self.entries.append(Run(dt))

    def applied(self, world: World, command: Any) -> None:
        """``command`` is about to be applied to ``world`` (a full log first moves its checkpoint there)."""
        if len(self.entries) >= MAX_ENTRIES:
            self.origin, self.entries = snapshot(world), []
        self.entries.append(command)

    @property
    def commands(self) -> list[Any]:
        """The commands since the checkpoint, in order (the runs between them left out)."""
        return [entry for entry in self.entries if not isinstance(entry, Run)]


def snapshot(world: World) -> World:
    """An independent copy of ``world`` without its log (its species, rules and edit sets shared: they
    never change)."""
    log, world.log = world.log, Log()
    try:
        keep = {id(world.system): world.system, id(world.rules): world.rules,
                id(world.tree.system): world.tree.system, id(world.roots.system): world.roots.system}
        return copy.deepcopy(world, keep)
    finally:
        world.log = log


def replay(log: Log) -> World:
    """The world ``log`` describes: its checkpoint copied and run through its entries."""
    if log.origin is None:
        raise ValueError("this log has no checkpoint to replay from")
    world = snapshot(log.origin)
    world.log = Log(origin=log.origin)
    for entry in log.entries:
        if isinstance(entry, Run):
            for _ in range(entry.count):
                world.step(entry.dt)
        else:
            world.apply(entry)
    return world
