"""What the game shows: the garden's geometry (rebuilt when the clocks or the L-strings change) and the HUD."""

from __future__ import annotations

import math
from concurrent.futures import ThreadPoolExecutor
from typing import TYPE_CHECKING

import moderngl
import numpy as np
import pygame

from engine.life.growth_view import GrowthView
from game.render.camera import OrbitCamera, project_points
from game.render.falling import FALL_SECONDS, falling_view
from game.render.garden import BARK, GardenRenderer, Placed
from game.render.instanced import LEAF_KEPT, SIDES, TreeBuffers
from game.render.ui import HudInfo, draw_hud, draw_rain_cloud
from game.strings import text

if TYPE_CHECKING:
    from game.screens.game import Game

HEALTHY_LEAF, WILTED_LEAF = np.array([1.0, 1.0, 1.0]), np.array([2.6, 0.85, 0.45])  # green -> yellow-brown
WILT_STEP = 0.02  # a change of wilt this large rebuilds the tree (drooping angles change its shape)
ASYNC_MODULES = 60_000  # trees with more modules are rebuilt on a worker thread
FALL_FRESH = 2.0  # physiological time: a branch shed earlier than this before it is first seen does not fall


def _triangles(buffers: TreeBuffers, lod: int) -> int:
    """Triangles one tree's buffers draw at level ``lod``."""
    parts = buffers.parts
    tubes = parts["tube"].count * 3 * SIDES[lod] if "tube" in parts else 0
    leaves = int(parts["leaf"].count * LEAF_KEPT[lod]) * 2 if "leaf" in parts else 0
    blossoms = parts["blossom"].count * 2 if "blossom" in parts else 0
    return tubes + leaves + blossoms


