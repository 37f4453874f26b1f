"""The prune tool of the modeler, which edits single branches (issue 48): its option (the button under the
tools) chooses what it does. Cut: a tap on a branch cuts it and everything growing from it (the trunk's
base stays). Width, angle, length: a tap picks the branch under it (shown lit) and an up or down drag
then changes it, shown live as the drag goes (drag up: wider, further from its parent's axis, longer),
committed as one undoable step when the pointer is let go; a drag that starts on a branch picks it and
changes it at once (engine/modeling/branch_edit.py, the world's BranchEdit command). Brush: a drag over
the tree widens every branch it passes over x1.25 (the width brush: one undoable step per drag; a branch
inside another brushed one widens with it, once; the world's WidthBrush command)."""

from __future__ import annotations

import numpy as np

from arbor.engine.base.units import METRE
from arbor.engine.life.world.commands import BranchEdit, Cut, WidthBrush
from arbor.engine.modeling.branch_edit import LIMITS, branch_of, branch_span, edited
from arbor.game.render.camera import OrbitCamera, project_points
from arbor.game.render.ui import draw_polyline
from arbor.game.strings import text
from arbor.game.tools.told import counted

PICK_PIXELS = 18.0  # how close a tap must be to a branch to cut or pick it
BRANCH_OPS = ("cut", "width", "angle", "length", "brush")
BRUSH_FACTOR = 1.25  # one pass of the width brush widens the branches it touched this much
PIXELS_PER_DOUBLING = 150.0  # a drag this far up doubles a width or a length
DEGREES_PER_PIXEL = 0.3  # an angle drag: degrees per pixel


