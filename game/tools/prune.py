"""The prune tool of the modeler: a tap on a branch cuts it and everything growing from it (one undoable
step); the trunk's base stays."""

from __future__ import annotations

import numpy as np

from arbor.engine.life.world.commands import Cut
from arbor.game.render.camera import OrbitCamera, project_points
from arbor.game.strings import text
from arbor.game.tools.told import counted

PICK_PIXELS = 18.0  # how close a tap must be to a branch to cut it


class PruneTool:
    """Cuts for one modeling mode."""

    def __init__(self, mode) -> None:
        self.mode = mode

    def cut_at(self, x: float, y: float, camera: OrbitCamera) -> bool:
        """Cut the branch under pixel (x, y) and what grows from it. False when no branch is there (the
        tap then opens the menu as usual)."""
        mode = self.mode
        segs = mode.segments(mode.modeler.lstring)
        if len(segs) == 0:
            return False
        a = project_points(camera, mode.size, segs.start)
        b = project_points(camera, mode.size, segs.end)
        ab = b - a
        t = np.clip(np.einsum("ij,ij->i", [x, y] - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-9), 0, 1)
        dist = np.linalg.norm(a + t[:, None] * ab - [x, y], axis=1)
        k = int(np.nanargmin(np.where(np.isnan(dist), np.inf, dist)))
        if not dist[k] <= PICK_PIXELS:
            return False
        if segs.parent[k] < 0:
            mode.state.say(text("messages.prune_base"))
            return True
        removed = mode.state.world.apply(Cut(int(segs.module[k])))
        mode.state.say(text("messages.pruned", pieces=counted(removed, "branch piece")))
        return True
