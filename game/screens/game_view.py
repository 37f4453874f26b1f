"""What the game shows: the garden's geometry (rebuilt when the clocks or the L-strings change) and the HUD."""

from __future__ import annotations

from typing import TYPE_CHECKING

import moderngl
import numpy as np
import pygame

from engine.geometry.mesh import merge_trees
from engine.life.growth import grow_geometry
from game.render.camera import OrbitCamera, project_points
from game.render.falling import FALL_SECONDS, falling_mesh
from game.render.ui import HudInfo, draw_hud, draw_rain_cloud
from game.strings import text

if TYPE_CHECKING:
    from game.screens.game import Game

HEALTHY_LEAF, WILTED_LEAF = np.array([1.0, 1.0, 1.0]), np.array([2.6, 0.85, 0.45])  # green -> yellow-brown


class GameView:
    """Builds the scene's meshes and draws the frame (3D scene, then the HUD overlay)."""

    def __init__(self, game: Game) -> None:
        self.game = game
        self.surface = pygame.Surface(game.size, pygame.SRCALPHA)
        self.built: tuple | None = None
        self.triangles = 0
        self.fall_started: dict[int, float] = {}  # shed branch -> real time its fall began

    def rebuild(self) -> None:
        """Mesh the garden again if anything visible changed since the last frame."""
        game = self.game
        clocks = game.clocks()
        shown = game.modeling.lstring() if game.modeling.active else game.world.tree.lstring
        others = game.others
        falls = self._falls()
        key = (id(shown), round(clocks.length_time, 6), round(clocks.girth_time, 6), round(clocks.wilt, 4),
               tuple((id(o.tree.lstring), round(o.sim.state.length_time, 3)) for o in others),
               tuple((id(f), round(p, 3)) for f, p, _ in falls))
        if key == self.built:
            return
        mesh = grow_geometry(shown, clocks, game.world.tree.geometry_constants).mesh
        if others or falls:  # the garden, drawn around the cared-for tree (which stays at the centre)
            here = np.array(game.world.position)
            meshes, offsets = [mesh], [np.zeros(3)]
            for other in others:
                meshes.append(other.tree.geometry(other.clocks()).mesh)
                offsets.append(self._offset(other, here))
            for fallen, progress, world in falls:
                meshes.append(falling_mesh(fallen, progress))
                offsets.append(self._offset(world, here))
            mesh = merge_trees(meshes, offsets)
        renderer = game.renderer
        renderer.set_tree(mesh)
        self.triangles = mesh.n_triangles
        alive = game.world.sim.state.alive
        wilt = clocks.wilt if alive else 1.0
        renderer.leaf_tint = tuple(HEALTHY_LEAF + (WILTED_LEAF - HEALTHY_LEAF) * wilt)
        renderer.bark_tint = (1.45, 1.35, 1.25) if alive else (1.0, 1.0, 1.0)
        self.built = key

    @staticmethod
    def _offset(world, here: np.ndarray) -> np.ndarray:
        dx, dz = np.array(world.position) - here
        return np.array([dx, 0.0, dz])

    def _falls(self) -> list[tuple]:
        """Branches shed since they were first seen, with their fall progress (real time)."""
        now, out, seen = self.game.clock(), [], set()
        for world in self.game.garden.worlds:
            for fallen in world.tree.fallen:
                seen.add(id(fallen))
                started = self.fall_started.setdefault(id(fallen), now)
                if now - started < FALL_SECONDS:
                    out.append((fallen, (now - started) / FALL_SECONDS, world))
        self.fall_started = {k: v for k, v in self.fall_started.items() if k in seen}
        return out

    def draw(self, fbo: moderngl.Framebuffer) -> None:
        """Render the scene and the HUD/menu overlay into ``fbo``."""
        game = self.game
        self.rebuild()
        camera = game.camera()
        game.renderer.render(fbo, camera, game.world.sim.sun_direction(), game.size)
        game.overlay.draw(self.overlay_pixels(camera))

    def hud_info(self) -> HudInfo:
        """What the HUD shows now."""
        game = self.game
        s, tree = game.world.sim.state, game.world.tree
        message = game.message if game.clock() < game.message_until else ""
        if not message and tree.budget_hit:
            message = text("messages.budget")
        status = text(f"status.{game.world.status()}")
        return HudInfo(s.sun_meter, s.water_meter, status, s.time, game.loop.speed, message, s.watering)

    def overlay_pixels(self, camera: OrbitCamera) -> bytes:
        """The HUD, menu, rain cloud, cursor and tool outlines as RGBA rows, bottom row first."""
        game = self.game
        self.surface.fill((0, 0, 0, 0))
        info = self.hud_info()
        if info.watering:
            self._draw_cloud(camera)
        draw_hud(self.surface, game.font, info)
        if game.cursor3d is not None:
            self._draw_cursor3d(camera)
        project = lambda points: self.project_many(camera, points)  # noqa: E731
        game.modeling.draw_outline(self.surface, project)
        game.modeling.draw_symbols(self.surface, camera, game.small_font, project)
        game.menu.draw(self.surface, game.font)
        for hook in game.overlay_hooks:
            hook(self.surface)
        return pygame.image.tobytes(self.surface, "RGBA", True)

    def project(self, camera: OrbitCamera, point) -> tuple[float, float] | None:
        """The window pixel of one 3D point, or None when it is behind the camera."""
        x, y = project_points(camera, self.game.size, np.asarray(point, float)[None])[0]
        return (float(x), float(y)) if np.isfinite(x) and np.isfinite(y) else None

    def project_many(self, camera: OrbitCamera, points) -> list[tuple[float, float]]:
        """Window pixels of many 3D points at once, leaving out those behind the camera."""
        pixels = project_points(camera, self.game.size, np.asarray(points, float).reshape(-1, 3))
        return [(float(x), float(y)) for x, y in pixels[np.isfinite(pixels).all(axis=1)]]

    def _draw_cloud(self, camera: OrbitCamera) -> None:
        game = self.game
        at = self.project(camera, (0.0, max(float(game.renderer.hi[1]), 1.0) * 1.25, 0.0))
        if at is not None:
            draw_rain_cloud(self.surface, (at[0], max(at[1], 60.0)), game.size[1] * 0.12, game.world.sim.state.time)

    def _draw_cursor3d(self, camera: OrbitCamera) -> None:
        """The 3D tracker's cursor (scene units, relative to the tree's base) as a ring with a drop line."""
        cursor = self.game.cursor3d
        at = self.project(camera, cursor)
        ground = self.project(camera, (cursor[0], 0.0, cursor[2]))
        if at is None:
            return
        if ground is not None:
            pygame.draw.line(self.surface, (255, 255, 255, 120), at, ground, 1)
        pygame.draw.circle(self.surface, (255, 230, 120, 230), (int(at[0]), int(at[1])), 10, 3)
