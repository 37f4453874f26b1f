"""The picture of a shared tree (a postcard): the tree from a three-quarter view with a caption strip of
its name, age and height; the save it carries is added by engine/life/keep/card.py."""

from __future__ import annotations

import numpy as np

from arbor.engine.base.units import METRE
from arbor.engine.life.keep.away import tree_height
from arbor.engine.life.keep.card import card_bytes
from arbor.engine.life.keep.save import SavedGarden
from arbor.engine.life.lineage.lineage import Family
from arbor.engine.life.world.world import World

CARD_SIZE = (960, 720)  # pixels: the picture of the tree and a strip of text under it
STRIP = 120  # pixels of the caption strip


def card_picture(world: World, size: tuple[int, int] = CARD_SIZE, ctx=None) -> np.ndarray:
    """The postcard's picture, (H, W, 3) uint8 (``ctx``: the game's GL context, else a headless one)."""
    from arbor.game.render.renderer import render_image  # (numba and the GL renderer: loaded when a card is made)

    w, h = size
    geometry = world.tree.geometry(world.clocks(), 0)
    tree = render_image(geometry.mesh, (w, h - STRIP), yaw=35.0, pitch=10.0, ctx=ctx)
    return np.concatenate([tree, _strip(world, w)], axis=0)


def card_file(world: World, family: Family, lsystem_name: str, ctx=None) -> bytes:
    """The bytes of a postcard PNG of ``world`` carrying a save of that tree alone, with its family (so its
    ancestry travels with it)."""
    from arbor.game.render.renderer import png_bytes

    carried = SavedGarden([world], 0, None, family=family, lsystem_name=lsystem_name)
    return card_bytes(png_bytes(card_picture(world, ctx=ctx)), carried)


def _strip(world: World, width: int) -> np.ndarray:
    """The caption: who the tree is, how old and how tall (pygame's own font)."""
    import pygame

    from arbor.game.strings import duration

    pygame.font.init()
    surf = pygame.Surface((width, STRIP))
    surf.fill((246, 241, 226))
    pygame.draw.line(surf, (150, 130, 100), (24, 8), (width - 24, 8), 2)
    big, small = pygame.font.Font(None, 52), pygame.font.Font(None, 30)
    lineage = world.lineage
    name = f"{lineage.species.replace('_', ' ').title()} {lineage.id[:8]}"
    alive = "" if world.sim.state.alive else " (no longer living)"
    facts = (f"{duration(world.sim.state.time)} old, {tree_height(world) / METRE:.1f} m tall, "
             f"generation {lineage.generation}{alive}")
    surf.blit(big.render(name, True, (52, 60, 40)), (24, 22))
    surf.blit(small.render(facts, True, (90, 82, 64)), (26, 72))
    surf.blit(small.render("Arbor", True, (150, 130, 100)), (width - 100, 72))
    return np.asarray(pygame.surfarray.array3d(surf)).transpose(1, 0, 2).copy()