class GameView:
    """Keeps every tree's instance records current and draws the frame (3D scene, then the HUD)."""

    def __init__(self, game: Game) -> None:
        self.game = game
        self.surface = pygame.Surface(game.size, pygame.SRCALPHA)
        self.views: dict[int, tuple[tuple, GrowthView, TreeBuffers, int]] = {}  # world id -> key, view, GPU, ver
        self.triangles = 0
        self.fall_started: dict[int, float] = {}  # shed branch -> real time its fall began
        self.falls: list[TreeBuffers] = []
        self._hud_key: tuple | None = None
        self.pending: dict[int, tuple] = {}  # world id -> (key, future) of a rebuild on the worker
        self.worker = ThreadPoolExecutor(max_workers=1, thread_name_prefix="arbor-rebuild")

    def rebuild(self) -> None:
        """Bring every tree's records up to date: a full build when its L-string (or wilt) changed,
        else only its growing parts move (engine/life/growth_view.py)."""
        game = self.game
        renderer: GardenRenderer = game.renderer
        here = np.array([game.world.position[0], 0.0, game.world.position[1]])
        placed, seen = [], set()
        for world in game.garden.worlds:
            cared = world is game.world
            shown = game.modeling.lstring() if cared and game.modeling.active else world.tree.lstring
            clocks = game.clocks() if cared else world.clocks()
            alive = world.sim.state.alive
            key = (id(shown), len(shown), round(clocks.wilt / WILT_STEP), alive)
            entry = self._view(world, shown, clocks, key)
            _, view, buffers, version = entry
            renderer.trees.sync(buffers, view)
            offset = np.array([world.position[0], 0.0, world.position[1]]) - here
            placed.append(Placed(buffers, offset, version))
            seen.add(id(world))
        for gone in set(self.views) - seen:
            self.views.pop(gone)[2].release()
        placed += self._falling(here)
        current = self.views[id(game.world)][1]
        renderer.place(placed, current.lo, current.hi)
        self._tints()
        self._count_triangles()

    def _view(self, world, shown, clocks, key: tuple) -> tuple:
        """The records for ``world``'s tree: rebuilt when ``key`` changed, else moved to ``clocks``. A
        big tree is rebuilt on a worker thread while frames keep drawing the old records, still growing
        (new parts are born at zero size, so the few frames' delay is invisible)."""
        entry = self.views.get(id(world))
        pending = self.pending.get(id(world))
        if pending is not None and pending[1].done():
            self.pending.pop(id(world))
            entry = self._adopt(world, entry, pending[0], pending[1].result())
        const = world.tree.geometry_constants
        if entry is None or (entry[0] != key and len(shown) < ASYNC_MODULES):
            entry = self._adopt(world, entry, key, GrowthView(shown, clocks, const))
        elif entry[0] != key and id(world) not in self.pending:  # one rebuild at a time: never a backlog
            self.pending[id(world)] = (key, self.worker.submit(GrowthView, shown, clocks, const))
        entry[1].update(clocks)  # (a stale view keeps growing until its successor is ready)
        return entry

    def _adopt(self, world, entry, key: tuple, view: GrowthView) -> tuple:
        buffers = entry[2] if entry else TreeBuffers()
        entry = (key, view, buffers, (entry[3] + 1) if entry else 0)
        self.views[id(world)] = entry
        return entry

    def _count_triangles(self) -> None:
        placed = self.game.renderer.placed
        self.triangles = sum(_triangles(p.buffers, lod) for p, lod in zip(placed, self._lods(placed), strict=True))

    def _lods(self, placed: list[Placed]) -> list[int]:
        lods = self.game.renderer.last_lods
        return lods if len(lods) == len(placed) else [0] * len(placed)

    def _tints(self) -> None:
        game, renderer = self.game, self.game.renderer
        alive = game.world.sim.state.alive
        wilt = game.clocks().wilt if alive else 1.0
        renderer.leaf_tint = tuple(HEALTHY_LEAF + (WILTED_LEAF - HEALTHY_LEAF) * wilt)
        renderer.bark_tint = BARK if alive else (1.0, 1.0, 1.0)

    def _falling(self, here: np.ndarray) -> list[Placed]:
        """Branches shed since they were first seen, falling (for FALL_SECONDS of real time)."""
        for old in self.falls:
            old.release()
        self.falls = []
        now, out, seen = self.game.clock(), [], set()
        for world in self.game.garden.worlds:
            offset = np.array([world.position[0], 0.0, world.position[1]]) - here
            recent = world.tree.last_rewrite_T - FALL_FRESH  # a branch shed long ago (while away) just lies there
            for fallen in world.tree.fallen:
                seen.add(id(fallen))
                started = self.fall_started.setdefault(id(fallen), now if fallen.at >= recent else -FALL_SECONDS)
                if now - started < FALL_SECONDS:
                    buffers = TreeBuffers()
                    self.game.renderer.trees.sync(buffers, falling_view(fallen, (now - started) / FALL_SECONDS))
                    self.falls.append(buffers)
                    out.append(Placed(buffers, offset, -1))
        self.fall_started = {k: v for k, v in self.fall_started.items() if k in seen}
        return out

    def draw(self, fbo: moderngl.Framebuffer) -> None:
        """Render the scene and the HUD/menu overlay into ``fbo``."""
        game = self.game
        self.rebuild()
        camera = game.camera()
        game.renderer.time = game.clock()
        game.renderer.wind = self.wind()
        game.renderer.render(fbo, camera, game.world.sim.sun_direction(), game.size)
        self._count_triangles()  # (again: the levels of detail of this very frame)
        key = self._overlay_key(camera)
        changed = key != self._hud_key
        if changed:
            self.paint(camera)
            self._hud_key = key
        game.overlay.draw_surface(self.surface, changed)

    def wind(self) -> np.ndarray:
        """The wind vector for the shaders: the rules' direction x strength, scaled to the tree's size,
        with slow gusts (in real time: the air moves the same at every game speed)."""
        rules = self.game.rules.wind
        height = max(float(self.game.renderer.hi[1]), 1.0)
        t = self.game.clock()
        gust = 1.0 + rules.gusts * (0.6 * math.sin(t * 0.23) + 0.4 * math.sin(t * 0.61 + 1.3))
        a = math.radians(rules.direction)
        return np.array([math.cos(a), 0.0, math.sin(a)]) * rules.strength * 0.1 * height * max(gust, 0.0)

    def _overlay_key(self, camera: OrbitCamera) -> tuple:
        """Everything the HUD layer shows: it is repainted (and uploaded) only when this changes, and
        at least 4 times a second for what animates (rain cloud, cursor, messages timing out)."""
        game = self.game
        info = self.hud_info()
        menu = game.menu
        widgets = tuple((w.value, w.pressed, w.label) for w in menu.widgets) if menu.visible else ()
        modeling = game.modeling
        view = (round(camera.yaw, 2), round(camera.pitch, 2), round(camera.distance, 3), len(modeling.points),
                id(modeling.preview)) if modeling.active or game.cursor3d is not None else ()
        return (round(info.sun * 200), round(info.water * 200), info.status, int(info.age_seconds // 60),
                info.speed, info.message, info.watering, menu.visible, widgets, view, game.cursor3d,
                len(game.overlay_hooks), int(game.clock() * 4))

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
        self.paint(camera)
        return pygame.image.tobytes(self.surface, "RGBA", True)

    def paint(self, camera: OrbitCamera) -> None:
        """Draw the HUD, menu, rain cloud, cursor and tool outlines into the overlay surface."""
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