class PruneTool:
    """Cuts and branch edits for one modeling mode (see module docstring)."""

    def __init__(self, mode) -> None:
        self.mode = mode
        self.op = BRANCH_OPS[0]
        self.picked: tuple[object, int] | None = None  # (the L-string it was picked on, its first module)
        self.camera: OrbitCamera | None = None  # the view a brush drag is made in
        self.drag: tuple[float, float] | None = None  # where an edit drag started (pixels)
        self.amount: float | None = None  # the edit the drag shows
        self.brushed: list[int] = []  # the pieces (modules) the width brush passed over in this drag

    def next_op(self) -> str:
        """The next of cut, width, angle, length (the option button)."""
        self.op = BRANCH_OPS[(BRANCH_OPS.index(self.op) + 1) % len(BRANCH_OPS)]
        self.drag = self.amount = None
        return self.op

    def clear(self) -> None:
        """No branch picked, no drag."""
        self.picked, self.drag, self.amount, self.brushed = None, None, None, []

    def _segment_at(self, x: float, y: float, camera: OrbitCamera):
        """The tree's segments and the one under pixel (x, y) (None: no branch within PICK_PIXELS)."""
        mode = self.mode
        segs = mode.segments(mode.modeler.lstring)
        if len(segs) == 0:
            return segs, None
        a = project_points(camera, mode.size, segs.start)
        b = project_points(camera, mode.size, segs.end)
        ab = b - a
        t = np.clip(np.einsum("ij,ij->i", [x, y] - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-9), 0, 1)
        dist = np.linalg.norm(a + t[:, None] * ab - [x, y], axis=1)
        k = int(np.nanargmin(np.where(np.isnan(dist), np.inf, dist)))
        return segs, (k if dist[k] <= PICK_PIXELS else None)

    def cut_at(self, x: float, y: float, camera: OrbitCamera) -> bool:
        """A tap: cut the branch under pixel (x, y) (or, editing, pick it). False when no branch is there
        (the tap then opens the menu as usual)."""
        mode = self.mode
        segs, k = self._segment_at(x, y, camera)
        if k is None:
            return False
        if self.op == "brush":  # (a tap is a brush over one branch)
            self.brushed = [int(segs.module[k])]
            self._brushed()
            return True
        if self.op != "cut":
            self._pick(segs, k)
            return True
        if segs.parent[k] < 0:
            mode.state.say(text("messages.prune_base"))
            return True
        removed = mode.state.world.apply(Cut(int(segs.module[k])))
        mode.state.say(text("messages.pruned", pieces=counted(removed, "branch piece")))
        return True

    def _pick(self, segs, k: int) -> None:
        """Pick the branch segment ``k`` lies on and say what it is."""
        ls = self.mode.modeler.lstring
        first = branch_of(segs, k)
        self.picked = (ls, int(segs.module[first]))
        chosen = self._chosen(segs, first)
        length = float(np.linalg.norm(segs.end[chosen] - segs.start[chosen], axis=1).sum()) / METRE
        self.mode.state.say(text("messages.branch_picked", pieces=counted(int(chosen.sum()), "piece"),
                                 length=length, width=2000.0 * float(segs.radius[first]) / METRE,
                                 op=text(f"branch_ops.{self.op}")))

    def _chosen(self, segs, first: int) -> np.ndarray:
        """Which segments are the branch starting at segment ``first``."""
        start, end = branch_span(self.mode.modeler.lstring, segs, first)
        return (segs.module >= start) & (segs.module < end)

    def _first(self, segs) -> int | None:
        """The picked branch's first segment, if it is still on the tree as it is."""
        if self.picked is None or self.picked[0] is not self.mode.modeler.lstring:
            self.picked = None
            return None
        k = np.flatnonzero(segs.module == self.picked[1])
        return int(k[0]) if len(k) else None

    def begin(self, x: float, y: float, camera: OrbitCamera) -> None:
        """An edit drag starts: on a branch it picks that one; else it edits the branch picked before."""
        if self.op == "cut":
            return
        segs, k = self._segment_at(x, y, camera)
        if self.op == "brush":
            self.drag, self.camera, self.brushed = (x, y), camera, []
            self._brush(x, y)
            return
        if k is not None:
            self.picked = (self.mode.modeler.lstring, int(segs.module[branch_of(segs, k)]))
        self.drag, self.amount = (x, y), None

    def move(self, x: float, y: float) -> None:
        """The drag moved: the picked branch as it would be, shown (not yet committed)."""
        if self.drag is None or self.mode.modeler is None:
            return
        if self.op == "brush":
            self._brush(x, y)
            return
        segs = self.mode.segments(self.mode.modeler.lstring)
        first = self._first(segs)
        if first is None:
            return
        up = self.drag[1] - y
        amount = up * DEGREES_PER_PIXEL if self.op == "angle" else 2.0 ** (up / PIXELS_PER_DOUBLING)
        self.amount = float(np.clip(amount, *LIMITS[self.op]))
        self.mode.preview = edited(self.mode.modeler.lstring, segs, first, self.op, self.amount)

    def end(self) -> None:
        """The drag ended: commit the edit it showed (one undoable step) and say what changed."""
        drag, amount, self.drag, self.amount = self.drag, self.amount, None, None
        mode = self.mode
        mode.preview = None
        if drag is None or mode.modeler is None:
            return
        if self.op == "brush":
            self._brushed()
            return
        if self._first(mode.segments(mode.modeler.lstring)) is None:
            mode.state.say(text("messages.branch_none"))
            return
        if amount is None or (abs(amount) < 1e-3 if self.op == "angle" else abs(amount - 1.0) < 1e-3):
            return
        result = mode.state.world.apply(BranchEdit(self.picked[1], self.op, amount))
        if result.pieces == 0:
            return
        self.picked = (mode.modeler.lstring, result.module)
        key = "messages.branch_turned" if self.op == "angle" else "messages.branch_scaled"
        grown = result.pieces - result.drawn if self.op != "angle" else 0
        note = text("messages.branch_grown", count=counted(grown, "grown piece")) if grown else ""
        mode.state.say(text(key, op=text(f"branch_ops.{self.op}"), amount=result.amount,
                            pieces=counted(result.pieces, "piece"), note=note))

    def _brush(self, x: float, y: float) -> None:
        """The width brush passed over pixel (x, y): the piece there (if any) is brushed."""
        segs, k = self._segment_at(x, y, self.camera)
        if k is not None and int(segs.module[k]) not in self.brushed:
            self.brushed.append(int(segs.module[k]))

    def _brushed(self) -> None:
        """The brush let go: the branches it passed over widened, one undoable step."""
        brushed, self.brushed = self.brushed, []
        if not brushed:
            self.mode.state.say(text("messages.brush_none"))
            return
        count = self.mode.state.world.apply(WidthBrush(tuple(brushed), BRUSH_FACTOR))
        self.mode.state.say(text("messages.brushed", branches=counted(count, "branch"), factor=BRUSH_FACTOR))

    def draw(self, surface, project) -> None:
        """The picked branch lit over the scene (as the drag shows it)."""
        mode = self.mode
        if self.op == "cut" or mode.modeler is None:
            return
        if self.op == "brush":
            segs = mode.segments(mode.modeler.lstring)
            for k in np.flatnonzero(np.isin(segs.module, self.brushed)):
                draw_polyline(surface, project, np.stack([segs.start[k], segs.end[k]]), (255, 230, 90, 230), False, 4)
            return
        ls = mode.preview if mode.preview is not None else mode.modeler.lstring
        segs = mode.segments(mode.modeler.lstring)
        first = self._first(segs)
        if first is None:
            return
        if mode.preview is not None:
            segs = mode.segments(ls)
        chosen = np.flatnonzero(self._chosen(mode.segments(mode.modeler.lstring), first))
        chosen = chosen[chosen < len(segs)]
        for k in chosen:
            draw_polyline(surface, project, np.stack([segs.start[k], segs.end[k]]), (255, 230, 90, 230), False, 3)
