"""Growth into lobes (seed 004 section 5) and the grown crown written into the L-string.

All vectorised, no loop over nodes: every attractor joins its nearest active node; a node's cluster
is split into ceil(theta_h/t) x ceil(theta_v/t) pieces by the azimuth/elevation span of its
attractors' directions; each piece grows one branch along
    V_A = V_cluster + alpha V_default + beta V_gravity      (alpha 0.8, beta -0.3)
with V_cluster the distance-weighted mean direction, as long as half the node's distance to the lobe
surface; nodes inside a lobe closer to its surface than ``stop`` stop, their attractors retire, and
attractors a new node reaches are used up. A branch that would leave the lobes once inside is not
grown.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from arbor.engine.geometry.turtle import INITIAL_FRAME, unit
from arbor.engine.lsystem import brackets
from arbor.engine.lsystem.lstring import concat, parse_lstring
from arbor.engine.lsystem.text import format_number
from arbor.engine.modeling.lobes import Crossings, Lobe
from arbor.engine.modeling.modeler import Modeler

ALPHA, BETA = 0.8, -0.3
GRAVITY = np.array([0.0, -1.0, 0.0])


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
        heading = np.vstack([[0.0, 1.0, 0.0], unit(np.diff(points, axis=0))])
        active = np.zeros(len(points), bool)
        active[-1] = True
        return cls(points, np.arange(len(points)) - 1, heading, active)


def _nearest(points: np.ndarray, targets: np.ndarray, chunk: int = 8192) -> tuple[np.ndarray, np.ndarray]:
    """Index of and distance to the nearest target for every point."""
    idx = np.empty(len(points), np.int64)
    dist = np.empty(len(points))
    fast = -2.0 * targets.astype(np.float32)  # single precision only ranks candidates; distances are exact
    tt = 0.25 * np.einsum("ij,ij->i", fast, fast)
    points32 = points.astype(np.float32)
    for s in range(0, len(points), chunk):
        scores = points32[s : s + chunk] @ fast.T
        scores += tt  # |p|^2 - 2 p.q + |q|^2 without the |p|^2, which does not change the order
        k = np.argmin(scores, axis=1)
        idx[s : s + chunk] = k
        gap = points[s : s + chunk] - targets[k]
        dist[s : s + chunk] = np.sqrt(np.einsum("ij,ij->i", gap, gap))
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
    deep = np.zeros(len(skeleton.parent), bool)  # the branch has been well inside a lobe
    t = np.radians(t_deg)
    owner_local = None
    for iteration in range(iterations):
        active = np.flatnonzero(skeleton.active)
        if len(remaining) == 0 or len(active) == 0 or len(skeleton.parent) >= max_nodes:
            break
        if owner_local is None:
            owner_local, _ = _nearest(remaining, skeleton.position[active])
        _, to_surface = _nearest(skeleton.position[active], surface)
        deep[active] |= inside[active] & (to_surface > 2 * stop)
        # only nodes inside a lobe stop at its surface, once their branch has been well inside it (a
        # branch entering through the surface keeps going), and the first nodes always sprout
        growing = (to_surface > stop) | ~inside[active] | ~deep[active] | (iteration == 0)
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
        deep = np.concatenate([deep, deep[nodes]])
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
    d = np.sqrt(np.einsum("ij,ij->i", vec, vec))
    toward = vec / np.maximum(d, 1e-12)[:, None]
    m = len(active)
    mean = np.stack([np.bincount(owner_local, weights=toward[:, c], minlength=m) for c in range(3)], axis=1)
    mean_az = np.arctan2(mean[:, 2], mean[:, 0])  # azimuths relative to the cluster's own mean, so a
    az = np.angle(np.exp(1j * (np.arctan2(toward[:, 2], toward[:, 0]) - mean_az[owner_local])))  # cluster
    el = np.arcsin(np.clip(toward[:, 1], -1.0, 1.0))  # that straddles +-180 deg is not split in two
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
    group = group.ravel()
    weighted = np.stack([np.bincount(group, weights=vec[:, c], minlength=len(keys)) for c in range(3)], axis=1)
    total = np.bincount(group, weights=d, minlength=len(keys))
    node_local = keys // (4096 * 4096)
    nodes = active[node_local]
    v_cluster = weighted / np.maximum(total, 1e-12)[:, None]
    directions = unit(v_cluster + ALPHA * skeleton.heading[nodes] + BETA * GRAVITY)
    lengths = np.minimum(step, 0.5 * to_surface[node_local] + 0.02)
    return nodes, directions, lengths


def skeleton_text(skeleton: Skeleton, root: int = 0, frame: np.ndarray = INITIAL_FRAME,
                  diameters: np.ndarray | None = None, tip: str = "") -> str:
    """The skeleton from node ``root`` on, for a turtle standing there with ``frame``, as ordinary
    L-string text: drawn F pieces (as the modeler writes them) with turns, side branches in brackets;
    each piece gets its diameter from ``diameters`` (per node), or none (then the pipe model sets the
    radii); ``tip`` ends every branch (e.g. a leaf). Frames are solved level by level in numpy; the
    text is assembled with an explicit stack (no recursion, any depth)."""
    pieces = _piece_texts(skeleton, root, np.array(frame, float), diameters)
    order = np.argsort(skeleton.parent, kind="stable")
    starts = np.searchsorted(skeleton.parent[order], np.arange(len(skeleton.parent) + 1))
    out: list[str] = []
    stack: list = [root]
    while stack:
        item = stack.pop()
        if isinstance(item, str):
            out.append(item)
            continue
        kids = order[starts[item] : starts[item + 1]].tolist()
        if not kids:
            out.append(tip)
            continue
        first, *sides = kids
        tokens: list = []
        for side in sides:
            tokens += ["[", pieces[side], side, "]"]
        tokens += [pieces[first], first]
        stack.extend(reversed(tokens))
    return "".join(out)


def _piece_texts(skeleton: Skeleton, root: int, frame: np.ndarray, diameters: np.ndarray | None) -> list[str]:
    """Text of the piece into every node below ``root``: the turn and pitch that aim the turtle (whose
    frame is the end frame of the piece into the parent) at the node, then F(length, start, heading,
    up, variation) as path_modules writes it."""
    parent, pos = skeleton.parent, skeleton.position
    n = len(parent)
    depth = np.full(n, -1)
    depth[root] = 0
    for _ in range(n):  # parents come before children: levels settle in (tree depth) passes
        below = (depth < 0) & (parent >= 0)
        below &= depth[np.maximum(parent, 0)] >= 0
        if not below.any():
            break
        depth[below] = depth[parent[below]] + 1
    ends = np.zeros((n, 3, 3))
    ends[root] = frame
    texts = [""] * n
    for level in range(1, int(depth.max()) + 1):
        nodes = np.flatnonzero(depth == level)
        start = ends[parent[nodes]]
        vec = pos[nodes] - pos[parent[nodes]]
        length = np.linalg.norm(vec, axis=1)
        d = vec / np.maximum(length, 1e-300)[:, None]
        turn = np.degrees(np.arctan2(_dot(d, start[:, :, 1]), _dot(d, start[:, :, 0])))
        turned = np.einsum("kij,kjl->kil", start, _rotations(turn, 2))
        pitch = np.degrees(np.arctan2(-_dot(d, turned[:, :, 2]), _dot(d, turned[:, :, 0])))
        end = np.einsum("kij,kjl->kil", turned, _rotations(pitch, 1))
        up = unit(end[:, :, 2] - _dot(end[:, :, 2], d)[:, None] * d)
        end = np.stack([d, np.cross(up, d), up], axis=2)
        variation = np.degrees(np.arccos(np.clip(_dot(start[:, :, 0], d), -1.0, 1.0)))
        moving = length > 1e-12  # a zero-length piece draws nothing and keeps the frame
        ends[nodes] = np.where(moving[:, None, None], end, start)
        for k, node in enumerate(nodes.tolist()):
            if moving[k]:
                texts[node] = _piece(turn[k], pitch[k], length[k], pos[parent[node]], d[k], up[k], variation[k],
                                     None if diameters is None else diameters[node])
    return texts


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.einsum("ki,ki->k", a, b)


def _rotations(deg: np.ndarray, axis: int) -> np.ndarray:
    """Rotation matrices about the turtle's U (axis 2, turns) or L (axis 1, pitches), one per angle."""
    a = np.radians(deg)
    c, s = np.cos(a), np.sin(a)
    r = np.zeros((len(a), 3, 3))
    i, j = (0, 1) if axis == 2 else (2, 0)
    r[:, axis, axis] = 1.0
    r[:, i, i], r[:, j, j], r[:, i, j], r[:, j, i] = c, c, -s, s
    return r


