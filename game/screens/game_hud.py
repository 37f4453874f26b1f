"""The game's 2D layer over the scene: meters, status, season, hints, reminders, garden markers, rain and
the cursor, then the screens of the game's stack over them (game/screens/stack.py: the modeler's outlines
and tool bar, the menu, the family tree, the kiosk's layers; the title stands in for all of it), then the
message. It is repainted (and uploaded) only when what it shows changes. In the modeler the hint line says
what a drag does with the tool in use, in place of the garden's hints and reminders (there a drag draws
and a tap opens the tools)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import pygame

from arbor.engine.base.units import METRE
from arbor.engine.life.rules.rules import Rules
from arbor.engine.life.world.status import fruit_count, need_line
from arbor.game.render.backdrop import sky_colors
from arbor.game.render.camera import OrbitCamera, project_points
from arbor.game.render.garden import GardenRenderer
from arbor.game.render.icons import draw_icon
from arbor.game.render.renderer import Overlay
from arbor.game.render.ui import HudInfo, draw_hud, draw_rain, draw_rain_cloud, draw_toast
from arbor.game.screens.coach import Coach
from arbor.game.screens.modeler import ModelingMode
from arbor.game.screens.stack import Canvas, ScreenStack
from arbor.game.screens.state import GameState
from arbor.game.strings import duration, text

NEEDS_ICON = {"thirsty": "can", "wilting": "sun", "starving": "sun", "needs_light": "sun", "drowning": "can",
              "dead": "cross", "dead_fruit": "cross"}
BADGE = 30  # pixels: a garden marker's size


@dataclass
class HudParts:
    """What the HUD draws with, beside the game's state and rules: the game's parts it shows and the
    services it paints through."""

    screens: ScreenStack
    overlay: Overlay
    renderer: GardenRenderer
    views: dict
    fonts: tuple[pygame.font.Font, pygame.font.Font]
    modeling: ModelingMode
    coach: Coach
    scene_sun: Callable[[], np.ndarray]


class GameHud:
    """Paints the overlay surface (see module docstring)."""

    def __init__(self, state: GameState, rules: Rules, size: tuple[int, int], parts: HudParts) -> None:
        self.state, self.rules, self.size = state, rules, size
        self.scene_sun = parts.scene_sun  # the sun the scene is lit by (see GameView.scene_sun)
        self.screens, self.overlay, self.renderer = parts.screens, parts.overlay, parts.renderer
        self.views = parts.views  # the view's records of the trees (world id -> key, records, ...)
        self.font, self.small_font = parts.fonts
        self.modeling, self.coach = parts.modeling, parts.coach
        self.surface = pygame.Surface(size, pygame.SRCALPHA)
        self._key: tuple | None = None
        self.marker_boxes: list[pygame.Rect] = []  # the garden markers last painted (none overlaps another)

    def draw(self, camera: OrbitCamera) -> None:
        """Repaint the overlay if anything on it changed, and composite it over the frame."""
        self.coach.watch()
        self.modeling.follow()  # (a tree changed outside the modeler shows none of the old tree's overlays)
        key = self._overlay_key(camera)
        changed = key != self._key
        if changed:
            self.paint(camera)
            self._key = key
        self.overlay.draw_surface(self.surface, changed)

    def _overlay_key(self, camera: OrbitCamera) -> tuple:
        """Everything the HUD layer shows: repainted only when this changes (a message timing out
        changes it too), and 4 times a second while rain or the watering cloud animate."""
        state = self.state
        info = self.hud_info()
        modeling = self.modeling
        moving = modeling.active or state.cursor3d is not None or len(state.garden.worlds) > 1
        view = (round(camera.yaw, 2), round(camera.pitch, 2), round(camera.distance, 3), len(modeling.points),
                id(modeling.preview)) if moving else ()
        return (round(info.sun * 200), round(info.water * 200), info.status, int(info.age_seconds // 60),
                info.speed, info.message, info.watering, info.season, info.raining, info.hint, info.reminder,
                view, state.cursor3d, tuple(w.status() for w in state.garden.worlds), state.garden.current,
                int(state.clock() * 4) if info.raining or info.watering else 0,  # (rain and cloud animate)
                self.screens.key())

    def hud_info(self) -> HudInfo:
        """What the HUD shows now."""
        state, rules = self.state, self.rules
        world = state.world
        s, tree = world.sim.state, world.tree
        message = state.shown_message()
        if not message and tree.budget_hit:
            message = text("messages.budget")
        fast, left = self.first_day()
        pace = max(state.loop.speed, 1.0) * fast  # game s per real s (as at 1x while paused)
        status = text(f"status.{world.status(self.dark_sky())}", hold=duration(world.sim.settle_left() / pace),
                      fruit=fruit_count(world))
        note = text("hud.first_day", fast=fast, left=duration(left / pace)) if left > 0 else ""
        season = ""
        if rules.seasons.enabled:
            day = int(s.sun_turns) + 1
            season = text("hud.season", season=text(f"seasons.{world.sim.season().name}"), day=day)
        modeling = self.modeling.active
        hint = self.modeling.hint() if modeling else self.coach.hint()
        if modeling:  # (the garden is paused: its status lines would only lie across the tree being drawn)
            status = season = ""
        return HudInfo(s.sun_meter, s.water_meter, status, s.time, state.loop.speed, message, s.watering, season,
                       world.sim.raining(), hint, "" if modeling else self.coach.reminder(), tree.height / METRE,
                       note, need_line(rules))

    def first_day(self) -> tuple[float, float]:
        """(how many times as fast a new garden's first day runs, game seconds left of it): (1, 0) when
        the garden is past it or the pace has none (the HUD tells the first day's pace even while the can
        pours and time runs at the loop's speed)."""
        left = self.state.first_day_left()
        return (self.rules.first_day_speed, left) if left > 0 else (1.0, 0.0)

    def dark_sky(self) -> bool:
        """True when the sky drawn now is a night's (at fast speeds the scene leans toward noon, so a
        night of the sim may be drawn as day: the status follows what the player sees)."""
        return sky_colors(self.scene_sun())[2] < 0.5

    def overlay_pixels(self, camera: OrbitCamera) -> bytes:
        """The HUD layer as RGBA rows, bottom row first."""
        self.paint(camera)
        return pygame.image.tobytes(self.surface, "RGBA", True)

    def paint(self, camera: OrbitCamera) -> None:
        """Draw the whole overlay into the surface: the HUD, the screens of the stack over it, the message
        (a screen that covers the HUD, the title, is drawn alone)."""
        self.surface.fill((0, 0, 0, 0))
        canvas = Canvas(self.surface, camera, lambda points: self.project_many(camera, points))
        if self.screens.covered():
            self.screens.draw(canvas)
            return
        info = self.hud_info()
        if info.raining:
            draw_rain(self.surface, self.state.clock())
        if info.watering:
            self._draw_cloud(camera)
        self._draw_markers(camera)
        draw_hud(self.surface, self.font, info)
        if self.state.cursor3d is not None:
            self._draw_cursor3d(camera)
        self.screens.draw(canvas)
        draw_toast(self.surface, self.font, info.message)

    def project(self, camera: OrbitCamera, point) -> tuple[float, float] | None:
        """The window pixel of one 3D point, or None when it is behind the camera."""
        x, y = project_points(camera, self.size, np.asarray(point, float)[None])[0]
        return (float(x), float(y)) if np.isfinite(x) and np.isfinite(y) else None

    def project_many(self, camera: OrbitCamera, points) -> list[tuple[float, float]]:
        """Window pixels of many 3D points at once, leaving out those behind the camera."""
        pixels = project_points(camera, self.size, np.asarray(points, float).reshape(-1, 3))
        return [(float(x), float(y)) for x, y in pixels[np.isfinite(pixels).all(axis=1)]]

    def _draw_markers(self, camera: OrbitCamera) -> None:
        """Over every tree of a garden: its number, and an icon when it needs something (water, sun);
        a ring at the foot of the tree being cared for."""
        state = self.state
        self.marker_boxes = []
        if len(state.garden.worlds) < 2 or self.modeling.active:
            return
        here = np.array(state.world.position)
        shown = []
        for number, world in enumerate(state.garden.worlds, 1):
            entry = self.views.get(id(world))
            top = max(float(entry[1].hi[1]), 1.0) if entry else 2.0
            dx, dz = np.array(world.position) - here
            at = self.project(camera, (dx, top * 1.08, dz))
            if at is not None and 0 <= at[0] < self.size[0] and 0 <= at[1] < self.size[1]:
                shown.append((number, world, (int(at[0]), int(max(at[1], BADGE + 4)))))
        self.marker_boxes = place_badges([foot for _, _, foot in shown], self.size)
        for (number, world, _), box in zip(shown, self.marker_boxes, strict=True):
            cared = world is state.world
            status = world.status()
            colour = (250, 250, 240, 230) if cared else (30, 40, 30, 190)
            pygame.draw.circle(self.surface, colour, box.center, BADGE // 2)
            icon = NEEDS_ICON.get(status)
            if icon:
                draw_icon(self.surface, icon, box.inflate(-6, -6))
            else:
                label = self.small_font.render(str(number), True, (30, 40, 30) if cared else (245, 245, 240))
                self.surface.blit(label, label.get_rect(center=box.center))
            if cared:
                foot = self.project(camera, (0.0, 0.0, 0.0))
                if foot is not None:
                    pygame.draw.ellipse(self.surface, (255, 255, 255, 160),
                                        pygame.Rect(0, 0, 70, 18).move(int(foot[0]) - 35, int(foot[1]) - 9), 2)

    def _draw_cloud(self, camera: OrbitCamera) -> None:
        at = self.project(camera, (0.0, max(float(self.renderer.hi[1]), 1.0) * 1.25, 0.0))
        if at is not None:
            draw_rain_cloud(self.surface, (at[0], max(at[1], 60.0)), self.size[1] * 0.12, self.state.clock())

    def _draw_cursor3d(self, camera: OrbitCamera) -> None:
        """The 3D tracker's cursor (scene units, relative to the tree's base) as a ring with a drop line."""
        cursor = self.state.cursor3d
        at = self.project(camera, cursor)
        ground = self.project(camera, (cursor[0], 0.0, cursor[2]))
        if at is None:
            return
        if ground is not None:
            pygame.draw.line(self.surface, (255, 255, 255, 120), at, ground, 1)
        pygame.draw.circle(self.surface, (255, 230, 120, 230), (int(at[0]), int(at[1])), 10, 3)


def place_badges(anchors: list[tuple[int, int]], size: tuple[int, int], badge: int = BADGE) -> list[pygame.Rect]:
    """A badge's square for each anchor (the midbottom it wants), none overlapping another: a badge that
    would cover one already placed moves up (then down) a badge and a gap at a time, kept on the screen."""
    placed: list[pygame.Rect] = []
    step = badge + 4
    for x, y in anchors:
        for k in range(2 * len(anchors) + 1):
            shift = -((k + 1) // 2) * step if k % 2 else (k // 2) * step
            box = pygame.Rect(0, 0, badge, badge)
            box.midbottom = (x, y + shift)
            box.clamp_ip(pygame.Rect(0, 0, *size))
            if box.collidelist(placed) < 0:
                break
        placed.append(box)
    return placed
