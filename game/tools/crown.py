"""The crown tools of the modeler (Zhang et al.): draw lobes, close them with arches, reshape them; the
crown regrows into the lobes after every change, as one undoable step.

Crown strokes: a closed outline drawn on the screen becomes a lobe (a silhouette); closed flat rings
drawn around the crown with a 3D tracker are stitched into a lobe that grows with every ring, and an
open stroke drawn across that lobe's top or bottom ring closes it with a dome instead of a flat cap. A
ring drawn away from that lobe (its centre outside the lobe's nearest ring, seen from above) starts a
new lobe instead of being stitched to the first.
Shape tool: a drag moves, scales, turns or squeezes the lobe under the pointer, or pulls one stroke
point (the operation is chosen with the menu's option button); only that lobe's crown regrows. The lobes
a tree's crown grew into are part of the tree (its world keeps them, engine/modeling/crowned.py): undo
and redo bring them back, and they are there again after Done, a save and load or a restart.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace

import numpy as np
import pygame

from arbor.engine.life.world.commands import Crown
from arbor.engine.lsystem.lstring import LString
from arbor.engine.modeling.crown_style import CrownStyle
from arbor.engine.modeling.lobes import Lobe, lobe_from_loops, lobe_from_outline
from arbor.game.render.camera import OrbitCamera, project_points, unproject_to_plane
from arbor.game.render.ui import draw_polyline
from arbor.game.strings import text
from arbor.game.tools.told import counted

MAX_CROWN_STATES = 32  # crown steps whose lobes undo/redo can bring back
SHAPE_OPS = ("move", "scale", "turn", "squeeze", "point")
POINT_PIXELS = 28.0  # how close a drag must start to a stroke point to pull it


@dataclass
class CrownState:
    """A crown step: the tree before any crown, the lobes, and the 3D rings and arches that make the
    last lobe while it is still being drawn."""

    base: LString
    lobes: list[Lobe] = field(default_factory=list)
    rings: list[np.ndarray] = field(default_factory=list)
    arches: list[np.ndarray] = field(default_factory=list)


@dataclass
class _Drag:
    """A shape drag in progress: the lobe it started on and its shape then."""

    index: int
    lobe: Lobe
    start: tuple[float, float]
    point: tuple[int, int] | None = None  # (ring, index) of the pulled stroke point
    edited: Lobe | None = None


SMALLEST = 1.0  # leaf lengths: a smaller outline could not hold one of the crown's leaves


def continues(rings: list[np.ndarray], ring: np.ndarray) -> bool:
    """Whether a tracker ring goes on with the lobe that ``rings`` are making: seen from above, its centre
    lies within the group's ring nearest to it in height, or the group's nearest ring's centre within it."""
    def plan(loop: np.ndarray) -> tuple[np.ndarray, float, float]:
        centre = loop.mean(axis=0)
        return centre[[0, 2]], float(np.linalg.norm(loop[:, [0, 2]] - centre[[0, 2]], axis=1).mean()), centre[1]

    at, radius, height = plan(ring)
    near = min((plan(loop) for loop in rings), key=lambda p: abs(p[2] - height))
    return float(np.linalg.norm(at - near[0])) <= max(radius, near[1])


