"""Trees that share a plot (a lab experiment with ``spacing``: the competition lesson) drawn in one scene:
every tree at its place in the row, at one scale, seen from the side the row faces, lit from the front
(the sun at the viewer's back, up and to the left, so the crowns are never dark against the sky) unless the
simulation's own sun is asked for; where each tree stands on screen, to write its name and state beneath it.
"""

from __future__ import annotations

import numpy as np

from arbor.engine.base.units import METRE
from arbor.engine.geometry.mesh import merge_trees
from arbor.game.render.camera import OrbitCamera, project_points
from arbor.game.render.renderer import TreeRenderer, sun_direction

YAW, PITCH = 8.0, 9.0  # degrees: nearly square on to the row (the row runs along x), a little from above
FRONT = (35.0, 45.0)  # the front light: azimuth from the camera's side (degrees) and elevation (degrees)
MIN_HEIGHT = 1.0 * METRE  # the scene frames at least this tall a box (a row of seedlings is not blown up)
LABEL_ROOM = 1.0  # the framed box reaches this share of the trees' height below the ground


def tree_state(world, meters) -> str:
    """One tree's line under its name: alive with its wilt and height, or the day it died."""
    s = world.sim.state
    if not s.alive:
        return f"dead (day {meters.died:.0f})"
    return f"alive, wilt {s.wilt:.2f}, {world.tree.height / METRE:.2f} m"


def front_light(yaw: float = YAW) -> np.ndarray:
    """The direction toward a light behind the viewer of a camera at ``yaw``: up and a little to one side."""
    return sun_direction(yaw + FRONT[0], FRONT[1])


def row_offsets(worlds: list) -> list[np.ndarray]:
    """Where each tree stands in the scene (its world's place on the plot, x and z)."""
    return [np.array([w.position[0], 0.0, w.position[1]], dtype=np.float32) for w in worlds]


class PlotScene:
    """One renderer for all the trees of a plot: ``update`` merges their meshes when any changed, ``render``
    draws them into a viewport, ``bases`` says where each trunk meets the ground on screen."""

    def __init__(self, ctx) -> None:
        self.renderer = TreeRenderer(ctx)
        self._shown: tuple | None = None
        self.camera = OrbitCamera(yaw=YAW, pitch=PITCH)

    def update(self, worlds: list) -> None:
        """Upload the trees as they are now (nothing when none changed since the last call)."""
        key = tuple((id(w.tree.lstring), w.clocks().length_time, w.clocks().girth_time, w.clocks().wilt)
                    for w in worlds)
        if key == self._shown:
            return
        meshes = [w.tree.geometry(w.clocks()).mesh for w in worlds]
        self.renderer.set_tree(merge_trees(meshes, row_offsets(worlds)))
        self._shown = key
        offsets = np.array(row_offsets(worlds))
        spread = float(np.ptp(offsets[:, 0])) if len(offsets) > 1 else 0.0
        self.renderer.radius = max(self.renderer.radius, spread * 0.6 + MIN_HEIGHT)  # ground and shadows for all
        self.renderer._make_ground()

    def frame(self, worlds: list, aspect: float) -> None:
        """Aim the camera at the whole row: every tree, and at least MIN_HEIGHT tall."""
        offsets = np.array(row_offsets(worlds))
        lo = np.minimum(self.renderer.lo, offsets.min(axis=0) - 0.2 * METRE)
        hi = np.maximum(self.renderer.hi, offsets.max(axis=0) + 0.2 * METRE)
        hi[1] = max(float(hi[1]), MIN_HEIGHT)
        lo[1] = -LABEL_ROOM * hi[1]  # (room under the trees for their names and states: see screens/lab.py)
        self.camera.frame_bounds(lo, hi, aspect, fill=0.9)

    def render(self, fbo, worlds: list, size: tuple[int, int], viewport: tuple[int, int, int, int] | None = None,
               sun: np.ndarray | None = None) -> None:
        """Draw the plot into ``fbo`` (in ``viewport``, of ``size``), lit from the front unless ``sun`` is given."""
        self.update(worlds)
        self.frame(worlds, size[0] / size[1])
        self.renderer.render(fbo, self.camera, front_light(self.camera.yaw) if sun is None else sun, size, viewport)

    def bases(self, worlds: list, size: tuple[int, int]) -> np.ndarray:
        """(x, y) window pixels (y down, in a viewport of ``size``) where each tree's trunk meets the ground."""
        return project_points(self.camera, size, np.array(row_offsets(worlds), dtype=float))

    def release(self) -> None:
        """Free the GPU buffers."""
        self.renderer.release_tree()
