"""Taps on the garden itself: pick a ripe fruit, or choose the tree to care for by tapping it."""

from __future__ import annotations

import numpy as np

from arbor.game.render.camera import OrbitCamera, project_points
from arbor.game.screens.care import CareActions
from arbor.game.screens.state import GameState
from arbor.game.strings import text

FRUIT_PIXELS = 28  # a tap this close to a ripe fruit picks it (a finger, not a mouse pointer)
TRUNK_PIXELS = 40  # a tap this close to another tree's trunk line chooses it


class Picker:
    """Finds what a tap on the scene points at (see module docstring)."""

    def __init__(self, state: GameState, views: dict, size: tuple[int, int], care: CareActions) -> None:
        self.state, self.size, self.care = state, size, care
        self.views = views  # the view's records of the trees (world id -> key, records, ...)

    def tap(self, x: float, y: float, camera: OrbitCamera) -> bool:
        """Pick the ripe fruit or choose the tree at (x, y) (to care for, or as the other parent of a
        cross the player started); False when the tap hit neither."""
        state, care = self.state, self.care
        if care.crossing is not None:
            care.cross_with(self.tree_at(x, y, camera))
            return True
        module = self.fruit_at(x, y, camera)
        if module is not None and state.garden.harvest(state.world, module) is not None:
            state.say(text("messages.picked", count=len(state.garden.seeds)), 4)
            return True
        index = self.tree_at(x, y, camera)
        if index is None:
            return False
        care.care_for(index)
        return True

    def fruit_at(self, x: float, y: float, camera: OrbitCamera) -> int | None:
        """The module of the ripe fruit of the cared-for tree nearest to (x, y), if one is close."""
        entry = self.views.get(id(self.state.world))
        if entry is None or not len(entry[1].fruits.data):
            return None
        view = entry[1]
        ripe = np.flatnonzero(view.fruits.data[:, 10] >= 1.0)
        if not len(ripe):
            return None
        pixels = project_points(camera, self.size, view.fruits.data[ripe, 0:3].astype(float))
        dist = np.hypot(pixels[:, 0] - x, pixels[:, 1] - y)
        dist[~np.isfinite(dist)] = np.inf
        best = int(np.argmin(dist))
        return int(view.fruit_module[ripe[best]]) if dist[best] <= FRUIT_PIXELS else None

    def tree_at(self, x: float, y: float, camera: OrbitCamera) -> int | None:
        """The index of the other tree whose trunk line (foot to top) passes closest to (x, y)."""
        state = self.state
        here = np.array(state.world.position)
        best, best_dist = None, float(TRUNK_PIXELS)
        for i, world in enumerate(state.garden.worlds):
            entry = self.views.get(id(world))
            if world is state.world or entry is None:
                continue
            dx, dz = np.array(world.position) - here
            top = max(float(entry[1].hi[1]), 1.0)
            ends = project_points(camera, self.size, np.array([[dx, 0.0, dz], [dx, top, dz]]))
            if not np.isfinite(ends).all():
                continue
            dist = _to_segment(np.array([x, y]), ends[0], ends[1])
            if dist < best_dist:
                best, best_dist = i, dist
        return best


def _to_segment(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> float:
    """Distance from point p to segment ab (pixels)."""
    ab = b - a
    t = float(np.clip(np.dot(p - a, ab) / max(float(np.dot(ab, ab)), 1e-9), 0.0, 1.0))
    return float(np.linalg.norm(p - (a + t * ab)))
