"""Lobes and growth into them (seed 004 sections 4-5): the crown drawn as a few closed strokes.

Lobe from strokes: closed strokes drawn around the crown at different heights are ordered along the
lobe's axis and given the same number of points by arc-length interpolation; each loop starts at the
point whose barycentric direction (eq. 2) is closest to the previous loop's start; strips join
neighbouring loops and fans close both ends, every triangle wound outwards: a closed manifold.

Growth (all vectorised, no loop over nodes): every attractor joins its nearest active node; a node's
cluster is split into ceil(theta_h/t) x ceil(theta_v/t) pieces by the azimuth/elevation span of its
attractors' directions; each piece grows one branch along
    V_A = V_cluster + alpha V_default + beta V_gravity      (alpha 0.8, beta -0.3)
with V_cluster the distance-weighted mean direction, as long as half the node's distance to the lobe
surface; nodes closer to the surface than ``stop`` stop, their attractors retire, and attractors a
new node reaches are used up.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

import numpy as np

from engine.history import Undoable
from engine.lstring import concat, parse_lstring
from engine.modeler import Modeler, ModelerSettings, path_modules
from engine.turtle import INITIAL_FRAME

_NO_WIDTH = re.compile(r"!\([^)]*\)")
ALPHA, BETA = 0.8, -0.3
GRAVITY = np.array([0.0, -1.0, 0.0])


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.maximum(np.linalg.norm(v, axis=-1, keepdims=True), 1e-12)


def resample_loop(points: np.ndarray, count: int) -> np.ndarray:
    """A closed stroke with ``count`` points evenly spaced along its length."""
    closed = np.concatenate([points, points[:1]])
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(closed, axis=0), axis=1))])
    t = np.linspace(0.0, s[-1], count, endpoint=False)
    return np.stack([np.interp(t, s, closed[:, c]) for c in range(3)], axis=1)


def barycentric_directions(loop: np.ndarray) -> np.ndarray:
    """Eq. 2: for each point p_i, normalize(sum over k != i of (p_k - p_i))."""
    return _unit(loop.sum(axis=0)[None, :] - len(loop) * loop)


@dataclass(eq=False)  # lobes compare by identity (their arrays have no single truth value)
class Lobe:
    """A closed triangle mesh around part of the crown: ``rings`` stitched strokes of ``ring_size``
    points each (the first vertices, ring by ring), then the two cap centres."""

    vertices: np.ndarray
    faces: np.ndarray
    ring_size: int = 0

    def transformed(self, move=(0.0, 0.0, 0.0), scale: float = 1.0, turn_deg: float = 0.0) -> Lobe:
        """Moved, scaled about its centre and turned about the vertical through it (lobe editing)."""
        centre = self.vertices.mean(axis=0)
        a = np.radians(turn_deg)
        rot = np.array([[np.cos(a), 0.0, np.sin(a)], [0.0, 1.0, 0.0], [-np.sin(a), 0.0, np.cos(a)]])
        moved = (self.vertices - centre) @ rot.T * scale + centre + np.asarray(move, float)
        return Lobe(moved, self.faces, self.ring_size)

    def squeezed(self, at, radius: float, amount: float) -> Lobe:
        """A local smooth deformation: surface within ``radius`` of ``at`` pulled towards the lobe's
        centre by ``amount`` (0..1; negative pushes out), fading smoothly to nothing at ``radius``."""
        d = np.linalg.norm(self.vertices - np.asarray(at, float), axis=1)
        w = np.clip(1.0 - (d / radius) ** 2, 0.0, 1.0) ** 2
        centre = self.vertices.mean(axis=0)
        return self._with_rings(self.vertices + (amount * w)[:, None] * (centre - self.vertices))

    def dragged(self, ring: int, index: int, to, width: int = 4) -> Lobe:
        """One stroke point dragged to ``to``; its neighbours along the stroke follow on a smooth
        (quadratic Bezier-like) falloff over ``width`` points each side."""
        n = self.ring_size
        rings = self.vertices[:-2].reshape(-1, n, 3).copy()
        offset = np.asarray(to, float) - rings[ring, index]
        k = np.arange(n)
        steps = np.minimum((k - index) % n, (index - k) % n)
        w = np.clip(1.0 - steps / (width + 1.0), 0.0, 1.0) ** 2
        rings[ring] += w[:, None] * offset
        return self._with_rings(np.concatenate([rings.reshape(-1, 3), self.vertices[-2:]]))

    def _with_rings(self, vertices: np.ndarray) -> Lobe:
        """The lobe with new vertices; cap centres follow their rings, triangles stay wound outwards."""
        vertices = vertices.copy()
        if self.ring_size:
            rings = vertices[:-2].reshape(-1, self.ring_size, 3)
            vertices[-2], vertices[-1] = rings[0].mean(axis=0), rings[-1].mean(axis=0)
        return Lobe(vertices, _wind_outwards(vertices, self.faces), self.ring_size)

    def contains(self, points: np.ndarray) -> np.ndarray:
        """True for points inside the lobe."""
        return Crossings([self]).inside(points) == 0

    def sample_inside(self, count: int, rng: np.random.Generator) -> np.ndarray:
        """``count`` points uniformly inside (rejection sampling in the bounding box)."""
        lo, hi = self.vertices.min(axis=0), self.vertices.max(axis=0)
        found: list[np.ndarray] = []
        for _ in range(64):
            cand = rng.uniform(lo, hi, (max(2 * count, 64), 3))
            found.append(cand[self.contains(cand)])
            if sum(len(f) for f in found) >= count:
                break
        return np.concatenate(found)[:count]


@dataclass
class LobeEditor(Undoable):
    """The crown's lobes while they are being drawn and edited, with undo and redo."""

    HISTORY_OF = "lobes"

    lobes: list[Lobe] = field(default_factory=list)
    undo_stack: list[list[Lobe]] = field(default_factory=list)
    redo_stack: list[list[Lobe]] = field(default_factory=list)

    def set(self, index: int, lobe: Lobe | None) -> None:
        """Replace lobe ``index`` (``len(lobes)`` adds one, None removes it), undoably."""
        lobes = list(self.lobes)
        if lobe is None:
            del lobes[index]
        elif index == len(lobes):
            lobes.append(lobe)
        else:
            lobes[index] = lobe
        self.commit(lobes)


