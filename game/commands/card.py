"""Share a tree as a postcard: `arbor card SAVE --out tree.png` draws the tree with its name, species and
age and hides its save inside the PNG; `arbor import tree.png` plants it in the home garden beside the
others, after the same checks as any shared save (engine/life/keep/card.py)."""

from __future__ import annotations

from pathlib import Path

from arbor.engine.base.files import atomic_write
from arbor.engine.life.keep.card import plant_card, read_card
from arbor.engine.life.keep.generations import rotate
from arbor.engine.life.keep.save import SavedGarden, read_garden, write_garden
from arbor.engine.life.world.garden import Garden
from arbor.engine.life.world.world import World
from arbor.game.errors import UserError
from arbor.game.render.postcard import card_file


def make_card(save: Path, out: Path, tree: int | None = None) -> World:
    """Write the postcard of one tree of ``save`` (default: the cared-for one) to ``out``."""
    garden = read_garden(save)
    index = garden.current if tree is None else tree
    if not 0 <= index < len(garden.worlds):
        raise UserError(f"--tree {index}: {save} holds {len(garden.worlds)} tree(s), numbered from 0")
    world = garden.worlds[index]
    atomic_write(out, card_file(world, garden.family, garden.lsystem_name))
    return world


def import_card(card: Path, saves: Path) -> tuple[World, int]:
    """Plant the tree a card carries in the garden of ``saves`` (its autosave), beside the others; returns
    the tree and the garden's size. The card is checked like any shared save; the garden is written
    atomically, and left untouched when it is full or already holds this tree."""
    shared = read_card(card)
    path = saves / "autosave.arbor"
    if not path.exists():
        garden, name = Garden([shared.world], family=shared.family), shared.lsystem_name
    else:
        home = read_garden(path)
        garden, name = home.garden(), home.lsystem_name
        try:
            plant_card(garden, shared)
        except ValueError as why:
            raise UserError(f"{card}: {why}") from None
    saves.mkdir(parents=True, exist_ok=True)
    rotate(path)  # the garden as it was stays as autosave.1.arbor (Settings -> Restore), as the game keeps it
    write_garden(SavedGarden.of(garden, name), path)
    return shared.world, len(garden.worlds)
