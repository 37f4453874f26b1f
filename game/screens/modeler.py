"""The modeler mode of the game (Modeler I): draw trunks and branches with one finger, the mouse or
a 3D tracker; the drawing becomes L-string modules of the living tree.

2D pointers draw on the vertical plane through the tree's axis that faces the camera (orbit between
strokes to draw in depth); 3D trackers draw where they are. The tree appears as the stroke is drawn (a live preview
of the converted stroke); undo/redo take strokes back and forth. The simulation pauses while
modeling and resumes, growing branches from the drawn growth points, when the mode is left.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pygame

from arbor.engine.life.form.interpret import grow_geometry
from arbor.engine.lsystem.lstring import LString
from arbor.engine.modeling.edits import EDIT_SETS, load_edit_sets
from arbor.engine.modeling.modeler import Modeler, ModelerSettings
from arbor.engine.modeling.regions import prune
from arbor.engine.modeling.strokes import Stroke
from arbor.game.paths import ASSETS
from arbor.game.render.camera import OrbitCamera, project_points, unproject_to_plane
from arbor.game.render.garden import GardenRenderer
from arbor.game.render.ui import draw_joint
from arbor.game.screens.state import GameState
from arbor.game.strings import text
from arbor.game.tools.crown import CrownTool
from arbor.game.tools.region import RegionTool

PICK_PIXELS = 18.0  # how close a tap must be to a branch to cut it
WORK_SIZE = 150.0  # scene units: strokes and the modeler's view stay inside +-this (a runaway view cannot grow)
MAX_STROKE_POINTS = 5000  # points of one stroke
PREVIEW_SECONDS = 0.05  # live preview at most 20 times per second of drawing


class ModelingMode:
    """Stroke capture, conversion and undo/redo for one game."""

    def __init__(self, state: GameState, renderer: GardenRenderer, size: tuple[int, int],
                 camera: Callable[[], OrbitCamera]) -> None:
        self.state, self.renderer, self.size, self.camera = state, renderer, size, camera
        self.active = False
        self.modeler: Modeler | None = None
        self.points: list[np.ndarray] = []
        self.times: list[float] = []
        self.preview: LString | None = None
        self.joint: np.ndarray | None = None  # where the stroke being drawn joins the tree (shown, Onishi et al. 2003)
        self.plane: tuple[np.ndarray, np.ndarray] | None = None  # point, normal
        self.last_plane: tuple[np.ndarray, np.ndarray] | None = None
        self.stroke_camera: OrbitCamera | None = None  # the view a 2D stroke is drawn in
        self.bounds: tuple[np.ndarray, np.ndarray] | None = None  # framing kept while modeling
        self.resume_speed = 1.0
        self.crown = False  # strokes are crown outlines, not branches
        self.pruning = False  # taps on branches cut them
        self.symbols = False  # drags move the region whose L-string symbols are shown
        self.region_tool = RegionTool(self)
        self.shaping = False  # drags reshape the crown's lobes
        self.crown_tool = CrownTool(self)
        self.edit = EDIT_SETS[0]
        self.edit_sets = load_edit_sets(ASSETS / "edits")
        self._segments: tuple | None = None
        self._preview_at = float("-inf")  # stroke time of the last live preview

    def segments(self, ls: LString):
        """The tree's segments as drawn now (the modeler's view of the geometry), cached per L-string:
        a stroke's every pointer move asks for them."""
        world = self.state.world
        key = (id(ls), len(ls), world.clocks().length_time)
        if self._segments is None or self._segments[0] != key:
            self._segments = (key, grow_geometry(ls, world.clocks(), world.tree.geometry_constants).turtle.segments)
        return self._segments[1]

    def toggle(self) -> None:
        """Enter or leave the modeler (pausing the simulation while in it)."""
        if self.active:
            self.active = False
            self.cancel()
            self.state.loop.speed = self.resume_speed
            self.state.say(text("messages.modeler_off"))
            return
        self.active = True
        r = self.renderer
        center = np.clip((r.lo + r.hi) / 2, -WORK_SIZE, WORK_SIZE)
        half = np.clip((r.hi - r.lo) / 2 * 1.6, 1.6, WORK_SIZE)  # the view never grows past the work volume
        self.bounds = (np.array([center[0] - half[0], 0.0, center[2] - half[2]]), center + half)
        self.resume_speed = self.state.loop.speed or 1.0
        self.state.loop.speed = 0.0
        tree = self.state.world.tree  # drawn axes get the species' density of side shoots, lambda(s)
        self.modeler = Modeler(lstring=tree.lstring, settings=ModelerSettings.for_species(tree.geometry_constants),
                               segments_of=self.segments)
        self.crown_tool.clear()  # a new editing session: earlier crown steps cannot be undone into
        self.state.say(text("messages.modeler_on"))

    def tool(self, name: str) -> None:
        """Switch to tool ``name`` (crown, shaping, pruning, symbols) or back to branches if it is on
        (entering the modeler if needed)."""
        if not self.active:
            self.toggle()
        on = not getattr(self, name)
        self.crown = self.shaping = self.pruning = self.symbols = False
        setattr(self, name, on)
        self.region_tool.clear()
        self.cancel()
        if name == "shaping" and on:
            self.state.say(text("messages.shaping_on", op=text(f"shapes.{self.crown_tool.op}")))
        else:
            self.state.say(text(f"messages.{name}_on" if on else "messages.crown_off"))

    def prune_at(self, x: float, y: float, camera: OrbitCamera) -> bool:
        """With the prune tool, cut the branch under pixel (x, y) and what grows from it (undoable).
        False when no branch is there (the tap then opens the menu as usual)."""
        if not (self.pruning and self.modeler is not None):
            return False
        segs = self.segments(self.modeler.lstring)
        if len(segs) == 0:
            return False
        a = project_points(camera, self.size, segs.start)
        b = project_points(camera, self.size, segs.end)
        ab = b - a
        t = np.clip(np.einsum("ij,ij->i", [x, y] - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-9), 0, 1)
        dist = np.linalg.norm(a + t[:, None] * ab - [x, y], axis=1)
        k = int(np.nanargmin(np.where(np.isnan(dist), np.inf, dist)))
        if not dist[k] <= PICK_PIXELS:
            return False
        if segs.parent[k] < 0:
            self.state.say(text("messages.prune_base"))
            return True
        before = self.modeler.lstring
        self.modeler.commit(prune(before, int(segs.module[k])))
        self.state.world.tree.lstring = self.modeler.lstring
        self.state.say(text("messages.pruned", count=len(segs) - len(self.segments(self.modeler.lstring))))
        return True

    def cancel(self) -> None:
        """Drop the stroke being drawn."""
        self.points, self.times, self.preview, self.plane, self.joint = [], [], None, None, None

    def begin2d(self, x: float, y: float, t: float, camera: OrbitCamera) -> None:
        """A finger or the mouse went down: start a stroke on the camera-facing plane."""
        normal = camera.target - camera.eye
        normal[1] = 0.0  # a vertical plane: it contains the tree's axis and faces the camera
        normal /= max(np.linalg.norm(normal), 1e-12)
        through = np.array([0.0, camera.target[1], 0.0])
        self.plane = self.last_plane = (through, normal)
        self.stroke_camera = camera
        self.cancel_points()
        if self.shaping:
            self.crown_tool.begin_shape(x, y, camera)
            return
        self.add2d(x, y, t, camera)

    def cancel_points(self) -> None:
        """Forget the points of the stroke being drawn (the drawing plane stays) and any shape or
        region drag in progress."""
        self.points, self.times, self.preview, self.joint = [], [], None, None
        self._preview_at = float("-inf")
        self.crown_tool.drag = None
        self.region_tool.cancel()

    def pinch(self, scale: float, x: float, y: float) -> bool:
        """With the symbols tool, a pinch over the region resizes it instead of zooming the camera."""
        return self.active and self.symbols and self.region_tool.pinch(scale, x, y)

    def add2d(self, x: float, y: float, t: float, camera: OrbitCamera) -> None:
        """The pointer moved: extend the stroke with the point under it on the drawing plane."""
        if self.plane is None:
            return
        if self.shaping:
            self.crown_tool.drag_shape(x, y, self.stroke_camera or camera)
            return
        hit = unproject_to_plane(self.stroke_camera or camera, self.size, x, y, *self.plane)
        if hit is not None:
            self.add3d(hit, t, (x, y))

    def add3d(self, point, t: float, pixel: tuple[float, float] | None = None) -> None:
        """Extend the stroke with a 3D point (a tracker's cursor; ``pixel``: where a 2D pointer is) and
        refresh the preview. Points are kept inside the work volume; a stroke holds at most
        MAX_STROKE_POINTS points and the preview is redrawn at most every PREVIEW_SECONDS of stroke
        time, so no pointer move costs more than one bounded conversion."""
        if len(self.points) >= MAX_STROKE_POINTS:
            return
        point = np.clip(np.asarray(point, dtype=np.float64), [-WORK_SIZE, 0.0, -WORK_SIZE],
                        [WORK_SIZE, 2 * WORK_SIZE, WORK_SIZE])
        if not np.all(np.isfinite(point)):
            return
        self.points.append(point)
        self.times.append(t)
        if self.symbols:
            self.region_tool.drag(self.points[-1], pixel)
        elif self._preview_due(t):
            self._preview_at = t
            self.preview, result = self.modeler.convert(Stroke(np.array(self.points), np.array(self.times)))
            self.joint = result.snap_point

    def _preview_due(self, t: float) -> bool:
        """A branch stroke of 3+ points whose last preview is PREVIEW_SECONDS old (or from another stroke)."""
        drawing = len(self.points) >= 3 and self.modeler is not None and not (self.crown or self.pruning)
        return drawing and (t - self._preview_at >= PREVIEW_SECONDS or t < self._preview_at)

    def finish(self) -> None:
        """The pointer went up: commit the stroke to the tree (undoable)."""
        if self.crown and self.modeler is not None:
            self.crown_tool.stroke(np.array(self.points))
        elif self.shaping:
            self.crown_tool.end_shape()
        elif self.symbols and self.stroke_camera is not None:
            self.region_tool.finish(self.points, self.stroke_camera)
        elif self.pruning:
            pass  # the prune tool cuts with taps
        elif self.modeler is not None and len(self.points) >= 3:
            new, result = self.modeler.convert(Stroke(np.array(self.points), np.array(self.times)))
            budget = self.state.world.tree.deriver.budget
            if budget is not None and len(new) > max(budget, len(self.modeler.lstring)):
                self.state.say(text("messages.stroke_budget"))  # nothing is lost: the stroke is just not added
                self.cancel()
                return
            if result.pieces:
                self.modeler.commit(new)
            self.state.world.tree.lstring = self.modeler.lstring
            how = text("messages.stroke_merged" if result.merged else "messages.stroke_joined"
                       if result.snapped_to is not None else "messages.stroke_new")
            if result.bypassed:
                how += ", " + text("messages.stroke_bent", count=result.bypassed)
            self.state.say(text("messages.stroke", pieces=result.pieces, points=result.growth_points, how=how))
        self.cancel()

    def draw_outline(self, surface: pygame.Surface, project) -> None:
        """The crown's lobes and the crown stroke being drawn, over the scene (crown and shape tools),
        and the joint point where a branch stroke being drawn will join the tree."""
        if (self.crown or self.shaping) and self.modeler is not None:
            self.crown_tool.draw(surface, project, self.points if self.crown else [], self.shaping)
        elif self.points and self.joint is not None:
            draw_joint(surface, project, self.joint)

    def born_visible(self) -> float:
        """A birth time for leaves and blossoms added while the garden is paused: one growth time
        constant ago, so they show at once (63 % grown) and finish growing when time runs again."""
        return self.state.world.clocks().length_time - self.state.world.tree.geometry_constants["TAU"]

    def option_label(self) -> str:
        """The menu option button's label: the lobe operation with the shape tool, else the region edit."""
        if self.shaping:
            return text("menu.shape_op", op=text(f"shapes.{self.crown_tool.op}"))
        return text("menu.edit", name=text(f"edits.{self.edit}"))

    def next_option(self) -> str:
        """The menu's option button: the next lobe operation with the shape tool, else the next region
        edit. Returns the button's new label."""
        if self.shaping:
            self.crown_tool.next_op()
        else:
            self.edit = EDIT_SETS[(EDIT_SETS.index(self.edit) + 1) % len(EDIT_SETS)]
        return self.option_label()

    def edit_at(self, x: float, y: float, camera: OrbitCamera) -> bool:
        """With the symbols tool, a tap inside the region applies the chosen edit there (undoable).
        False when the tap is outside the region (it then opens the menu as usual)."""
        return self.symbols and self.region_tool.edit_at(x, y, camera, self.edit, self.edit_sets.get(self.edit))

    def draw_symbols(self, surface: pygame.Surface, camera: OrbitCamera, font: pygame.font.Font, project) -> None:
        """The symbols tool's region, contours and L-string overlay (see game/tools/region.py)."""
        if self.symbols:
            self.region_tool.draw(surface, camera, font, project, self.points)
        else:
            self.region_tool.labels = []

    def undo(self) -> None:
        """Take back the last stroke."""
        if self.modeler is not None and self.modeler.undo():
            self.state.world.tree.lstring = self.modeler.lstring

    def redo(self) -> None:
        """Put back the last undone stroke."""
        if self.modeler is not None and self.modeler.redo():
            self.state.world.tree.lstring = self.modeler.lstring

    def lstring(self) -> LString:
        """What to draw now: the live preview while a stroke is being drawn, else the tree."""
        return self.preview if self.preview is not None else self.state.world.tree.lstring