class Crossings:
    """Inside test for a set of lobes by the parity of crossings along a ray in +x, done as a 2D
    point-in-triangle test in the y-z plane (vectorised over points and all lobes' triangles)."""

    def __init__(self, lobes: list[Lobe]) -> None:
        tri = np.concatenate([lobe.vertices[lobe.faces] for lobe in lobes])
        self.lobe = np.repeat(np.arange(len(lobes)), [len(lobe.faces) for lobe in lobes])
        self.count = len(lobes)
        self.p0 = tri[:, 0]
        self.e1, self.e2 = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
        det = self.e1[:, 1] * self.e2[:, 2] - self.e1[:, 2] * self.e2[:, 1]
        ok = np.abs(det) > 1e-15  # triangles seen edge-on from the ray are never crossed
        self.inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
        self.tri_lo, self.tri_hi = tri.min(axis=1), tri.max(axis=1)
        self.tri_lo[~ok] = np.inf
        self.lo, self.hi = tri.min(axis=(0, 1)), tri.max(axis=(0, 1))
        self.nudge = np.array([3.7e-9, 7.1e-9]) * max(float(np.max(self.hi - self.lo)), 1e-6)

    def inside(self, points: np.ndarray) -> np.ndarray:
        """Index of a lobe containing each point, -1 for points outside all of them."""
        which = np.full(len(points), -1, np.int64)
        rows = np.flatnonzero(np.all((points >= self.lo) & (points <= self.hi), axis=1))
        for start in range(0, len(rows), 1024):
            chunk = rows[start : start + 1024]
            # a tiny odd offset keeps the ray off shared edges and vertices (points on a ring's plane)
            y, z = points[chunk, 1:2] + self.nudge[0], points[chunk, 2:3] + self.nudge[1]
            near = ((y >= self.tri_lo[:, 1]) & (y <= self.tri_hi[:, 1])
                    & (z >= self.tri_lo[:, 2]) & (z <= self.tri_hi[:, 2]))
            p, t = np.nonzero(near)  # only triangles whose y-z box holds the point can be crossed
            dy, dz = y[p, 0] - self.p0[t, 1], z[p, 0] - self.p0[t, 2]
            u = (dy * self.e2[t, 2] - dz * self.e2[t, 1]) * self.inv[t]
            v = (dz * self.e1[t, 1] - dy * self.e1[t, 2]) * self.inv[t]
            x = self.p0[t, 0] + u * self.e1[t, 0] + v * self.e2[t, 0]
            hit = (u >= 0) & (v >= 0) & (u + v <= 1) & (x > points[chunk[p], 0])
            crossings = np.bincount(p[hit] * self.count + self.lobe[t[hit]], minlength=len(chunk) * self.count)
            odd = crossings.reshape(len(chunk), self.count) % 2 == 1
            which[chunk] = np.where(odd.any(axis=1), np.argmax(odd, axis=1), -1)
        return which


