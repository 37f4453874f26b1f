"""The family-tree screen: the garden's trees and their known ancestors, one row per generation, each
with a thumbnail (a side-view sketch of the tree as it stands; a sapling icon for ancestors no longer
in the garden), parents joined to children; a tap on a tree of the garden cares for it. It is a screen of
the game's stack (game/screens/stack.py): up from Garden -> Family until the next tap, which it takes."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np
import pygame

from arbor.engine.life.lineage.lineage import Lineage
from arbor.game.input.events import InputEvent
from arbor.game.render.icons import draw_icon
from arbor.game.render.ui import Menu
from arbor.game.screens.stack import TAP, Canvas, Screen, ScreenStack
from arbor.game.screens.state import GameState
from arbor.game.strings import text

if TYPE_CHECKING:
    from arbor.engine.life.world.world import World

THUMB = 112  # pixels: a thumbnail's side
MAX_SHOWN = 24  # members drawn at most (the garden's trees first, then their nearest ancestors)
INK, PANEL, LINE = (245, 245, 235), (18, 28, 22, 235), (150, 190, 120)


def sketch(world: World, size: int = THUMB) -> pygame.Surface:
    """A side view of ``world``'s tree: wood as lines as wide as the branches, leaves as green dots."""
    surface = pygame.Surface((size, size), pygame.SRCALPHA)
    turtle = world.tree.geometry(world.clocks(), lod=3).turtle
    segs = turtle.segments
    if not len(segs):
        return surface
    pts = np.concatenate([segs.start, segs.end])
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    scale = (size - 8) / max(float(hi[1] - lo[1]), float(hi[0] - lo[0]), 1e-6)
    mid = (lo[0] + hi[0]) / 2

    def px(p: np.ndarray) -> np.ndarray:
        return np.stack([size / 2 + (p[:, 0] - mid) * scale, size - 4 - (p[:, 1] - lo[1]) * scale], axis=1)

    a, b = px(segs.start), px(segs.end)
    widths = np.clip(segs.radius * 2 * scale, 1, 6).astype(int)
    for p, q, w in zip(a, b, widths, strict=True):
        pygame.draw.line(surface, (120, 92, 66), p, q, int(w))
    leaves = turtle.leaves.position
    if len(leaves):
        step = max(len(leaves) // 300, 1)
        for x, y in px(leaves[::step]):
            pygame.draw.circle(surface, (70, 150, 60), (int(x), int(y)), 2)
    return surface


class FamilyScreen(Screen):
    """Layout, drawing and taps of the family tree (see module docstring)."""

    def __init__(self, state: GameState, menu: Menu, size: tuple[int, int], screens: ScreenStack,
                 fonts: tuple[pygame.font.Font, pygame.font.Font]) -> None:
        self.state, self.menu, self.size, self.stack, self.fonts = state, menu, size, screens, fonts
        self.on_choose: Callable[[int], None] | None = None  # told the index of a tree of the garden tapped
        self.boxes: list[tuple[pygame.Rect, Lineage]] = []
        self._thumbs: dict[tuple, pygame.Surface] = {}

    def open(self) -> None:
        """Show the screen (the menu closes)."""
        super().open()
        self.menu.hide()

    def members(self) -> list[Lineage]:
        """Who is drawn: every tree of the garden, then their known ancestors, nearest first."""
        garden = self.state.garden
        shown = {w.lineage.id: w.lineage for w in garden.worlds}
        for world in garden.worlds:
            for ancestor in garden.family.ancestors(world.lineage):
                if len(shown) < MAX_SHOWN:
                    shown.setdefault(ancestor.id, ancestor)
        return list(shown.values())

    def layout(self) -> None:
        """Boxes by generation (oldest at the top), centred on each row."""
        width, height = self.size
        members = sorted(self.members(), key=lambda m: (m.generation, m.planted, m.id))
        generations = sorted({m.generation for m in members})
        row_h = min(THUMB + 60, (height - 90) // max(len(generations), 1))
        thumb = max(min(THUMB, row_h - 40, (width - 40) // max(len(members), 1) - 12), 32)
        self.boxes = []
        for r, gen in enumerate(generations):
            row = [m for m in members if m.generation == gen]
            gap = width / (len(row) + 1)
            for k, member in enumerate(row):
                box = pygame.Rect(0, 0, thumb, thumb)
                box.center = (int(gap * (k + 1)), 80 + r * row_h + thumb // 2)
                self.boxes.append((box, member))

    def handle(self, e: InputEvent) -> InputEvent | None:
        """A tap closes the screen (on a tree of the garden: that tree is cared for); the rest goes down."""
        if e.kind != TAP:
            return e
        index = self.tap(e.x, e.y)
        if index is not None and self.on_choose is not None:
            self.on_choose(index)
        return None

    def draw(self, canvas: Canvas) -> None:
        """The screen over the scene."""
        surface, (font, small) = canvas.surface, self.fonts
        self.layout()
        panel = pygame.Surface(surface.get_size(), pygame.SRCALPHA)
        panel.fill(PANEL)
        surface.blit(panel, (0, 0))
        surface.blit(font.render(text("family.title"), True, INK), (24, 20))
        hint = small.render(text("family.hint"), True, INK)
        surface.blit(hint, (surface.get_width() - hint.get_width() - 24, 28))
        where = {lin.id: box for box, lin in self.boxes}
        for box, lin in self.boxes:
            for parent in lin.parents:
                if parent in where:
                    pygame.draw.line(surface, LINE, where[parent].midbottom, box.midtop, 3)
        worlds = {w.lineage.id: (i, w) for i, w in enumerate(self.state.garden.worlds)}
        for box, lin in self.boxes:
            here = worlds.get(lin.id)
            cared = here is not None and here[1] is self.state.world
            pygame.draw.rect(surface, (40, 60, 38), box, border_radius=8)
            pygame.draw.rect(surface, (250, 230, 120) if cared else LINE, box, width=3 if cared else 1,
                             border_radius=8)
            if here is not None:
                surface.blit(pygame.transform.smoothscale(self._thumb(here[1]), box.size), box.topleft)
            else:
                draw_icon(surface, "sapling", box.inflate(-box.width // 3, -box.height // 3))
            label = text("family.tree", number=here[0] + 1) if here else text("family.gone")
            for k, line in enumerate((f"{lin.species} - {text('family.generation', n=lin.generation)}", label)):
                rendered = small.render(line, True, INK)
                if rendered.get_width() > box.width + 40:
                    rendered = pygame.transform.smoothscale_by(rendered, (box.width + 40) / rendered.get_width())
                surface.blit(rendered, rendered.get_rect(midtop=(box.centerx, box.bottom + 2 + 18 * k)))

    def _thumb(self, world: World) -> pygame.Surface:
        key = (id(world), len(world.tree.lstring), round(world.sim.state.length_time))
        if key not in self._thumbs:
            self._thumbs = {k: v for k, v in self._thumbs.items() if k[0] != id(world)}
            self._thumbs[key] = sketch(world)
        return self._thumbs[key]

    def tap(self, x: float, y: float) -> int | None:
        """Any tap closes the screen; a tap on a tree of the garden returns its index (to care for it)."""
        self.close()
        hit = next((lin for box, lin in self.boxes if box.collidepoint(x, y)), None)
        if hit is None:
            return None
        return next((i for i, w in enumerate(self.state.garden.worlds) if w.lineage.id == hit.id), None)
