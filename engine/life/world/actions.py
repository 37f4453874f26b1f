"""The player's actions as values: what the menu, the keys, the kiosk and replays ask the game to do.

Every action is one :class:`Action`; its value is the action's name as text, which is how actions are
written wherever they are text (benchmark scripts, logs): :meth:`Action.named` turns such a name back
into the action, and refuses a name that is none. The first four change a :class:`World` (its
:meth:`~arbor.engine.life.world.world.World.apply`); the rest are the game's own (time speed, files,
the garden, the modeler), carried out by its one dispatcher (game/screens/care.py).
"""

from __future__ import annotations

from enum import Enum


class Action(Enum):
    """One thing the player can do; the value is its name as text (see module docstring)."""

    WATER = "water"  # value 1: the can is held, 0: released
    ORBIT_HEIGHT = "orbit_height"  # value: the sun's orbit height
    SUN_SPEED = "sun_speed"  # value: the sun's speed
    REPLANT = "replant"  # a fresh sapling in the tree's place
    SPEED = "speed"
    GO_ON = "go_on"  # after the fast-forward guardian's stop: tend the garden and fly on
    SAVE = "save"
    LOAD = "load"
    RESTORE = "restore"  # bring back an earlier autosave (each press one generation further back)
    PLANT = "plant"
    SPECIES = "species"  # the next species of the collection for Plant a tree (Garden)
    SOW = "sow"
    CROSS = "cross"
    FAMILY = "family"
    ROCK = "rock"
    ROOTS = "roots"
    NEXT = "next"
    MODELER = "modeler"  # the menu's Draw / Done: into the modeler (with the draw tool) and out of it
    DRAW = "draw"  # the modeler's draw tool: strokes draw branches (entering the modeler if needed)
    CROWN = "crown"
    SHAPE = "shape"
    PRUNE = "prune"
    SYMBOLS = "symbols"
    EDIT = "edit"
    UNDO = "undo"
    REDO = "redo"
    DEVICES = "devices"
    VOLUME = "volume"  # value: the sound's volume 0..1 (Settings)
    MUTE = "mute"  # sound off / back on (Settings)
    AWAY = "away"  # the garden watered while the player is away, or not (Settings)
    GARDENER = "gardener"  # the gardener cares while time flies (10x, 100x), or not: the guardian stops (Settings)
    SHARE = "share"  # a postcard of the cared-for tree, its save inside, in the saves folder's cards/ (Settings)
    IMPORT = "import"  # plant the newest card's tree found in cards/ beside the others (Garden)

    @classmethod
    def named(cls, name: str) -> Action:
        """The action called ``name`` (as text files write it); a ValueError naming the known ones if none is."""
        try:
            return cls(name)
        except ValueError:
            known = ", ".join(a.value for a in cls)
            raise ValueError(f"unknown action {name!r} (known: {known})") from None

    @property
    def on_world(self) -> bool:
        """True for the actions a world applies itself (the rest are the game's)."""
        return self in WORLD_ACTIONS

    @property
    def on_sun(self) -> bool:
        """True for the sun's sliders: a garden's trees share one sun, so these apply to all of them."""
        return self in (Action.ORBIT_HEIGHT, Action.SUN_SPEED)


WORLD_ACTIONS = frozenset({Action.WATER, Action.ORBIT_HEIGHT, Action.SUN_SPEED, Action.REPLANT})
