"""The modeler mode of the game (Modeler I): draw trunks and branches with one finger, the mouse or
a 3D tracker; the drawing becomes L-string modules of the living tree.

2D pointers draw on the vertical plane through the tree's axis that faces the camera (orbit between
strokes to draw in depth); 3D trackers draw where they are. The tree appears as the stroke is drawn (a live preview
of the converted stroke); undo/redo take strokes back and forth. The simulation pauses while
modeling and resumes, growing branches from the drawn growth points, when the mode is left.
"""

from __future__ import annotations

import time

import numpy as np
import pygame

from engine.crown import grow_crown
from engine.edits import EDIT_SETS, apply_edit, load_edit_sets
from engine.growth import grow_geometry, render_view
from engine.lobes import Lobe, lobe_from_loops, lobe_from_outline
from engine.lstring import LString, format_number
from engine.modeler import Modeler
from engine.regions import Sphere, prune
from engine.strokes import Stroke
from engine.turtle import TurtleConfig, module_positions
from game.camera import OrbitCamera, project_points
from game.render import ASSETS
from game.strings import text
from game.symbols_overlay import draw_symbols

PICK_PIXELS = 18.0  # how close a tap must be to a branch to cut it
MAX_CROWN_MODULES = 24000  # one crown's bound even without a tree budget
MAX_CROWN_STATES = 32  # crown steps whose lobes undo/redo can bring back