def lobe_from_loops(loops: list[np.ndarray], points_per_loop: int = 32) -> Lobe:
    """Stitch two or more closed strokes into a closed lobe mesh (see module docstring)."""
    if len(loops) < 2:
        raise ValueError("a lobe needs at least two closed strokes")
    centers = np.array([np.asarray(loop, float).mean(axis=0) for loop in loops])
    span = centers.max(axis=0) - centers.min(axis=0)
    axis = np.eye(3)[int(np.argmax(span))] if span.max() > 1e-9 else np.array([0.0, 1.0, 0.0])
    order = np.argsort(centers @ axis)
    rings = [_counter_clockwise(resample_loop(np.asarray(loops[i], float), points_per_loop), axis) for i in order]
    for k in range(1, len(rings)):  # eq. 2: start where the barycentric directions agree best
        start = barycentric_directions(rings[k - 1])[0]
        rings[k] = np.roll(rings[k], -int(np.argmax(barycentric_directions(rings[k]) @ start)), axis=0)
    n, i = points_per_loop, np.arange(points_per_loop)
    verts = np.concatenate([*rings, [rings[0].mean(axis=0), rings[-1].mean(axis=0)]])
    faces = []
    for k in range(len(rings) - 1):
        a, b, c, d = k * n + i, k * n + (i + 1) % n, (k + 1) * n + i, (k + 1) * n + (i + 1) % n
        faces += [np.stack([a, b, c], 1), np.stack([b, d, c], 1)]
    bottom, top, last = len(verts) - 2, len(verts) - 1, (len(rings) - 1) * n
    faces.append(np.stack([np.full(n, bottom), (i + 1) % n, i], 1))
    faces.append(np.stack([np.full(n, top), last + i, last + (i + 1) % n], 1))
    return Lobe(verts, _wind_outwards(verts, np.concatenate(faces).astype(np.int64)), points_per_loop)


def _counter_clockwise(ring: np.ndarray, axis: np.ndarray) -> np.ndarray:
    c = ring.mean(axis=0)
    normal = np.cross(ring - c, np.roll(ring, -1, axis=0) - c).sum(axis=0)
    return ring if normal @ axis > 0 else ring[::-1].copy()


