"""What makes the garden a place (issue 47, looks): a ring of edging stones round each tree's foot, a
few low shrubs beside it and a path of stepping stones from tree to tree (from a lone tree, out toward
the viewer). Cheap on purpose: stones are the renderer's ball records (kind 4, one quad each, no
shadow pass) and a shrub is a dome of a dozen leaf cards; a garden of three trees adds about 80 quads.

Everything is placed by the trees' positions and sizes alone (no randomness from outside: the same
garden looks the same at every start) and scaled with the trees, so a seedling is not dwarfed by its
shrubs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from arbor.engine.geometry.instances import LEAF_FLOATS, LeafInstances, TubeInstances
from arbor.game.render.falling import StaticView

EDGING = 9  # stones round a tree's foot
SHRUBS = 3  # beside each tree
SHRUB_CARDS = 12  # leaf cards in a shrub
STEP = 2.4  # between stepping stones, in units of the garden's scale
LONE_PATH = 6  # stepping stones out from a lone tree
# On a software GL (llvmpipe, no multisampling) the scenery is drawn into the backdrop's picture with the
# grass (garden.draw_cover: redrawn when the camera, the light or the trees move), not at every frame, and
# its box (the garden's ground) bounds neither the ground's shadow tests nor the smoothing (garden.placed_boxes):
# a sapling's frame with it drawn every frame was 48.5 ms p50 against 16.3 without (load average 10 on 2
# cores; 25 ms of it smoothing and shadow tests over the box, 5 ms the stones' rock shading), now 10.5
# against 12.0 (same load). False leaves it out on a software GL.
ON_SOFTWARE_GL = True


@dataclass(frozen=True)
class Spot:
    """A tree's place in the garden: its foot (x, z, scene units) and its scale (1: a tree of 15 units,
    1.5 m, tall; a seedling's is smaller, down to 0.1)."""

    x: float
    z: float
    scale: float


def scale_of(height: float) -> float:
    """A tree's scale for its scenery from its height (scene units), in steps of 1.5x (the scenery is
    rebuilt only when a tree crosses a step)."""
    size = min(max(height / 15.0, 0.1), 2.0)
    return float(1.5 ** round(math.log(size, 1.5)))


def scenery_view(spots: list[Spot], toward: tuple[float, float] = (-0.087, 0.996)) -> StaticView:
    """Edging stones, shrubs and stepping stones for trees at ``spots`` (a lone tree's path leads
    along ``toward``, a horizontal unit direction (x, z): by default across the game's first view, yaw 255
    degrees, and a little away; a path toward the viewer put big stones before the camera, whose rock
    shading cost a sapling's frame 5 ms on llvmpipe). The view's box spans the scenery on the ground and
    reaches up to the trees' height, so it moves the scene's centre little (the crown's lighting)."""
    stones, leaves = [], []
    for k, spot in enumerate(spots):
        s, here = spot.scale, np.array([spot.x, spot.z])
        for i in range(EDGING):
            a = 2 * math.pi * (i + 0.3 * _hash(k, i)) / EDGING
            radius = s * (0.38 + 0.14 * _hash(k, i + 20))
            stones.append((*(here + 3.2 * s * np.array([math.cos(a), math.sin(a)])), radius))
        for i in range(SHRUBS):
            a = 2 * math.pi * (i + 0.4 * _hash(k, i + 40)) / SHRUBS + 0.9
            at = here + 7.5 * s * np.array([math.cos(a), math.sin(a)])
            leaves += _shrub(at, s * (1.6 + 0.8 * _hash(k, i + 50)), k * 10 + i)
    pairs = [(spots[i], spots[i + 1]) for i in range(len(spots) - 1)]
    if len(spots) == 1:
        s = spots[0].scale
        far = np.array([spots[0].x, spots[0].z]) + np.asarray(toward) * (4.5 + STEP * LONE_PATH) * s
        pairs = [(spots[0], Spot(float(far[0]), float(far[1]), s))]
    for a, b in pairs:
        stones += _path(a, b, end_ring=len(spots) > 1)
    return _view(np.array(stones, np.float32).reshape(-1, 3),
                 np.array(leaves, np.float32).reshape(-1, LEAF_FLOATS),
                 max((15.0 * spot.scale for spot in spots), default=1.0))