class ModelingMode:
    """Stroke capture, conversion and undo/redo for one game."""

    def __init__(self, game) -> None:
        self.game = game
        self.active = False
        self.modeler: Modeler | None = None
        self.points: list[np.ndarray] = []
        self.times: list[float] = []
        self.preview: LString | None = None
        self.plane: tuple[np.ndarray, np.ndarray] | None = None  # point, normal
        self.last_plane: tuple[np.ndarray, np.ndarray] | None = None
        self.stroke_camera: OrbitCamera | None = None  # the view a 2D stroke is drawn in
        self.bounds: tuple[np.ndarray, np.ndarray] | None = None  # framing kept while modeling
        self.resume_speed = 1.0
        self.crown = False  # strokes are crown outlines, not branches
        self.pruning = False  # taps on branches cut them
        self.symbols = False  # drags move the region whose L-string symbols are shown
        self.roi: np.ndarray | None = None
        self.labels: list[tuple[str, float, float, bool]] = []  # last drawn: symbol, x, y, transformation
        self._positions: tuple[LString, np.ndarray] | None = None
        self.crown_states: dict[int, tuple] = {}  # id(L-string) -> (it, tree before crown, lobes, rings)
        self.edit = EDIT_SETS[0]
        self.edit_sets = load_edit_sets(ASSETS / "edits")

    def _segments(self, ls: LString):
        world = self.game.world
        return grow_geometry(ls, world.clocks(), world.tree.geometry_constants).turtle.segments

    def toggle(self) -> None:
        """Enter or leave the modeler (pausing the simulation while in it)."""
        if self.active:
            self.active = False
            self.cancel()
            self.game.set_speed(self.resume_speed)
            self.game.say(text("messages.modeler_off"))
            return
        self.active = True
        r = self.game.renderer
        center, half = (r.lo + r.hi) / 2, np.maximum((r.hi - r.lo) / 2, 1.0) * 1.6
        self.bounds = (np.array([center[0] - half[0], 0.0, center[2] - half[2]]), center + half)
        self.resume_speed = self.game.loop.speed or 1.0
        self.game.set_speed(0.0)
        self.modeler = Modeler(lstring=self.game.world.tree.lstring, segments_of=self._segments)
        self.crown_states.clear()  # a new editing session: earlier crown steps cannot be undone into
        self.game.say(text("messages.modeler_on"))

    def _tool(self, name: str) -> None:
        """Switch to tool ``name`` (crown, pruning, symbols) or back to branches if it is on already."""
        if not self.active:
            self.toggle()
        on = not getattr(self, name)
        self.crown = self.pruning = self.symbols = False
        setattr(self, name, on)
        self.roi = None
        self.cancel()
        self.game.say(text(f"messages.{name}_on" if on else "messages.crown_off"))

    def toggle_crown(self) -> None:
        """Switch strokes between branches and crown outlines (entering the modeler if needed)."""
        self._tool("crown")

    def toggle_prune(self) -> None:
        """Switch the pruning tool on or off (entering the modeler if needed)."""
        self._tool("pruning")

    def toggle_symbols(self) -> None:
        """Switch the L-string overlay tool on or off (entering the modeler if needed)."""
        self._tool("symbols")

    def prune_at(self, x: float, y: float, camera: OrbitCamera) -> bool:
        """With the prune tool, cut the branch under pixel (x, y) and what grows from it (undoable).
        False when no branch is there (the tap then opens the menu as usual)."""
        if not (self.pruning and self.modeler is not None):
            return False
        segs = self._segments(self.modeler.lstring)
        if len(segs) == 0:
            return False
        a = project_points(camera, self.game.size, segs.start)
        b = project_points(camera, self.game.size, segs.end)
        ab = b - a
        t = np.clip(np.einsum("ij,ij->i", [x, y] - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-9), 0, 1)
        dist = np.linalg.norm(a + t[:, None] * ab - [x, y], axis=1)
        k = int(np.nanargmin(np.where(np.isnan(dist), np.inf, dist)))
        if not dist[k] <= PICK_PIXELS:
            return False
        if segs.parent[k] < 0:
            self.game.say(text("messages.prune_base"))
            return True
        before = self.modeler.lstring
        self.modeler.commit(prune(before, int(segs.module[k])))
        self.game.world.tree.lstring = self.modeler.lstring
        self.game.say(text("messages.pruned", count=len(segs) - len(self._segments(self.modeler.lstring))))
        return True

    def cancel(self) -> None:
        """Drop the stroke being drawn."""
        self.points, self.times, self.preview, self.plane = [], [], None, None

    def begin2d(self, x: float, y: float, t: float, camera: OrbitCamera) -> None:
        """A finger or the mouse went down: start a stroke on the camera-facing plane."""
        normal = camera.target - camera.eye
        normal[1] = 0.0  # a vertical plane: it contains the tree's axis and faces the camera
        normal /= max(np.linalg.norm(normal), 1e-12)
        through = np.array([0.0, camera.target[1], 0.0])
        self.plane = self.last_plane = (through, normal)
        self.stroke_camera = camera
        self.cancel_points()
        self.add2d(x, y, t, camera)

    def cancel_points(self) -> None:
        """Forget the points of the stroke being drawn (the drawing plane stays)."""
        self.points, self.times, self.preview = [], [], None

    def add2d(self, x: float, y: float, t: float, camera: OrbitCamera) -> None:
        """The pointer moved: extend the stroke with the point under it on the drawing plane."""
        if self.plane is None:
            return
        hit = unproject_to_plane(self.stroke_camera or camera, self.game.size, x, y, *self.plane)
        if hit is not None:
            self.add3d(hit, t)

    def add3d(self, point, t: float) -> None:
        """Extend the stroke with a 3D point (a tracker's cursor) and refresh the preview."""
        self.points.append(np.asarray(point, dtype=np.float64))
        self.times.append(t)
        if self.symbols:
            self.roi = self.points[-1]
        elif len(self.points) >= 3 and self.modeler is not None and not (self.crown or self.pruning):
            self.preview, _ = self.modeler.convert(Stroke(np.array(self.points), np.array(self.times)))

    def finish(self) -> None:
        """The pointer went up: commit the stroke to the tree (undoable)."""
        if self.crown and self.modeler is not None:
            self._grow_crown()
        elif self.pruning or self.symbols:
            pass  # the prune tool cuts with taps; the symbols tool's drag only moved its region
        elif self.modeler is not None and len(self.points) >= 3:
            new, result = self.modeler.convert(Stroke(np.array(self.points), np.array(self.times)))
            budget = self.game.world.tree.deriver.budget
            if budget is not None and len(new) > max(budget, len(self.modeler.lstring)):
                self.game.say(text("messages.stroke_budget"))  # nothing is lost: the stroke is just not added
                self.cancel()
                return
            if result.pieces:
                self.modeler.commit(new)
            self.game.world.tree.lstring = self.modeler.lstring
            how = text("messages.stroke_joined" if result.snapped_to is not None else "messages.stroke_new")
            if result.bypassed:
                how += ", " + text("messages.stroke_bent", count=result.bypassed)
            self.game.say(text("messages.stroke", pieces=result.pieces, points=result.growth_points, how=how))
        self.cancel()

    def _crown_state(self) -> tuple[LString, list[Lobe], list[np.ndarray]]:
        """The tree before its crown, the crown's lobes and the pending rings, for the tree as it is
        now (so undo and redo of crown steps bring their lobes back too)."""
        kept = self.crown_states.get(id(self.modeler.lstring))
        if kept is not None and kept[0] is self.modeler.lstring:
            return kept[1], kept[2], kept[3]
        return self.modeler.lstring, [], []

    def _remember_crown(self, ls: LString, base: LString, lobes: list[Lobe], rings: list[np.ndarray]) -> None:
        self.crown_states[id(ls)] = (ls, base, lobes, rings)
        while len(self.crown_states) > MAX_CROWN_STATES:  # bounded: the oldest crown steps are forgotten
            del self.crown_states[next(iter(self.crown_states))]

    def _grow_crown(self) -> None:
        if len(self.points) < 8:
            return
        points = np.array(self.points)
        base, lobes, rings = self._crown_state()
        span = np.ptp(points, axis=0)
        if span.max() < 1e-3:
            return
        if span[1] < 0.25 * max(span[0], span[2]):  # a ring around the crown (3D trackers): stitch rings
            rings = [*rings, points]
            if len(rings) < 2:
                self._remember_crown(self.modeler.lstring, base, lobes, rings)
                self.game.say(text("messages.crown_ring"))
                return
            lobes = [*lobes[:-1], lobe_from_loops(rings)] if len(rings) > 2 else [*lobes, lobe_from_loops(rings)]
        else:
            lobes, rings = [*lobes, lobe_from_outline(points)], []
        start = time.perf_counter()
        grown, added, limited = self._regrow(base, lobes)
        ms = (time.perf_counter() - start) * 1e3
        self.modeler.commit(grown)  # the whole crown regrown into every lobe: one undoable step
        self._remember_crown(grown, base, lobes, rings)
        self.game.world.tree.lstring = self.modeler.lstring
        key = "messages.crown_none" if added == 0 else "messages.crown_full" if limited else "messages.crown"
        self.game.say(text(key, count=added, ms=ms, lobes=len(lobes)))

    def _regrow(self, base: LString, lobes: list[Lobe]) -> tuple[LString, int, bool]:
        """The crown grown from ``base`` into ``lobes`` within the tree's module budget: a try that is
        too big is grown again with proportionally fewer nodes (at most four tries). Returns the L-string,
        the branch pieces added and whether the budget limited them."""
        budget = self.game.world.tree.deriver.budget
        room = MAX_CROWN_MODULES if budget is None else min(MAX_CROWN_MODULES, budget - len(base))
        nodes, seed = MAX_CROWN_MODULES // 4, int(self.modeler.rng.integers(2**31))
        for _ in range(4):
            if room <= 0 or nodes < 2:
                break
            scratch = Modeler(lstring=base, segments_of=self._segments)
            added = grow_crown(scratch, lobes, np.random.default_rng(seed), per_lobe=250, step_fraction=0.2,
                               max_nodes=nodes, tip=f"[&(45)L({format_number(self._born_visible())})]")
            extra = len(scratch.lstring) - len(base)
            if extra <= room:
                return scratch.lstring, added, added >= nodes - 2 or nodes < MAX_CROWN_MODULES // 4
            nodes = int(added * room / extra * 0.9)
        return base, 0, True

    def draw_outline(self, surface: pygame.Surface, project) -> None:
        """The crown's lobes (their stitched strokes, faint) and the outline being drawn, as closed
        lines over the scene (``project``: 3D -> pixels)."""
        if not self.crown or self.modeler is None:
            return
        _, lobes, rings = self._crown_state()
        loops = [ring for lobe in lobes for ring in lobe.vertices[:-2].reshape(-1, lobe.ring_size, 3)] + rings
        for loop in loops:
            faint = [p for p in (project(point) for point in loop) if p is not None]
            if len(faint) >= 3:
                pygame.draw.lines(surface, (170, 240, 170, 110), True, faint, 2)
        if len(self.points) < 2:
            return
        pixels = [p for p in (project(point) for point in self.points) if p is not None]
        if len(pixels) >= 2:
            pygame.draw.lines(surface, (120, 230, 120, 230), len(pixels) >= 8, pixels, 4)

    def _born_visible(self) -> float:
        """A birth time for leaves and blossoms added while the garden is paused: one growth time
        constant ago, so they show at once (63 % grown) and finish growing when time runs again."""
        return self.game.world.clocks().length_time - self.game.world.tree.geometry_constants["TAU"]

    def next_edit(self) -> str:
        """Choose the next region edit (the menu button cycles through them)."""
        self.edit = EDIT_SETS[(EDIT_SETS.index(self.edit) + 1) % len(EDIT_SETS)]
        return self.edit

    def _roi_sphere(self) -> Sphere:
        r = self.game.renderer
        return Sphere(tuple(self.roi), 0.15 * max(float(np.max(r.hi - r.lo)), 1.0))

    def edit_at(self, x: float, y: float, camera: OrbitCamera) -> bool:
        """With the symbols tool, a tap inside the region applies the chosen edit there (undoable).
        False when the tap is outside the region (it then opens the menu as usual)."""
        if not (self.symbols and self.roi is not None and self.modeler is not None):
            return False
        sphere = self._roi_sphere()
        centre = project_points(camera, self.game.size, self.roi[None])[0]
        edge = project_points(camera, self.game.size, (self.roi + sphere.radius * camera.view()[0, :3])[None])[0]
        if not np.hypot(x - centre[0], y - centre[1]) <= np.linalg.norm(edge - centre):
            return False
        ls = self.game.world.tree.lstring
        new, changed, held = apply_edit(ls, self._module_positions(ls), sphere, self.edit_sets[self.edit],
                                        {"T": self._born_visible(), "G": self.game.world.clocks().girth_time},
                                        budget=self.game.world.tree.deriver.budget)
        if changed:
            self.modeler.commit(new)
            self.game.world.tree.lstring = new
        message = text("messages.edited", edit=text(f"edits.{self.edit}"), count=changed)
        self.game.say(message + (" " + text("messages.budget") if held else ""))
        return True

    def draw_symbols(self, surface: pygame.Surface, camera: OrbitCamera, font: pygame.font.Font) -> None:
        """The L-string overlay of the symbols tool (see game/symbols_overlay.py)."""
        self.labels = []
        if self.symbols and self.roi is not None:
            ls = self.game.world.tree.lstring
            self.labels = draw_symbols(surface, font, camera, self.game.size, ls, self._module_positions(ls),
                                       self._roi_sphere())

    def _module_positions(self, ls: LString) -> np.ndarray:
        """Turtle positions of every module of the tree as drawn now (cached per L-string)."""
        if self._positions is None or self._positions[0] is not ls:
            tree, clocks = self.game.world.tree, self.game.world.clocks()
            view = render_view(ls, clocks, tree.geometry_constants)
            self._positions = (ls, module_positions(view, TurtleConfig(pipe_model=False, leaves_at_tips=0)))
        return self._positions[1]

    def undo(self) -> None:
        """Take back the last stroke."""
        if self.modeler is not None and self.modeler.undo():
            self.game.world.tree.lstring = self.modeler.lstring

    def redo(self) -> None:
        """Put back the last undone stroke."""
        if self.modeler is not None and self.modeler.redo():
            self.game.world.tree.lstring = self.modeler.lstring

    def lstring(self) -> LString:
        """What to draw now: the live preview while a stroke is being drawn, else the tree."""
        return self.preview if self.preview is not None else self.game.world.tree.lstring


def unproject_to_plane(camera: OrbitCamera, size: tuple[int, int], x: float, y: float,
                       point: np.ndarray, normal: np.ndarray) -> np.ndarray | None:
    """The point of the plane (point, normal) under window pixel (x, y)."""
    vp = camera.projection(size[0] / size[1]) @ camera.view()
    inv = np.linalg.inv(vp)
    ndc = np.array([2 * x / size[0] - 1, 1 - 2 * y / size[1]])
    near = inv @ np.array([*ndc, -1.0, 1.0])
    far = inv @ np.array([*ndc, 1.0, 1.0])
    a, b = near[:3] / near[3], far[:3] / far[3]
    d = b - a
    denom = float(d @ normal)
    if abs(denom) < 1e-12:
        return None
    s = float((point - a) @ normal) / denom
    return a + s * d if s > 0 else None