def _piece(turn, pitch, length, start, d, up, variation, diameter) -> str:
    out = f"+({format_number(float(turn))})" if abs(turn) > 1e-9 else ""
    out += f"&({format_number(float(pitch))})" if abs(pitch) > 1e-9 else ""
    out += f"!({format_number(float(diameter))})" if diameter is not None else ""
    return out + "F(" + ",".join(format_number(float(v)) for v in (length, *start, *d, *up, variation)) + ")"


def grow_crown(modeler: Modeler, lobes: list[Lobe], rng: np.random.Generator, per_lobe: int = 1500,
               max_nodes: int = 6000, tip: str = "", step_fraction: float = 0.12) -> int:
    """Grow the modeled tree into ``lobes`` (seed 004 section 5) and commit the branches to its
    L-string (undoable). Every node of the tree, drawn or grown, may grow toward the attractors of the
    lobes (each attractor joins its nearest node), so every lobe fills from the branches nearest to it;
    where nothing is drawn yet, a straight trunk grows from the base into the lowest lobe first.
    ``tip`` ends every new branch (a leaf in the game). Branch pieces are ``step_fraction`` of a lobe's
    size long, so a crown looks alike at any scale. Returns the number of branch pieces added."""
    surface = np.concatenate([lobe.vertices for lobe in lobes])
    attractors = np.concatenate([surface] + [lobe.sample_inside(per_lobe, rng) for lobe in lobes])
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
    m = len(segs)
    sizes["max_nodes"] = m + max_nodes
    start = Skeleton(segs.end.copy(), segs.parent.copy(), segs.frame[:, :, 0].copy(), np.ones(m, bool))
    grown = grow_into_lobes(start, lobes, attractors, **sizes)
    if len(grown.parent) == m:
        return 0
    modeler.commit(_graft(modeler.lstring, segs, grown, tip))
    return len(grown.parent) - m


