"""The modeler mode of the game (Modeler I): draw trunks and branches with one finger, the mouse or
a 3D tracker; the drawing becomes L-string modules of the living tree.

2D pointers draw on the vertical plane through the tree's axis that faces the camera (orbit between
strokes to draw in depth); 3D trackers draw where they are. The tree appears as the stroke is drawn (a live preview
of the converted stroke); undo/redo take strokes back and forth. The simulation pauses while
modeling and resumes, growing branches from the drawn growth points, when the mode is left.

One tool is in use at a time (Draw, Crown, Shape, Prune, Symbols), shown lit on the modeler's tool bar
(game/render/ui.py ToolBar) and told by the hint line (what a drag does with it). Entering the modeler
starts with Draw; leaving it (Done) or a new sapling clears every overlay the tools drew (lobe rings,
regions, the joint marker). The view frames the tree as the modeler opens and never re-frames by itself
while a tool is in use (the next outline lands where it was aimed); F frames the tree and its lobes.
Toasts say what changed (the pieces, leaves and lobes an undo took away or a redo put back).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pygame

from arbor.engine.life.world.commands import BeginEditing, Stroke
from arbor.engine.lsystem.lstring import LString
from arbor.engine.modeling.edits import EDIT_SETS, load_edit_sets
from arbor.engine.modeling.modeler import Modeler
from arbor.engine.modeling.strokes import Stroke as StrokePoints
from arbor.game.paths import ASSETS
from arbor.game.render.camera import OrbitCamera, unproject_to_plane
from arbor.game.render.garden import GardenRenderer
from arbor.game.render.ui import ToolBar, draw_joint
from arbor.game.screens.stack import Screen
from arbor.game.screens.state import GameState
from arbor.game.strings import text
from arbor.game.tools.choice import ToolChoice
from arbor.game.tools.crown import CrownTool
from arbor.game.tools.crown_panel import CrownPanel
from arbor.game.tools.prune import PruneTool
from arbor.game.tools.region import RegionTool
from arbor.game.tools.told import HistoryTold, counted

WORK_SIZE = 150.0  # scene units: strokes and the modeler's view stay inside +-this (a runaway view cannot grow)
MAX_STROKE_POINTS = 5000  # points of one stroke
PREVIEW_SECONDS = 0.05  # live preview at most 20 times per second of drawing
FRAME_MARGIN = 1.15  # the view's box round the tree and its lobes, this much bigger


def entry_box(ends: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The view's box on entering the modeler, round the tree's segment ends: half as big again on every
    side, at least 1.6 units each way (room to draw), never past the work volume."""
    ends = ends[np.isfinite(ends).all(axis=1)] if len(ends) else ends
    lo, hi = (ends.min(axis=0), ends.max(axis=0)) if len(ends) else (np.zeros(3), np.zeros(3))
    center = np.clip((lo + hi) / 2, -WORK_SIZE, WORK_SIZE)
    half = np.clip((hi - lo) / 2 * 1.6, 1.6, WORK_SIZE)
    return np.array([center[0] - half[0], 0.0, center[2] - half[2]]), center + half


