"""Share a tree as a postcard: `arbor card SAVE --out tree.png` draws the tree with its name, species and
age and hides its save inside the PNG; `arbor import tree.png` plants it in the home garden beside the
others, after the same checks as any shared save (engine/life/keep/card.py)."""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np

from arbor.engine.base.files import atomic_write
from arbor.engine.base.units import METRE
from arbor.engine.life.keep.away import tree_height
from arbor.engine.life.keep.card import card_bytes, read_card
from arbor.engine.life.keep.save import SavedGarden, read_garden, write_garden
from arbor.engine.life.world.garden import MAX_GARDEN
from arbor.engine.life.world.world import World
from arbor.game.errors import UserError

CARD_SIZE = (960, 720)  # pixels: the picture of the tree and a strip of text under it
STRIP = 120  # pixels of the text strip


def card_picture(world: World, size: tuple[int, int] = CARD_SIZE, ctx=None) -> np.ndarray:
    """The postcard's picture, (H, W, 3) uint8: the tree from a three-quarter view, its name, species,
    age and height written on a strip under it."""
    from arbor.game.render.renderer import render_image

    w, h = size
    geometry = world.tree.geometry(world.clocks(), 0)
    tree = render_image(geometry.mesh, (w, h - STRIP), yaw=35.0, pitch=10.0, ctx=ctx)
    return np.concatenate([tree, _strip(world, w)], axis=0)


def _strip(world: World, width: int) -> np.ndarray:
    """The card's caption: who the tree is, how old and how tall (drawn with pygame's own font)."""
    import pygame

    from arbor.game.strings import duration

    pygame.font.init()
    surf = pygame.Surface((width, STRIP))
    surf.fill((246, 241, 226))
    pygame.draw.line(surf, (150, 130, 100), (24, 8), (width - 24, 8), 2)
    big, small = pygame.font.Font(None, 52), pygame.font.Font(None, 30)
    lineage = world.lineage
    name = f"{lineage.species.replace('_', ' ').title()} {lineage.id[:8]}"
    height = tree_height(world) / METRE
    alive = "" if world.sim.state.alive else " (no longer living)"
    facts = f"{duration(world.sim.state.time)} old, {height:.1f} m tall, generation {lineage.generation}{alive}"
    surf.blit(big.render(name, True, (52, 60, 40)), (24, 22))
    surf.blit(small.render(facts, True, (90, 82, 64)), (26, 72))
    surf.blit(small.render("Arbor", True, (150, 130, 100)), (width - 100, 72))
    return np.asarray(pygame.surfarray.array3d(surf)).transpose(1, 0, 2).copy()


def png_bytes(pixels: np.ndarray) -> bytes:
    """A picture as PNG bytes (pygame's writer)."""
    import pygame

    surf = pygame.image.frombuffer(np.ascontiguousarray(pixels).tobytes(), (pixels.shape[1], pixels.shape[0]), "RGB")
    out = io.BytesIO()
    pygame.image.save(surf, out, "card.png")
    return out.getvalue()


def make_card(save: Path, out: Path, tree: int | None = None) -> World:
    """Write the postcard of one tree of ``save`` (default: the cared-for one) to ``out``: a PNG that
    carries a save of that tree alone (with its family, so its ancestry travels with it)."""
    garden = read_garden(save)
    index = garden.current if tree is None else tree
    if not 0 <= index < len(garden.worlds):
        raise UserError(f"--tree {index}: {save} holds {len(garden.worlds)} tree(s), numbered from 0")
    world = garden.worlds[index]
    carried = SavedGarden([world], 0, garden.saved_at, family=garden.family, lsystem_name=garden.lsystem_name)
    atomic_write(out, card_bytes(png_bytes(card_picture(world)), carried))
    return world


def import_card(card: Path, saves: Path) -> tuple[World, int]:
    """Plant the tree a card carries in the garden of ``saves`` (its autosave), beside the others; returns
    the tree and the garden's size. The card is checked like any shared save; the garden is written
    atomically, and refused untouched when it is full or already holds this tree."""
    from arbor.engine.life.world.garden import Garden

    shared = read_card(card)
    world = shared.world
    path = saves / "autosave.arbor"
    if not path.exists():
        garden = Garden([world])
        kept = SavedGarden.of(garden, shared.lsystem_name)
    else:
        home = read_garden(path)
        if any(w.lineage.id == world.lineage.id for w in home.worlds):
            raise UserError(f"{card}: this tree ({world.lineage.id}) is already in your garden")
        if len(home.worlds) >= MAX_GARDEN:
            raise UserError(f"your garden is full ({MAX_GARDEN} trees): make room before importing {card}")
        garden = home.garden()
        for member in shared.family.members.values():  # the card's ancestry joins the garden's family
            garden.family.add(member)
        garden.adopt(world)
        kept = SavedGarden.of(garden, home.lsystem_name)
    saves.mkdir(parents=True, exist_ok=True)
    write_garden(kept, path)
    return world, len(garden.worlds)