TWIG = 0.03  # diameter of a crown branch's last piece (the pipe model widens it toward the tree)


def _graft(ls, segs, grown: Skeleton, tip: str):
    """The L-string with the grown branches inserted where they leave the tree: after the module of the
    segment whose end they start from, each in a bracket (the tree's own axes continue unchanged)."""
    m = len(segs)
    parent = grown.parent.copy()
    parent[:m] = -1  # the tree's own nodes: only their new children are written
    detached = Skeleton(grown.position, parent, grown.heading, grown.active)
    tips = (np.bincount(parent[parent >= 0], minlength=len(parent)) == 0).astype(float)
    for node in range(len(tips) - 1, m - 1, -1):  # children always come after their parents
        if parent[node] >= m:
            tips[parent[node]] += tips[node]
    raw = TWIG * np.sqrt(np.maximum(tips, 1.0))
    first = np.arange(len(parent))  # the first piece of the branch each new node is on
    scale = np.ones(len(parent))
    for node in range(m, len(parent)):  # parents first: a branch is never wider than where it starts
        if parent[node] < m:
            scale[node] = min(1.0, 2.0 * float(segs.radius_end[grown.parent[node]]) / raw[node])
        else:
            first[node] = first[parent[node]]
    diameters = raw * scale[first]
    sources = np.unique(parent[m:][parent[m:] < m])
    is_tip = np.bincount(segs.parent[segs.parent >= 0], minlength=m)[sources] == 0
    at = segs.module[sources]
    ends = brackets.branch_ends(ls.sym, at)
    parts, last = [], 0
    index = np.arange(len(ls))
    for k in np.argsort(at, kind="stable"):
        pos = int(at[k]) + 1
        text = skeleton_text(detached, root=int(sources[k]), frame=segs.frame[sources[k]], diameters=diameters,
                             tip=tip)
        parts.append(ls.select((index >= last) & (index < pos)))
        if is_tip[k]:  # the crown continues a tip's axis (one smooth joint); what followed the tip on
            rest = ls.select((index >= pos) & (index < ends[k]))  # its branch (buds, leaves, an apex)
            if len(rest):  # stays at the tip in a bracket of its own
                parts += [parse_lstring("["), rest, parse_lstring("]")]
            parts.append(parse_lstring(text))
            last = int(ends[k])
        else:
            parts.append(parse_lstring("[" + text + "]"))
            last = pos
    parts.append(ls.select(index >= last))
    return concat(*parts)