def holding(bounds: tuple[np.ndarray, np.ndarray], points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The view's box grown to hold ``points`` (with FRAME_MARGIN to spare), never shrunk. The camera
    orbits the tree's axis, so the box is square round that axis: what is off to one side stays in view
    from every side."""
    lo, hi = bounds
    points = points[np.isfinite(points).all(axis=1)]
    reach = max(float(np.max(np.abs(np.r_[lo[[0, 2]], hi[[0, 2]]]))),
                float(np.max(np.abs(points[:, [0, 2]]), initial=0.0)) * FRAME_MARGIN)
    top = max(float(hi[1]), float(np.max(points[:, 1], initial=0.0)) * FRAME_MARGIN)
    reach, top = min(reach, WORK_SIZE), min(top, 2 * WORK_SIZE)
    return np.array([-reach, 0.0, -reach]), np.array([reach, top, reach])


class ModelingMode(ToolChoice, HistoryTold):
    """Stroke capture, conversion and undo/redo for one game (the choice of tool: game/tools/choice.py)."""

    def __init__(self, state: GameState, renderer: GardenRenderer, size: tuple[int, int],
                 camera: Callable[[], OrbitCamera]) -> None:
        self.state, self.renderer, self.size, self.camera = state, renderer, size, camera
        self.screen: Screen | None = None  # its screen on the game's stack (game/screens/modeler_screen.py)
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
        self.prune_tool = PruneTool(self)
        self.symbols = False  # drags move the region whose L-string symbols are shown
        self.region_tool = RegionTool(self)
        self.shaping = False  # drags reshape the crown's lobes
        self.crown_tool = CrownTool(self)
        self.crown_panel = CrownPanel(self)  # the crown's presets and options (the Crown tool's option)
        self.edit = EDIT_SETS[0]
        self.edit_sets = load_edit_sets(ASSETS / "edits")
        self.bar = ToolBar(size)
        self.garden_zoom = 1.0  # the camera's zoom before the modeler (given back when it is left)
        self._preview_at = float("-inf")  # stroke time of the last live preview

    @property
    def modeler(self) -> Modeler | None:
        """The cared-for tree's edit session (its world's; engine/life/world/commands.py), None before one."""
        return self.state.world.editor if self.active else None

    def segments(self, ls: LString):
        """The tree's segments as drawn now (the modeler's view of the geometry; see World.drawn_segments)."""
        return self.state.world.drawn_segments(ls)

    @property
    def active(self) -> bool:
        """Whether the modeler is open: its screen is up on the game's screen stack."""
        return self.screen is not None and self.screen.up

    def toggle(self, leave_key: bool = False) -> None:
        """Enter the modeler with the draw tool (pausing the simulation) or leave it, clearing what the
        tools drew (``leave_key``: left with Esc, and told that the next Esc asks before quitting)."""
        if self.active:
            self.screen.close()
            self.reset_tools()
            self.state.loop.speed = self.resume_speed
            self.state.control.distance = self.garden_zoom
            self.state.say(text("messages.modeler_left" if leave_key else "messages.modeler_off"))
            return
        self.screen.open()
        self.resume_speed = self.state.loop.speed or 1.0
        self.state.loop.speed = 0.0
        self.garden_zoom = self.state.control.distance
        self._start()
        self.state.say(text("messages.modeler_on"))

    def _start(self) -> None:
        """A new editing session on the cared-for tree: the draw tool, no overlays, earlier steps (and
        crown steps) out of undo's reach, the view framing the tree as it is drawn now."""
        tree = self.state.world.tree
        self.state.world.apply(BeginEditing())
        segs = self.segments(tree.lstring)  # (the tree itself: the renderer may still hold the one it replaced)
        self.bounds = entry_box(np.r_[segs.start, segs.end])
        self.state.control.distance = 1.0  # (a garden zoomed out or in would show the tree too small or cut)
        self.reset_tools()
        self.reframe()

    def replanted(self) -> None:
        """A new sapling took the cared-for tree's place: in the modeler, a new session on it (the old
        tree's lobes, regions and undo steps are gone with it)."""
        if self.active:
            self._start()

    def follow(self) -> None:
        """If the cared-for tree changed outside the modeler while it is open (another tree cared for, a
        garden loaded, time run on), edit that tree from now on: a new session, keeping the tool."""
        if self.active and (self.modeler is None or self.modeler.lstring is not self.state.world.tree.lstring):
            tool = self.current_tool
            self._start()
            self.tool(tool, quiet=True)

    def reframe(self) -> None:
        """Grow the view's box to hold the tree and the crown's lobes (it never shrinks while modeling, so
        the view does not jump back and forth)."""
        if self.modeler is None or self.bounds is None:
            return
        parts = [lobe.vertices for lobe in self.crown_tool.state().lobes]
        segs = self.segments(self.modeler.lstring)
        self.bounds = holding(self.bounds, np.concatenate([*parts, segs.start, segs.end]))

    def frame(self) -> None:
        """Frame the tree and the crown's lobes as they are now (the F key): the view's box fits them
        afresh (it may shrink) and a zoom is undone."""
        if self.modeler is None:
            return
        parts = [lobe.vertices for lobe in self.crown_tool.state().lobes]
        segs = self.segments(self.modeler.lstring)
        points = np.concatenate([*parts, segs.start, segs.end])
        self.bounds = holding(entry_box(points), points)
        self.state.control.distance = 1.0
        self.state.say(text("messages.framed"))

    def prune_at(self, x: float, y: float, camera: OrbitCamera) -> bool:
        """With the prune tool, cut the branch under pixel (x, y) (see game/tools/prune.py); False when
        no branch is there (the tap then opens the menu as usual)."""
        if not (self.pruning and self.modeler is not None):
            return False
        self.follow()
        return self.prune_tool.cut_at(x, y, camera)

    def cancel(self) -> None:
        """Drop the stroke being drawn."""
        self.points, self.times, self.preview, self.plane, self.joint = [], [], None, None, None

    def begin2d(self, x: float, y: float, t: float, camera: OrbitCamera) -> None:
        """A finger or the mouse went down: start a stroke on the camera-facing plane."""
        self.follow()
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
        if self.pruning:
            self.prune_tool.begin(x, y, camera)
            return
        self.add2d(x, y, t, camera)

    def cancel_points(self) -> None:
        """Forget the points of the stroke being drawn (the drawing plane stays) and any shape or
        region drag in progress."""
        self.points, self.times, self.preview, self.joint = [], [], None, None
        self._preview_at = float("-inf")
        self.crown_tool.drag = None
        self.prune_tool.drag = None
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
        if self.pruning:
            self.prune_tool.move(x, y)
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
        if not self.points:
            self.follow()  # (a tracker's stroke starts here)
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
            self.preview, result = self.modeler.preview(StrokePoints(np.array(self.points), np.array(self.times)))
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
            self.prune_tool.end()  # (its cuts are taps; its edits are drags)
        elif self.modeler is not None and len(self.points) >= 3:
            result = self.state.world.apply(Stroke(np.array(self.points), np.array(self.times)))
            if result is None:
                self.state.say(text("messages.stroke_budget"))  # nothing is lost: the stroke is just not added
                self.cancel()
                return
            how = text("messages.stroke_merged" if result.merged else "messages.stroke_joined"
                       if result.snapped_to is not None else "messages.stroke_new")
            if result.moved:  # (started in the air: the preview showed it moved onto the tree)
                how += ", " + text("messages.stroke_moved", distance=result.moved)
            if result.bypassed:
                how += ", " + text("messages.stroke_bent", count=result.bypassed)
            self.state.say(text("messages.stroke", pieces=counted(result.pieces, "piece"),
                                points=counted(result.growth_points, "growth point"), how=how))
        self.cancel()

    def draw_outline(self, surface: pygame.Surface, project) -> None:
        """The crown's lobes and the crown stroke being drawn, over the scene (crown and shape tools),
        and the joint point where a branch stroke being drawn will join the tree; nothing outside the modeler."""
        if not self.active:
            return
        if (self.crown or self.shaping) and self.modeler is not None:
            self.crown_tool.draw(surface, project, self.points if self.crown else [], self.shaping)
        elif self.pruning:
            self.prune_tool.draw(surface, project)
        elif self.points and self.joint is not None:
            draw_joint(surface, project, self.joint)

    def edit_at(self, x: float, y: float, camera: OrbitCamera) -> bool:
        """With the symbols tool, a tap inside the region applies the chosen edit there (undoable).
        False when the tap is outside the region (it then opens the menu as usual)."""
        if not self.symbols:
            return False
        self.follow()
        return self.region_tool.edit_at(x, y, camera, self.edit, self.edit_sets.get(self.edit))

    def draw_symbols(self, surface: pygame.Surface, camera: OrbitCamera, font: pygame.font.Font, project) -> None:
        """The symbols tool's region, contours and L-string overlay (see game/tools/region.py)."""
        if self.active and self.symbols:
            self.region_tool.draw(surface, camera, font, project, self.points)
        else:
            self.region_tool.labels = []

    def lstring(self) -> LString:
        """What to draw now: the live preview while a stroke is being drawn, else the tree."""
        return self.preview if self.preview is not None else self.state.world.tree.lstring

