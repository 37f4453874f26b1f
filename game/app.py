"""The `arbor` window: shows a tree you can orbit (drag), zoom (wheel) and grow step by step (space).

This is the viewer the tamagotchi game (issue 4) builds on; it already uses the shared pipeline
(derive -> turtle -> mesh -> renderer).
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

import numpy as np

from engine.derive import Deriver
from engine.lsys import load_lsystem
from engine.tree import build_geometry
from game.camera import OrbitCamera
from game.render import ASSETS, TreeRenderer, sun_direction

DEFAULT_SOURCE = ASSETS / "lsystems" / "abop_2_8_tree.lsys"
MAX_STEPS = 9


class Viewer:
    """State of the viewer window: the growing tree, the camera and the renderer."""

    def __init__(self, ctx, size: tuple[int, int], source: Path = DEFAULT_SOURCE) -> None:
        self.size = size
        self.system = load_lsystem(source)
        self.deriver = Deriver(self.system, budget=2_000_000)
        self.lstring = self.system.axiom
        self.steps = 0
        self.renderer = TreeRenderer(ctx)
        self.camera = OrbitCamera()
        self.grow_to(max(self.system.iterations - 2, 1))

    def grow_to(self, steps: int) -> None:
        """Derive up to ``steps`` steps (clamped) and upload the new geometry."""
        steps = max(0, min(steps, MAX_STEPS))
        if steps < self.steps:
            self.lstring, self.steps = self.system.axiom, 0
        while self.steps < steps:
            self.lstring, _ = self.deriver.step(self.lstring)
            self.steps += 1
        geometry = build_geometry(self.lstring, self.system)
        self.renderer.set_tree(geometry.mesh)
        self.camera.frame_bounds(self.renderer.lo, self.renderer.hi, self.size[0] / self.size[1])

    def drag(self, dx: float, dy: float) -> None:
        """Orbit: horizontal drag turns the tree, vertical drag tilts (kept above the ground)."""
        self.camera.yaw -= dx * 0.4
        self.camera.pitch = float(np.clip(self.camera.pitch + dy * 0.3, -5.0, 80.0))

    def zoom(self, clicks: float) -> None:
        """Wheel zoom, proportional to the distance so it feels the same near and far."""
        self.camera.distance *= 0.9**clicks

    def draw(self, fbo) -> None:
        """Render one frame into ``fbo``."""
        self.renderer.render(fbo, self.camera, sun_direction(self.camera.yaw + 55.0, 48.0), self.size)


def run_app(args: argparse.Namespace | None = None) -> int:
    """Open the window and run until closed (Esc or the window's close button)."""
    import moderngl
    import pygame

    pygame.init()
    size = (1280, 720)
    pygame.display.gl_set_attribute(pygame.GL_CONTEXT_MAJOR_VERSION, 3)
    pygame.display.gl_set_attribute(pygame.GL_CONTEXT_MINOR_VERSION, 3)
    pygame.display.gl_set_attribute(pygame.GL_CONTEXT_PROFILE_MASK, pygame.GL_CONTEXT_PROFILE_CORE)
    pygame.display.set_mode(size, pygame.OPENGL | pygame.DOUBLEBUF)
    pygame.display.set_caption("Arbor")
    ctx = moderngl.create_context()
    viewer = Viewer(ctx, size)
    clock = pygame.time.Clock()
    max_frames = int(os.environ.get("ARBOR_MAX_FRAMES", "0"))
    frames = 0
    running = True
    while running:
        for event in pygame.event.get():
            if event.type == pygame.QUIT or (event.type == pygame.KEYDOWN and event.key == pygame.K_ESCAPE):
                running = False
            elif event.type == pygame.MOUSEMOTION and event.buttons[0]:
                viewer.drag(*event.rel)
            elif event.type == pygame.MOUSEWHEEL:
                viewer.zoom(event.y)
            elif event.type == pygame.KEYDOWN and event.key == pygame.K_SPACE:
                viewer.grow_to(viewer.steps + 1)
            elif event.type == pygame.KEYDOWN and event.key == pygame.K_BACKSPACE:
                viewer.grow_to(viewer.steps - 1)
        viewer.draw(ctx.screen)
        if max_frames and frames + 1 >= max_frames and os.environ.get("ARBOR_SCREENSHOT"):
            ctx.finish()
            _save_screen(ctx, size, os.environ["ARBOR_SCREENSHOT"])
        pygame.display.flip()
        clock.tick(60)
        frames += 1
        running = running and not (max_frames and frames >= max_frames)
    pygame.quit()
    return 0


def _save_screen(ctx, size: tuple[int, int], path: str) -> None:
    """Save what the window shows (used by tests and bug reports)."""
    from game.render import save_png

    pixels = np.frombuffer(ctx.screen.read(components=3), np.uint8).reshape(size[1], size[0], 3)
    save_png(pixels[::-1], path)
