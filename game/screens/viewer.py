"""`arbor view`: a plain viewer for any L-system (orbit, zoom, grow and shrink a step at a time)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pygame

from arbor.engine.forest.geomatree import load_grown
from arbor.engine.geometry.tree import build_geometry
from arbor.engine.lsystem.derive import Deriver
from arbor.game.errors import UserError
from arbor.game.input.events import DOWN, KEY_DOWN, MOVE, QUIT, WHEEL
from arbor.game.render.camera import OrbitCamera
from arbor.game.render.renderer import TreeRenderer, sun_direction

MAX_VIEW_STEPS = 9
VIEW_BUDGET = 300_000  # modules: the viewer stays interactive (a few hundred MB at most)


class Viewer:
    """A plain L-system viewer: orbit (drag), zoom (wheel), grow (space) and shrink (backspace)."""

    def __init__(self, ctx, size: tuple[int, int], source: Path) -> None:
        self.size = size
        self.system = load_grown(source)  # GeoMaTree's sources grow as the default species
        if self.system.externs:
            raise UserError(f"{source.name} needs values from the game at every step (#extern); "
                            "the viewer grows L-systems that run on their own")
        self.deriver = Deriver(self.system, budget=min(self.system.budget or VIEW_BUDGET, VIEW_BUDGET))
        self.lstring = self.system.axiom
        self.steps = 0
        self.renderer = TreeRenderer(ctx)
        self.camera = OrbitCamera()
        self._last: tuple[float, float] | None = None
        self.grow_to(self.system.iterations)

    def grow_to(self, steps: int) -> None:
        """Derive up to ``steps`` steps (clamped) and upload the new geometry."""
        steps = max(0, min(steps, MAX_VIEW_STEPS))
        if steps < self.steps:
            self.lstring, self.steps = self.system.axiom, 0
        while self.steps < steps:
            self.lstring, _ = self.deriver.step(self.lstring)
            self.steps += 1
        lod = 0 if len(self.lstring) < 60_000 else 1 if len(self.lstring) < 150_000 else 2  # big trees: coarser
        self.renderer.set_tree(build_geometry(self.lstring, self.system, lod=lod).mesh)
        self.camera.frame_bounds(self.renderer.lo, self.renderer.hi, self.size[0] / self.size[1])

    def update(self, seconds: float) -> None:
        """Nothing moves by itself in the viewer."""

    def draw(self, fbo) -> None:
        """Render the tree."""
        self.renderer.render(fbo, self.camera, sun_direction(self.camera.yaw + 55.0, 48.0), self.size)

    def handle_input(self, e) -> bool:
        """Orbit (drag), zoom (wheel), grow (space), shrink (backspace); returns False to quit."""
        if e.kind == QUIT or (e.kind == KEY_DOWN and e.key == pygame.K_ESCAPE):
            return False
        if e.kind == DOWN:
            self._last = (e.x, e.y)
        elif e.kind == MOVE and e.dims == 2 and self._last is not None:
            dx, dy = e.x - self._last[0], e.y - self._last[1]
            self._last = (e.x, e.y)
            self.camera.yaw -= dx * 0.4
            self.camera.pitch = float(np.clip(self.camera.pitch + dy * 0.3, -5.0, 80.0))
        elif e.kind == WHEEL:
            self.camera.distance *= 0.9**e.amount
        elif e.kind == KEY_DOWN and e.key == pygame.K_SPACE:
            self.grow_to(self.steps + 1)
        elif e.kind == KEY_DOWN and e.key == pygame.K_BACKSPACE:
            self.grow_to(self.steps - 1)
        return True