def _hash(k: int, i: int) -> float:
    """A fixed pseudo-random number in [0, 1) for tree ``k``'s ``i``-th choice."""
    return math.modf(abs(math.sin(k * 78.233 + i * 12.9898)) * 43758.5453)[0]


def _path(a: Spot, b: Spot, end_ring: bool) -> list[tuple[float, float, float]]:
    """Stepping stones from outside ``a``'s edging to outside ``b``'s (or to ``b`` itself: a path's end)."""
    start, end = np.array([a.x, a.z]), np.array([b.x, b.z])
    length = float(np.linalg.norm(end - start))
    if length < 1e-6:
        return []
    along, side = (end - start) / length, np.array([-(end - start)[1], (end - start)[0]]) / length
    first, last = 4.5 * a.scale, length - (4.5 * b.scale if end_ring else 0.0)
    scale = 0.5 * (a.scale + b.scale)
    out = []
    for i, d in enumerate(np.arange(first, last, STEP * scale)):
        wobble = (0.5 * (i % 2) - 0.25 + 0.2 * _hash(i, 7)) * scale  # (stones left and right of the line)
        x, z = start + along * d + side * wobble
        out.append((float(x), float(z), scale * (0.62 + 0.12 * _hash(i, 9))))
    return out


def _shrub(centre: np.ndarray, size: float, seed: int) -> list[np.ndarray]:
    """A low dome of SHRUB_CARDS leaf cards ``size`` units high round ``centre`` (x, z) on the ground."""
    rng = np.random.default_rng(seed)
    rows = []
    for _ in range(SHRUB_CARDS):
        a, up = rng.uniform(0, 2 * math.pi), rng.uniform(0.25, 1.0)
        out = np.array([math.cos(a) * math.sqrt(1 - up * up), up, math.sin(a) * math.sqrt(1 - up * up)])
        base = np.array([centre[0], 0.05 * size, centre[1]]) + out * np.array([0.35, 0.2, 0.35]) * size
        axis = out / np.linalg.norm(out)
        normal = np.cross(axis, np.array([-math.sin(a), 0.0, math.cos(a)]))
        row = np.zeros(LEAF_FLOATS, np.float32)
        row[0:3], row[3:6], row[6:9] = base, axis, normal / max(float(np.linalg.norm(normal)), 1e-6)
        row[9], row[10], row[11], row[12] = 0.9 * size, 0.45 * size, 0.0, rng.random()
        rows.append(row)
    return rows


def _view(stones: np.ndarray, leaves: np.ndarray, height: float) -> StaticView:
    """The records as a view; stones as balls (x, z, radius) resting on the ground."""
    data = np.zeros((len(stones), LEAF_FLOATS), np.float32)
    data[:, 0], data[:, 1], data[:, 2] = stones[:, 0], 0.35 * stones[:, 2], stones[:, 1]
    data[:, 4], data[:, 8], data[:, 9] = 1.0, 1.0, 2 * stones[:, 2]
    points = np.concatenate([data[:, 0:3], leaves[:, 0:3]]) if len(leaves) else data[:, 0:3]
    if len(points) == 0:
        points = np.zeros((1, 3), np.float32)
    lo, hi = points.min(axis=0) - 2.0, points.max(axis=0) + 2.0
    lo[1], hi[1] = 0.0, max(float(hi[1]), height)
    return StaticView(TubeInstances.empty(), LeafInstances(leaves), LeafInstances.empty(), lo, hi,
                      stones=LeafInstances(data))
