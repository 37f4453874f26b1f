"""The symbols tool of the modeler (Onishi et al. 2003 sections 4.2, 5.2 and Fig. 7): a region of interest, the
L-string symbols inside it, and region-limited edits.

A short drag places a sphere that follows the pointer. A tall drag is a contour: the left and right
outlines of a crown region, and two of them are fitted with eq. 3's supertoroid (leaning with the
outlines), its width across the view they were drawn in. A drag that starts on the region's centre
handle or well inside it (within MOVE_INSIDE of the way to its rim, as seen) moves it; one that starts
on its rim resizes it; anywhere else a drag starts a new region. A tap inside the region applies the edit
chosen with the menu's option button, to the modules inside only (one undoable step); a prune that would
cut drawn work, or a quarter of the tree, says so first and is done by a second tap inside the region.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import pygame

from arbor.engine.life.world.commands import RegionEdit
from arbor.engine.lsystem.lstring import LString
from arbor.engine.modeling.edits import prune_region
from arbor.engine.modeling.modeler import DRAWN, F_PARAMS
from arbor.engine.modeling.regions import Sphere, Supertoroid, fit_supertoroid, moved_region, scaled_region
from arbor.game.render.camera import OrbitCamera, project_ball, project_points
from arbor.game.render.ui import draw_polyline
from arbor.game.strings import text
from arbor.game.tools.symbols import draw_symbols
from arbor.game.tools.told import counted

if TYPE_CHECKING:
    from scipy.spatial import ConvexHull

CONTOUR_PIXELS = 80.0  # a drag at least this tall, and twice as tall as wide, is a contour
GROUPS = {"grow": "grown", "prune": "pruned_region"}  # edits with their own message
ASK_SECONDS = 5.0  # a prune asked about is done by a second tap inside the region within this time
ASK_SHARE = 0.25  # a prune cutting more than this share of the tree's modules is asked about
HANDLE_PIXELS = 12.0  # radius of the region's centre handle (a touch-sized disc): a drag from it moves the region
MOVE_INSIDE = 0.6  # a drag starting within this share of the way from the centre to the rim moves the region
RIM_PIXELS = 16.0  # a drag starting up to this far outside the rim (as seen) still resizes the region


class RegionTool:
    """Region, contours and edits of the symbols tool for one modeling mode."""

    def __init__(self, mode) -> None:
        self.mode = mode
        self.region: Sphere | Supertoroid | None = None
        self.kept: Sphere | Supertoroid | None = None  # the region before the drag being made
        self.grab: tuple | None = None  # a drag that holds the region: ("move" | "size", region, start)
        self.contours: list[np.ndarray] = []  # a left outline waiting for its right one
        self.pixels: list[tuple[float, float]] = []  # the drag being made, in window pixels
        self.labels: list[tuple[str, float, float, bool]] = []  # last drawn: symbol, x, y, transformation
        self._positions: tuple[LString, np.ndarray] | None = None
        self.asked: tuple | None = None  # a prune asked about: (its region, the tree then, when)

    def clear(self) -> None:
        """Forget the region and any half-drawn contours."""
        self.region, self.contours, self.pixels = None, [], []

    def _is_contour(self) -> bool:
        if len(self.pixels) < 8:
            return False
        span = np.ptp(np.array(self.pixels), axis=0)
        return span[1] >= CONTOUR_PIXELS and span[1] >= 2 * span[0]

    def _radius(self) -> float:
        r = self.mode.renderer
        return 0.15 * max(float(np.max(r.hi - r.lo)), 1.0)

    def drag(self, point: np.ndarray, pixel: tuple[float, float] | None) -> None:
        """The pointer moved to ``point`` (at window ``pixel`` for a 2D pointer; None for a 3D
        tracker, whose drags always move the sphere). A drag that starts inside the region moves it, one
        that starts on its rim resizes it (sphere or supertoroid alike); elsewhere a short drag places a
        sphere that follows it (a tap does not), and a tall one is drawn as a contour."""
        if pixel is None:
            self.region = Sphere(tuple(point), self._radius())
            return
        if not self.pixels:
            self.kept, self.grab = self.region, self._grab(pixel, point)
        self.pixels.append(pixel)
        moved = abs(pixel[0] - self.pixels[0][0]) + abs(pixel[1] - self.pixels[0][1]) >= 12  # not a tap
        if self.grab is not None and moved:
            self.region = self._grabbed(point)
        elif moved and not self._is_contour():
            self.region = Sphere(tuple(point), self._radius())
        elif self.grab is None and self._is_contour():
            self.region = self.kept  # an outline, not a sphere drag: no sphere follows it

    def _grab(self, pixel: tuple[float, float], point: np.ndarray) -> tuple | None:
        """What a drag starting at ``pixel`` holds: ("move" | "size", the region then, the start point);
        None (a new region) unless it starts on the centre handle, inside the region or on its rim."""
        if self.region is None:
            return None
        away, rim = self._reach(pixel, self.mode.camera())
        if not (np.isfinite(away) and np.isfinite(rim)) or away > rim + RIM_PIXELS:
            return None
        move = away <= max(HANDLE_PIXELS, MOVE_INSIDE * rim)
        return ("move" if move else "size", self.region, np.asarray(point, float))

    def _reach(self, pixel: tuple[float, float], camera: OrbitCamera) -> tuple[float, float]:
        """How far ``pixel`` is from the region's projected centre, and how far the region's rim is
        from the centre in that direction (pixels; the rim of its projected outline's convex hull)."""
        size = self.mode.size
        if isinstance(self.region, Sphere):
            centre, radius = project_ball(camera, size, self.region.center, self.region.radius)
            return float(np.hypot(pixel[0] - centre[0], pixel[1] - centre[1])), radius
        centre = project_points(camera, size, np.asarray(self.region.center, float)[None])[0]
        offset = np.subtract(pixel, centre)
        away = float(np.hypot(*offset))
        hull = self._hull(camera)
        if hull is None or not np.isfinite(away):
            return float("nan"), 0.0
        direction = offset / away if away > 1e-9 else np.array([1.0, 0.0])
        normals, offsets = hull[:, :2], hull[:, 2]
        facing = normals @ direction
        gaps = -(offsets + normals @ centre)  # each edge's distance from the centre
        rim = np.min(np.where(facing > 1e-9, gaps / np.maximum(facing, 1e-9), np.inf))
        return away, float(max(rim, 0.0))

    def _hull(self, camera: OrbitCamera) -> np.ndarray | None:
        """The supertoroid's outline as seen: its convex hull's edges (normal x, normal y, offset; a
        pixel p is inside when normal . p + offset <= 0), None when it is out of view."""
        seen = self._seen(camera)
        return None if seen is None else seen.equations

    def _seen(self, camera: OrbitCamera) -> ConvexHull | None:
        """The convex hull of the supertoroid's projected surface points (window pixels)."""
        from scipy.spatial import ConvexHull, QhullError  # here, not when the game starts

        pixels = project_points(camera, self.mode.size, self._outline().reshape(-1, 3))
        pixels = pixels[np.isfinite(pixels).all(axis=1)]
        try:
            return ConvexHull(pixels) if len(pixels) >= 3 else None
        except QhullError:
            return None

    def _grabbed(self, point: np.ndarray) -> Sphere | Supertoroid:
        """The held region moved by (or resized toward) the pointer."""
        how, region, start = self.grab
        centre = np.asarray(region.center, float)
        if how == "move":
            return moved_region(region, np.asarray(point, float) - start)
        scale = max(np.linalg.norm(point - centre), 1e-3) / max(np.linalg.norm(start - centre), 1e-3)
        return scaled_region(region, min(max(scale, 0.2), 5.0))

    def cancel(self) -> None:
        """The drag being made was the start of a two-finger gesture: undo what it did to the region."""
        if self.pixels:
            self.region = self.kept
        self.pixels, self.grab = [], None

    def pinch(self, scale: float, x: float, y: float) -> bool:
        """A two-finger pinch centred on the region resizes it by ``scale`` (fingers apart: bigger);
        False when the pinch is elsewhere (the camera zooms instead)."""
        if self.region is None or not self.hit(x, y, self.mode.camera()):
            return False
        self.pixels, self.grab = [], None  # the first finger's drag is not a region drag any more
        self.region = scaled_region(self.region, min(max(scale, 0.5), 2.0))
        return True

    def finish(self, points: list[np.ndarray], camera: OrbitCamera) -> None:
        """The pointer went up: a contour is kept; with two of them the region becomes a supertoroid."""
        contour = self._is_contour() and self.grab is None
        self.pixels, self.grab = [], None
        if not contour:
            return
        self.region = self.kept  # the start of the contour had moved the sphere: put it back
        self.contours.append(np.array(points))
        if len(self.contours) < 2:
            self.mode.state.say(text("messages.contour_one"))
            return
        side = camera.view()[0, :3]  # the screen's right, in the world (horizontal)
        left, right = sorted(self.contours[-2:], key=lambda c: float(c.mean(axis=0) @ side))
        self.contours = []
        try:
            self.region = fit_supertoroid(left, right, across=side)  # width across the view drawn in
        except ValueError:
            self.mode.state.say(text("messages.contour_apart"))
            return
        self.mode.state.say(text("messages.contour_region"))

    def _outline(self) -> np.ndarray:
        """Points on the region's surface, (rings, points, 3): for drawing and for tap tests. A
        supertoroid's rings are at evenly spaced heights, and near its top and bottom, whatever n."""
        if isinstance(self.region, Sphere):
            u = np.linspace(-np.pi / 2, np.pi / 2, 9)[1:-1, None]
            v = np.linspace(0, 2 * np.pi, 33)[None, :]
            unit = np.stack([np.cos(u) * np.cos(v), np.sin(u) + 0 * v, np.cos(u) * np.sin(v)], axis=-1)
            return np.asarray(self.region.center) + self.region.radius * unit
        height = np.r_[-0.99, np.linspace(-0.8, 0.8, 5), 0.99]  # of a_y, from the centre
        u = np.arcsin(np.sign(height) * np.abs(height) ** (1.0 / self.region.n))[:, None]
        v = np.linspace(-np.pi, np.pi, 33)[None, :]
        return self.region.surface(u + 0 * v, v + 0 * u)

    def hit(self, x: float, y: float, camera: OrbitCamera) -> bool:
        """Whether pixel (x, y) lies on the region as seen (inside its projected outline: a circle for
        a sphere, the convex hull of a supertoroid's)."""
        if self.region is None:
            return False
        size = self.mode.size
        if isinstance(self.region, Sphere):
            c, radius = project_ball(camera, size, self.region.center, self.region.radius)
            return bool(np.hypot(x - c[0], y - c[1]) <= radius)
        hull = self._hull(camera)
        return hull is not None and bool(np.all(hull[:, :2] @ [x, y] + hull[:, 2] <= 1e-9))

    def edit_at(self, x: float, y: float, camera: OrbitCamera, edit: str, system) -> bool:
        """A tap: inside the region, apply ``edit`` (production set ``system``) to the modules inside it
        (undoable). False when the tap is outside (it then opens the menu as usual)."""
        mode = self.mode
        if mode.modeler is None or not self.hit(x, y, camera):
            return False
        if edit == "prune" and self._ask(edit):
            return True
        done = mode.state.world.apply(RegionEdit(edit, self.region, system))
        changed, held = done.changed, done.held
        key = "messages.new_axis" if changed < 0 else f"messages.{GROUPS.get(edit, 'edited')}"
        message = text(key, edit=text(f"edits.{edit}"), count=changed)
        mode.state.say(message + (" " + text("messages.budget") if held else ""))
        return True

    def _ask(self, edit: str) -> bool:
        """Whether a prune here must first be asked about (told, and done by a second tap inside the same
        region within ASK_SECONDS): it would cut drawn work (strokes, crowns) or more than ASK_SHARE of
        the tree's modules. A Prune here once cut a drawn branch whose base lay at the region's edge
        without a word."""
        mode = self.mode
        ls = mode.modeler.lstring
        now = mode.state.clock()
        asked, self.asked = self.asked, None
        if asked is not None and asked[0] is self.region and asked[1] is ls and now - asked[2] <= ASK_SECONDS:
            return False  # (the second tap: do it)
        new, removed = prune_region(ls, self.positions(ls), self.region)
        drawn = _drawn(ls) - _drawn(new)
        if drawn == 0 and removed <= ASK_SHARE * len(ls):
            return False
        self.asked = (self.region, ls, now)
        key = "messages.prune_ask" if drawn else "messages.prune_ask_much"
        mode.state.say(text(key, drawn=counted(drawn, "drawn piece"), count=counted(removed, "module"),
                            share=removed / max(len(ls), 1), seconds=ASK_SECONDS), ASK_SECONDS)
        return True

    def draw(self, surface: pygame.Surface, camera: OrbitCamera, font: pygame.font.Font, project,
             points: list[np.ndarray]) -> None:
        """The region's outline and centre handle, its modules' symbols (see game/tools/symbols.py),
        pending contours and the contour being drawn."""
        self.labels = []
        for contour in [*self.contours, *([np.array(points)] if self._is_contour() else [])]:
            draw_polyline(surface, project, contour, (255, 255, 255, 200), False, 3)
        if self.region is None:
            return
        if isinstance(self.region, Supertoroid):
            for ring in self._outline():
                draw_polyline(surface, project, ring, (255, 255, 255, 110), True, 1)
            seen = self._seen(camera)
            if seen is not None:  # the region's outline as seen now
                pygame.draw.lines(surface, (255, 255, 255, 210), True, seen.points[seen.vertices], 3)
        ls = self.mode.state.world.tree.lstring
        self.labels = draw_symbols(surface, font, camera, self.mode.size, ls, self.positions(ls), self.region)
        centre = project_points(camera, self.mode.size, np.asarray(self.region.center, float)[None])[0]
        if np.isfinite(centre).all():  # the handle a drag moves the region by
            pygame.draw.circle(surface, (255, 255, 255, 200), centre, HANDLE_PIXELS)
            pygame.draw.circle(surface, (40, 60, 40, 220), centre, HANDLE_PIXELS, 2)

    def positions(self, ls: LString) -> np.ndarray:
        """Turtle positions of every module of the tree as drawn now (cached per L-string)."""
        if self._positions is None or self._positions[0] is not ls:
            self._positions = (ls, self.mode.state.world.module_positions(ls))
        return self._positions[1]


def _drawn(ls: LString) -> int:
    """The drawn pieces (strokes' and crowns') of ``ls``."""
    return int(((ls.sym == DRAWN) & (ls.nparams == F_PARAMS)).sum())