class CrownTool:
    """Crown strokes and lobe shaping for one modeling mode (see module docstring)."""

    def __init__(self, mode) -> None:
        self.mode = mode
        self.states: dict[int, tuple[LString, CrownState]] = {}
        self.op = SHAPE_OPS[0]
        self.drag: _Drag | None = None
        self.style: CrownStyle | None = None  # how the first crown grows (the crown panel's choice)

    def clear(self) -> None:
        """A new modeling session: rings being drawn are dropped (the tree's lobes stay with the tree)."""
        self.states.clear()
        self.drag = None

    def state(self) -> CrownState:
        """The crown step of the tree as it is now: the rings being drawn on it, else its lobes (part of
        the tree: its world keeps them through Done, saves and loads; engine/modeling/crowned.py), else a
        fresh one."""
        ls = self.mode.modeler.lstring
        kept = self.states.get(id(ls))
        if kept is not None and kept[0] is ls:
            return kept[1]
        crown = self.mode.state.world.crown
        if crown is None:
            return CrownState(ls)
        return CrownState(crown.base_for(ls), list(crown.lobes))

    def remember(self, ls: LString, state: CrownState) -> None:
        """The crown step ``state`` stands with the tree ``ls`` (undo and redo to it find it again); bounded."""
        self.states[id(ls)] = (ls, state)
        while len(self.states) > MAX_CROWN_STATES:  # bounded: the oldest crown steps are forgotten
            del self.states[next(iter(self.states))]

    def stroke(self, points: np.ndarray) -> None:
        """A finished crown stroke: a silhouette, a ring around the crown or an arch closing it."""
        if len(points) < 8 or np.ptp(points, axis=0).max() < 1e-3:
            return
        state = self.state()
        span = np.ptp(points, axis=0)
        closed = np.linalg.norm(points[-1] - points[0]) < 0.25 * span.max()
        if not closed and len(state.rings) >= 2:  # an arch across the ring lobe's top or bottom
            state = replace(state, arches=[*state.arches, points])
            state.lobes = [*state.lobes[:-1], lobe_from_loops(state.rings, open_strokes=state.arches)]
        elif span[1] < 0.25 * max(span[0], span[2]):  # a ring around the crown (3D trackers)
            away = bool(state.rings) and not continues(state.rings, points)
            if away:  # a new group of rings: the lobe of the last group stays as it is
                state = replace(state, rings=[], arches=[])
            rings = [*state.rings, points]
            if len(rings) < 2:
                self.remember(self.mode.modeler.lstring, replace(state, rings=rings))
                self.mode.state.say(text("messages.crown_ring_new" if away else "messages.crown_ring"))
                return
            lobe = lobe_from_loops(rings, open_strokes=state.arches)
            lobes = [*state.lobes[:-1], lobe] if len(rings) > 2 else [*state.lobes, lobe]
            state = replace(state, lobes=lobes, rings=rings)
        elif not closed:  # (an open line is no silhouette: it would make a lobe of the wrong shape)
            self.mode.state.say(text("messages.crown_open"))
            return
        elif span.max() < SMALLEST * self.mode.state.world.tree.geometry_constants["LS"]:
            self.mode.state.say(text("messages.crown_small"))
            return
        else:
            state = CrownState(state.base, [*state.lobes, lobe_from_outline(points)])
        self._regrow_into(state, "messages.crown")

    def _regrow_into(self, state: CrownState, key: str, only: int | None = None, **extra) -> None:
        """Regrow the crown from the tree before it into ``state``'s lobes (``only``: the one lobe an edit
        changed, whose crown alone regrows); one undoable step."""
        start = time.perf_counter()
        world = self.mode.state.world
        style = None if world.crown is not None else self.style  # (a crown standing keeps its own style)
        grown = world.apply(Crown(state.base, tuple(state.lobes), only, style))
        if grown.refused is not None:  # (nothing grew: the lobes stay as they were)
            self.mode.state.say(text("messages.crown_refused", why=grown.refused))
            return
        added, limited = grown.added, grown.limited
        ms = (time.perf_counter() - start) * 1e3
        self.remember(world.tree.lstring, state)  # (the view stays: F frames the crown and its lobes)
        if added == 0:
            key = "messages.crown_none"
        elif limited:
            key = "messages.shaped_full" if key == "messages.shaped" else "messages.crown_full"
        lobes = counted(len(state.lobes), "lobe")
        self.mode.state.say(text(key, count=added, ms=ms, lobes=lobes, **extra))

    def next_op(self) -> str:
        """Choose the next shape operation (the menu's option button cycles through them)."""
        self.op = SHAPE_OPS[(SHAPE_OPS.index(self.op) + 1) % len(SHAPE_OPS)]
        return self.op

    def begin_shape(self, x: float, y: float, camera: OrbitCamera) -> None:
        """A drag starts: take the lobe (or, for 'point', the stroke point) under the pointer."""
        self.drag = None
        lobes = self.state().lobes
        if not lobes:
            self.mode.state.say(text("messages.shape_none"))
            return
        size = self.mode.size
        if self.op == "point":
            best = None
            for i, lobe in enumerate(lobes):
                pixels = project_points(camera, size, lobe.stroke_rings.reshape(-1, 3))
                dist = np.hypot(pixels[:, 0] - x, pixels[:, 1] - y)
                k = int(np.nanargmin(np.where(np.isnan(dist), np.inf, dist)))
                if dist[k] <= POINT_PIXELS and (best is None or dist[k] < best[0]):
                    best = (dist[k], i, divmod(k, lobe.ring_size))
            if best is not None:
                self.drag = _Drag(best[1], lobes[best[1]], (x, y), best[2])
            return
        centres = project_points(camera, size, np.array([lobe.vertices.mean(axis=0) for lobe in lobes]))
        for i in np.argsort(np.hypot(centres[:, 0] - x, centres[:, 1] - y)):
            pixels = project_points(camera, size, lobes[i].vertices)
            lo, hi = np.nanmin(pixels, axis=0), np.nanmax(pixels, axis=0)
            if lo[0] <= x <= hi[0] and lo[1] <= y <= hi[1]:
                self.drag = _Drag(int(i), lobes[i], (x, y))
                return

    def drag_shape(self, x: float, y: float, camera: OrbitCamera) -> None:
        """The pointer moved: the picked lobe, edited by the drag so far (shown; not yet grown into)."""
        d = self.drag
        if d is None:
            return
        dx, dy = x - d.start[0], y - d.start[1]
        lobe, centre = d.lobe, d.lobe.vertices.mean(axis=0)
        if self.op == "move":
            d.edited = lobe.transformed(move=self._on_plane(x, y, centre, camera) - self._on_plane(
                *d.start, centre, camera))
        elif self.op == "scale":
            d.edited = lobe.transformed(scale=float(np.exp(-dy / 200.0)))
        elif self.op == "turn":
            d.edited = lobe.transformed(turn_deg=dx * 0.5)
        elif self.op == "squeeze":
            at = self._on_plane(*d.start, centre, camera)
            toward = project_points(camera, self.mode.size, centre[None])[0] - d.start
            amount = float(np.clip(np.dot([dx, dy], toward) / max(np.linalg.norm(toward), 1.0) / 150.0, -0.6, 0.6))
            d.edited = lobe.squeezed(at, 0.5 * float(np.ptp(lobe.vertices, axis=0).max()), amount)
        elif d.point is not None:
            ring, index = d.point
            to = self._on_plane(x, y, lobe.stroke_rings[ring, index], camera)
            d.edited = lobe.dragged(ring, index, to)

    def end_shape(self) -> None:
        """The drag ended: regrow the crown into the edited lobe (one undoable step)."""
        d, self.drag = self.drag, None
        if d is None or d.edited is None:
            return
        state = self.state()
        lobes = list(state.lobes)
        lobes[d.index] = d.edited
        edited = CrownState(state.base, lobes)  # rings and arches made the old shape: drawing starts anew
        self._regrow_into(edited, "messages.shaped", d.index, op=text(f"shapes.{self.op}"))

    def _on_plane(self, x: float, y: float, through: np.ndarray, camera: OrbitCamera) -> np.ndarray:
        """The point under pixel (x, y) on the camera-facing plane through ``through``."""
        normal = camera.target - camera.eye
        normal = normal / max(float(np.linalg.norm(normal)), 1e-12)
        hit = unproject_to_plane(camera, self.mode.size, x, y, through, normal)
        return through if hit is None else hit

    def draw(self, surface: pygame.Surface, project, points: list[np.ndarray], shaping: bool) -> None:
        """The lobes' stroke rings (faint; the one being reshaped bright), pending rings and arches,
        and the crown stroke being drawn (``project``: 3D points -> the pixels of those in view)."""
        state = self.state()
        lobes = list(state.lobes)
        if self.drag is not None and self.drag.edited is not None:
            lobes[self.drag.index] = self.drag.edited
        for i, lobe in enumerate(lobes):
            bright = shaping and self.drag is not None and i == self.drag.index
            colour = (255, 240, 150, 230) if bright else (170, 240, 170, 110)
            for loop in lobe.stroke_rings:
                draw_polyline(surface, project, loop, colour, True, 3 if bright else 2)
        for loop in state.rings:
            draw_polyline(surface, project, loop, (170, 240, 170, 110), True, 2)
        for arch in state.arches:
            draw_polyline(surface, project, arch, (170, 240, 170, 110), False, 2)
        if len(points) >= 2 and not shaping:
            draw_polyline(surface, project, np.array(points), (120, 230, 120, 230), len(points) >= 8, 4)