def _wind_outwards(verts: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Flip any triangle whose normal points towards the lobe's centre (lobes are star-shaped)."""
    tri = verts[faces]
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    inward = np.einsum("ij,ij->i", normal, tri.mean(axis=1) - verts.mean(axis=0)) < 0
    faces = faces.copy()
    faces[inward] = faces[inward][:, ::-1]
    return faces


@dataclass
class Skeleton:
    """Branch nodes: position, parent (-1 for the root), heading of the branch into the node."""

    position: np.ndarray
    parent: np.ndarray
    heading: np.ndarray
    active: np.ndarray

    @classmethod
    def from_trunk(cls, points: np.ndarray) -> Skeleton:
        """A chain of nodes (a drawn trunk); only its tip grows."""
        points = np.asarray(points, float)
        heading = np.vstack([[0.0, 1.0, 0.0], _unit(np.diff(points, axis=0))])
        active = np.zeros(len(points), bool)
        active[-1] = True
        return cls(points, np.arange(len(points)) - 1, heading, active)


def _nearest(points: np.ndarray, targets: np.ndarray, chunk: int = 4096) -> tuple[np.ndarray, np.ndarray]:
    """Index of and distance to the nearest target for every point."""
    idx = np.empty(len(points), np.int64)
    dist = np.empty(len(points))
    fast = targets.astype(np.float32)  # single precision only ranks candidates; distances are exact
    tt = np.einsum("ij,ij->i", fast, fast)
    for s in range(0, len(points), chunk):
        p = points[s : s + chunk]
        k = np.argmin(tt[None] - 2.0 * (p.astype(np.float32) @ fast.T), axis=1)  # |p|^2 does not change the order
        idx[s : s + chunk] = k
        dist[s : s + chunk] = np.linalg.norm(p - targets[k], axis=1)
    return idx, dist


def grow_into_lobes(skeleton: Skeleton, lobes: list[Lobe], attractors: np.ndarray, t_deg: float = 40.0,
                    step: float = 0.6, kill: float = 0.3, stop: float = 0.15, iterations: int = 30,
                    max_nodes: int = 8000) -> Skeleton:
    """Seed 004's growth (see module docstring), bounded by ``max_nodes``. A branch that would leave
    the lobes once inside them is not grown, so the crown keeps the drawn silhouette."""
    remaining = np.asarray(attractors, float)
    surface = np.concatenate([lobe.vertices for lobe in lobes])
    crossings = Crossings(lobes)
    inside = crossings.inside(skeleton.position) >= 0
    t = np.radians(t_deg)
    owner_local = None
    for iteration in range(iterations):
        active = np.flatnonzero(skeleton.active)
        if len(remaining) == 0 or len(active) == 0 or len(skeleton.parent) >= max_nodes:
            break
        if owner_local is None:
            owner_local, _ = _nearest(remaining, skeleton.position[active])
        _, to_surface = _nearest(skeleton.position[active], surface)
        # only nodes inside a lobe stop at its surface, and the first nodes always sprout
        growing = (to_surface > stop) | ~inside[active] | (iteration == 0)
        keep = growing[owner_local]  # attractors of stopped nodes retire
        remaining, owner_local = remaining[keep], owner_local[keep]
        skeleton.active[active] = False
        if len(remaining) == 0:
            break
        nodes, directions, lengths = _grow_step(skeleton, remaining, active, owner_local, to_surface, t, step)
        new_pos = skeleton.position[nodes] + directions * lengths[:, None]
        new_inside = crossings.inside(new_pos) >= 0
        stays = new_inside | ~inside[nodes]
        nodes, directions, new_pos, new_inside = nodes[stays], directions[stays], new_pos[stays], new_inside[stays]
        room = max_nodes - len(skeleton.parent)
        nodes, directions, new_pos, new_inside = nodes[:room], directions[:room], new_pos[:room], new_inside[:room]
        if len(nodes) == 0:
            break
        inside = np.concatenate([inside, new_inside])
        skeleton.position = np.concatenate([skeleton.position, new_pos])
        skeleton.parent = np.concatenate([skeleton.parent, nodes])
        skeleton.heading = np.concatenate([skeleton.heading, directions])
        skeleton.active = np.concatenate([skeleton.active, np.ones(len(nodes), bool)])
        owner_local, reach = _nearest(remaining, new_pos)  # the new nodes are the next active set
        remaining, owner_local = remaining[reach > kill], owner_local[reach > kill]
    return skeleton


def _grow_step(skeleton: Skeleton, points, active, owner_local, to_surface, t, step):
    """One branch per (node, split piece): parent nodes, unit directions V_A, lengths."""
    base = skeleton.position[active][owner_local]
    vec = points - base
    d = np.linalg.norm(vec, axis=1)
    unit = vec / np.maximum(d, 1e-12)[:, None]
    az = np.arctan2(unit[:, 2], unit[:, 0])
    el = np.arcsin(np.clip(unit[:, 1], -1.0, 1.0))
    m = len(active)
    lo_az, hi_az = np.full(m, np.inf), np.full(m, -np.inf)
    lo_el, hi_el = np.full(m, np.inf), np.full(m, -np.inf)
    np.minimum.at(lo_az, owner_local, az)
    np.maximum.at(hi_az, owner_local, az)
    np.minimum.at(lo_el, owner_local, el)
    np.maximum.at(hi_el, owner_local, el)
    nh = np.maximum(np.ceil((hi_az - lo_az) / t), 1).astype(np.int64)
    nv = np.maximum(np.ceil((hi_el - lo_el) / t), 1).astype(np.int64)
    span_az = np.maximum(hi_az - lo_az, 1e-12)[owner_local]
    span_el = np.maximum(hi_el - lo_el, 1e-12)[owner_local]
    ih = np.minimum(((az - lo_az[owner_local]) / span_az * nh[owner_local]).astype(np.int64), nh[owner_local] - 1)
    iv = np.minimum(((el - lo_el[owner_local]) / span_el * nv[owner_local]).astype(np.int64), nv[owner_local] - 1)
    keys, group = np.unique((owner_local * 4096 + ih) * 4096 + iv, return_inverse=True)
    weighted = np.zeros((len(keys), 3))
    np.add.at(weighted, group, unit * d[:, None])
    total = np.bincount(group, weights=d, minlength=len(keys))
    node_local = keys // (4096 * 4096)
    nodes = active[node_local]
    v_cluster = weighted / np.maximum(total, 1e-12)[:, None]
    directions = _unit(v_cluster + ALPHA * skeleton.heading[nodes] + BETA * GRAVITY)
    lengths = np.minimum(step, 0.5 * to_surface[node_local] + 0.02)
    return nodes, directions, lengths


def pipe_diameters(skeleton: Skeleton, root_diameter: float, root: int = 0) -> np.ndarray:
    """Diameter of the piece into every node by the pipe model (area preserving): proportional to the
    square root of the number of tips it carries, ``root_diameter`` at ``root``."""
    tips = (np.bincount(skeleton.parent[skeleton.parent >= 0], minlength=len(skeleton.parent)) == 0).astype(float)
    for node in range(len(tips) - 1, 0, -1):  # children always come after their parents
        if skeleton.parent[node] >= 0:
            tips[skeleton.parent[node]] += tips[node]
    return root_diameter * np.sqrt(tips / max(tips[root], 1.0))


def skeleton_text(skeleton: Skeleton, root: int = 0, frame: np.ndarray = INITIAL_FRAME,
                  diameters: np.ndarray | None = None, tip: str = "") -> str:
    """The skeleton from node ``root`` on, for a turtle standing there with ``frame``, as ordinary
    L-string text: F pieces with turns, side branches in brackets; each piece gets its diameter from
    ``diameters`` (per node), or none (then the pipe model sets the radii); ``tip`` ends every branch
    (e.g. a leaf). Walks each axis
    iteratively; recursion only enters side branches, whose nesting is bounded by the number of
    growth iterations."""
    children: dict[int, list[int]] = {}
    for child, parent in enumerate(skeleton.parent.tolist()):
        if parent >= 0:
            children.setdefault(parent, []).append(child)
    settings = ModelerSettings(density=0.0)

    def piece(a: int, b: int, frame: np.ndarray) -> tuple[str, np.ndarray]:
        if diameters is not None:
            return path_modules(skeleton.position[[a, b]], frame, diameters[b : b + 1], [], settings)
        text, end = path_modules(skeleton.position[[a, b]], frame, np.ones(1), [], settings)
        return _NO_WIDTH.sub("", text), end

    def axis(node: int, frame: np.ndarray) -> str:
        out = []
        while children.get(node):
            first, *sides = children[node]
            for side in sides:
                text, side_frame = piece(node, side, frame)
                out.append("[" + text + axis(side, side_frame) + "]")
            text, frame = piece(node, first, frame)
            out.append(text)
            node = first
        return "".join(out) + tip

    return axis(root, np.array(frame, float))


def lobe_from_outline(outline: np.ndarray, depth: float = 1.0, rings: int = 7) -> Lobe:
    """A lobe from one closed silhouette drawn on a vertical plane (a finger or the mouse): at
    ``rings`` heights the outline's left and right edges give a horizontal ring (an ellipse whose
    depth is ``depth`` times its width), and the rings are stitched like drawn closed strokes."""
    outline = np.asarray(outline, float)
    flat = outline - outline.mean(axis=0)
    across = np.linalg.svd(flat[:, [0, 2]], full_matrices=False)[2][0]  # the plane's horizontal axis
    side = np.array([across[0], 0.0, across[1]])
    normal = np.cross(side, [0.0, 1.0, 0.0])
    closed = np.concatenate([outline, outline[:1]])
    y0, y1 = outline[:, 1].min(), outline[:, 1].max()
    if y1 - y0 < 1e-6:
        raise ValueError("a silhouette needs some height")
    a = np.linspace(0, 2 * np.pi, 32, endpoint=False)[:, None]
    loops = []
    for y in y0 + (y1 - y0) * (np.arange(rings) + 0.5) / rings:
        a_y, b_y = closed[:-1, 1], closed[1:, 1]
        cross = (a_y - y) * (b_y - y) <= 0  # outline pieces that cross this height
        f = (y - a_y[cross]) / np.where(b_y[cross] == a_y[cross], 1.0, b_y[cross] - a_y[cross])
        points = closed[:-1][cross] + f[:, None] * (closed[1:][cross] - closed[:-1][cross])
        along = points @ side
        centre = points[np.argmin(along)] + (along.max() - along.min()) / 2 * side
        radius = max((along.max() - along.min()) / 2, 1e-3)
        loops.append(np.array([centre[0], y, centre[2]]) + radius * (np.cos(a) * side + depth * np.sin(a) * normal))
    return lobe_from_loops(loops)


def grow_crown(modeler: Modeler, lobes: list[Lobe], rng: np.random.Generator, per_lobe: int = 1500,
               max_nodes: int = 6000, tip: str = "", step_fraction: float = 0.12) -> int:
    """Grow the modeled tree into ``lobes`` (seed 004) and commit the branches to its L-string
    (undoable). Growth starts at the drawn tip nearest the lobes, or where nothing is drawn yet at a
    straight trunk from the base into the lowest lobe; ``tip`` ends every new branch (a leaf in the game).
    Branch pieces are ``step_fraction`` of a lobe's size long, so a crown looks alike at any scale.
    Returns the number of branch pieces added."""
    surface = np.concatenate([lobe.vertices for lobe in lobes])
    attractors = np.concatenate([surface] + [lobe.sample_inside(per_lobe, rng) for lobe in lobes])
    centre = surface.mean(axis=0)
    step = step_fraction * float(np.mean([np.ptp(lobe.vertices, axis=0).max() for lobe in lobes]))
    sizes = {"step": step, "kill": step / 2, "stop": step / 4, "max_nodes": max_nodes}
    segs = modeler.segments() if len(modeler.lstring) else None
    if segs is None or len(segs) == 0:  # nothing drawn yet: a trunk from the base into the lowest lobe
        lowest = min(lobes, key=lambda lobe: lobe.vertices[:, 1].min())
        entry = lowest.vertices.mean(axis=0)
        entry[1] = lowest.vertices[:, 1].min() + 0.2 * np.ptp(lowest.vertices[:, 1])
        grown = grow_into_lobes(Skeleton.from_trunk(np.stack([np.zeros(3), entry])), lobes, attractors, **sizes)
        text = skeleton_text(grown, tip=tip)
        kept = modeler.lstring  # modules that draw nothing yet (a new sapling's apex) stay
        modeler.commit(concat(parse_lstring(f"[{text}]"), kept) if len(kept) else parse_lstring(text))
        return len(grown.parent) - 1
    tips = np.setdiff1d(np.arange(len(segs)), segs.parent)
    k = int(tips[np.argmin(np.linalg.norm(segs.end[tips] - centre, axis=1))])
    heading = segs.frame[k][:, 0]
    start = Skeleton(np.stack([segs.start[k], segs.end[k]]), np.array([-1, 0]), np.stack([heading, heading]),
                     np.array([False, True]))
    grown = grow_into_lobes(start, lobes, attractors, **sizes)
    if len(grown.parent) == 2:
        return 0
    diameters = pipe_diameters(grown, 2.0 * float(segs.radius_end[k]), root=1)
    body = "[" + skeleton_text(grown, root=1, frame=segs.frame[k], diameters=diameters, tip=tip) + "]"
    module = int(segs.module[k])
    index = np.arange(len(modeler.lstring))
    new = concat(modeler.lstring.select(index <= module), parse_lstring(body), modeler.lstring.select(index > module))
    modeler.commit(new)
    return len(grown.parent) - 2
