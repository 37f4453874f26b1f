"""Growth into lobes (Zhang et al. section 5) and the grown crown written into the L-string.

All vectorised, no loop over nodes: every attractor joins its nearest active node; a node's cluster
is split into ceil(theta_h/t) x ceil(theta_v/t) pieces by the azimuth/elevation span of its
attractors' directions; each piece grows one branch along
    V_A = V_cluster + alpha V_default + beta V_gravity      (alpha 0.8, beta -0.3)
with V_cluster the distance-weighted mean direction, as long as three quarters of the node's distance
to the lobe surface (the paper: proportional to it; half filled flat lobes with pieces too short for a
game's module budget); nodes inside a lobe closer to its surface than ``stop`` stop, their attractors
retire, attractors a new node reaches are used up, and so are those no growth has come closer to for
a few steps (branches circling them). A branch that would leave the lobes once inside is not grown.
The grown skeleton is written as modules by engine/modeling/skeleton.py.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from arbor.engine.geometry.turtle import INITIAL_FRAME, unit
from arbor.engine.lsystem import brackets
from arbor.engine.lsystem.lstring import concat, parse_lstring
from arbor.engine.modeling.crown_style import CrownStyle
from arbor.engine.modeling.lobes import Crossings, Lobe
from arbor.engine.modeling.modeler import DRAWN, F_PARAMS, Modeler
from arbor.engine.modeling.skeleton import Skeleton, skeleton_lstrings

ALPHA, BETA = 0.8, -0.3
FINE = CrownStyle(twig=0.12)  # grow_crown's default style: short pieces (no module budget to mind)
GRAVITY = np.array([0.0, -1.0, 0.0])
STALL = 3  # growth steps without coming closer after which an attractor retires
OUT_REACH = 1.5  # steps: wood outside the lobes farther than this from them does not sprout
SURFACE_SHARE = 0.75  # a piece grows this share of its node's distance to the lobe surface (at most a step)


def _kdtree(points: np.ndarray, **options):
    """scipy's cKDTree of ``points`` (scipy imported here on first use, not when the game starts)."""
    from scipy.spatial import cKDTree

    return cKDTree(points, **options)


def _nearest(points: np.ndarray, targets: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Index of and distance to the nearest target for every point (a k-d tree: O(n log m), not n x m)."""
    if len(targets) == 0 or len(points) == 0:
        return np.zeros(len(points), np.int64), np.full(len(points), np.inf)
    dist, idx = _kdtree(targets, balanced_tree=False, compact_nodes=False).query(points)
    return idx.astype(np.int64), dist


@dataclass(frozen=True)
class LobeGrowth:
    """How :func:`grow_into_lobes` grows (Zhang et al. section 5; lengths in scene units)."""

    t_deg: float = 40.0  # a node's cluster of attractors is split into pieces t degrees across (see above)
    step: float = 0.6  # longest branch piece
    kill: float = 0.3  # an attractor a new node comes this close to is used up
    stop: float = 0.15  # nodes inside a lobe this close to its surface stop
    iterations: int = 30  # growth steps at most
    max_nodes: int = 8000  # the skeleton's nodes at most (its budget)
    alpha: float = ALPHA  # the weight of a branch's own heading in V_A
    beta: float = BETA  # the weight of gravity in V_A (negative: up)


def grow_into_lobes(skeleton: Skeleton, lobes: list[Lobe], attractors: np.ndarray, how: LobeGrowth = LobeGrowth(),
                    labels: np.ndarray | None = None, rng: np.random.Generator | None = None) -> Skeleton:
    """Seed 004's growth (see module docstring) as ``how`` says, bounded by its ``max_nodes``. A branch that
    would leave the lobes once inside them is not grown, so the crown keeps the drawn silhouette. ``labels``
    says which lobe each attractor belongs to: when the budget binds, the pieces of a step are shared among
    the lobes in proportion to their unfilled volume (see _fair)."""
    t_deg, step, kill, stop, iterations, max_nodes = (how.t_deg, how.step, how.kill, how.stop, how.iterations,
                                                      how.max_nodes)
    remaining = np.asarray(attractors, float)
    labels = np.zeros(len(remaining), np.int64) if labels is None else np.asarray(labels, np.int64)
    rng = np.random.default_rng(0) if rng is None else rng
    count0 = np.maximum(np.bincount(labels, minlength=len(lobes)), 1)
    volume = np.array([max(lobe.volume, 1e-12) for lobe in lobes])
    surface = _kdtree(np.concatenate([lobe.vertices for lobe in lobes]))
    crossings = Crossings(lobes)
    inside = crossings.inside(skeleton.position) >= 0
    # wood far outside every lobe does not sprout (a drawn branch running past a crown grew a comb of
    # bare twigs toward it); a lobe no wood is near is reached by the axis grown to it (see _bridged)
    near = inside | (surface.query(skeleton.position)[0] <= OUT_REACH * step)
    if (skeleton.active & near).any():
        skeleton.active = skeleton.active & near
    deep = np.zeros(len(skeleton.parent), bool)  # the branch has been well inside a lobe
    start_nodes, grown_by = len(skeleton.parent), np.zeros(len(lobes), np.int64)  # new nodes of each lobe
    t = np.radians(t_deg)
    owner_local = None
    best, stale = np.full(len(remaining), np.inf), np.zeros(len(remaining), np.int64)
    for iteration in range(iterations):
        active = np.flatnonzero(skeleton.active)
        if len(remaining) == 0 or len(active) == 0 or len(skeleton.parent) >= max_nodes:
            break
        if owner_local is None:
            owner_local, _ = _nearest(remaining, skeleton.position[active])
        to_surface = surface.query(skeleton.position[active])[0]
        deep[active] |= inside[active] & (to_surface > 2 * stop)
        # only nodes inside a lobe stop at its surface, once their branch has been well inside it (a
        # branch entering through the surface keeps going), and the first nodes always sprout
        growing = (to_surface > stop) | ~inside[active] | ~deep[active] | (iteration == 0)
        keep = growing[owner_local]  # attractors of stopped nodes retire
        remaining, owner_local, labels = remaining[keep], owner_local[keep], labels[keep]
        best, stale = best[keep], stale[keep]
        skeleton.active[active] = False
        if len(remaining) == 0:
            break
        nodes, directions, lengths, lobe_of = _grow_pieces(skeleton, remaining, active, owner_local, to_surface, t,
                                                         step, labels, how)
        new_pos = skeleton.position[nodes] + directions * lengths[:, None]
        new_inside = crossings.inside(new_pos) >= 0
        stays = new_inside | ~inside[nodes]
        room = max_nodes - len(skeleton.parent)
        unfilled = volume * np.bincount(labels, minlength=len(lobes)) / count0
        allowed = _quota(volume, grown_by, np.bincount(labels, minlength=len(lobes)) > 0, max_nodes - start_nodes)
        chosen = _fair(_capped(np.flatnonzero(stays), lobe_of, allowed), lobe_of, unfilled, room, rng)
        grown_by += np.bincount(lobe_of[chosen], minlength=len(lobes))
        nodes, directions, new_pos, new_inside = nodes[chosen], directions[chosen], new_pos[chosen], new_inside[chosen]
        if len(nodes) == 0:
            break
        inside = np.concatenate([inside, new_inside])
        deep = np.concatenate([deep, deep[nodes]])
        skeleton.position = np.concatenate([skeleton.position, new_pos])
        skeleton.parent = np.concatenate([skeleton.parent, nodes])
        skeleton.heading = np.concatenate([skeleton.heading, directions])
        skeleton.active = np.concatenate([skeleton.active, np.ones(len(nodes), bool)])
        owner_local, reach = _nearest(remaining, new_pos)  # the new nodes are the next active set
        # an attractor the growth has not come closer to for STALL steps is one the branches circle
        # around without reaching (pieces overshoot the kill distance): it retires
        stale = np.where(reach < best - 1e-9, 0, stale + 1)
        best = np.minimum(best, reach)
        far = (reach > kill) & (stale < STALL)
        remaining, owner_local, labels = remaining[far], owner_local[far], labels[far]
        best, stale = best[far], stale[far]
    return skeleton


def _quota(volume: np.ndarray, grown_by: np.ndarray, growing: np.ndarray, total: int) -> np.ndarray:
    """How many more pieces each lobe may grow: the node budget ``total`` less what the lobes that are done
    (``growing`` False: no attractors left) used, shared among the growing ones by volume, less what each
    has grown. A lobe near much wood sprouts many pieces every step and, shared only when the budget
    binds, had used most of it before a lobe reached late by its bridging axis began (six small lobes
    round a tree: 63 % and 66 % filled beside 91 %)."""
    if not growing.any():
        return np.zeros(len(volume), np.int64)
    left = total - int(grown_by[~growing].sum())
    share = np.where(growing, left * volume / float(volume[growing].sum()), 0.0)
    return np.maximum(np.floor(share).astype(np.int64) - grown_by, 0)


def _capped(candidates: np.ndarray, lobe_of: np.ndarray, allowed: np.ndarray) -> np.ndarray:
    """The first ``allowed[lobe]`` candidate pieces of each lobe, in growth order."""
    lobe = lobe_of[candidates]
    order = np.argsort(lobe, kind="stable")
    starts = np.searchsorted(lobe[order], np.arange(len(allowed)))
    rank = np.empty(len(candidates), np.int64)
    rank[order] = np.arange(len(candidates)) - starts[lobe[order]]
    return candidates[rank < allowed[lobe]]


def _fair(candidates: np.ndarray, lobe_of: np.ndarray, unfilled: np.ndarray, room: int,
          rng: np.random.Generator) -> np.ndarray:
    """The candidate pieces to grow within ``room``: all of them when they fit; else each lobe gets
    a share of the room in proportion to its unfilled volume (what is left over goes to lobes with more
    candidates), taken in growth order among its candidates (a random pick measured worse: it thins
    every branch instead of finishing some), so no lobe starves another. ``rng`` is kept for callers."""
    if len(candidates) <= room:
        return candidates
    if room <= 0:
        return candidates[:0]
    lobe = lobe_of[candidates]
    wanted = np.bincount(lobe, minlength=len(unfilled))
    share = np.zeros(len(unfilled), np.int64)
    left, open_ = room, wanted > 0
    while left > 0 and open_.any():  # water-filling: a lobe never gets more than it asks for
        weight = np.where(open_, np.maximum(unfilled, 1e-12), 0.0)
        give = np.minimum(np.floor(left * weight / weight.sum()).astype(np.int64), wanted - share)
        if give.sum() == 0:
            give[np.argmax(np.where(open_, wanted - share, -1))] = 1
        share += give
        left -= int(give.sum())
        open_ = share < wanted
    order = np.arange(len(candidates))
    rank = np.empty(len(candidates), np.int64)
    by_lobe = order[np.argsort(lobe[order], kind="stable")]
    starts = np.searchsorted(lobe[by_lobe], np.arange(len(unfilled)))
    rank[by_lobe] = np.arange(len(candidates)) - starts[lobe[by_lobe]]
    return np.sort(candidates[rank < share[lobe]])


def _grow_step(skeleton: Skeleton, points, active, owner_local, to_surface, t, step):
    """One branch per (node, split piece): parent nodes, unit directions V_A, lengths."""
    return _grow_pieces(skeleton, points, active, owner_local, to_surface, t, step, np.zeros(len(points), np.int64))[:3]


def _grow_pieces(skeleton: Skeleton, points, active, owner_local, to_surface, t, step, labels,
                 how: LobeGrowth = LobeGrowth()):
    """_grow_step's pieces and the lobe of each piece's attractors (the lobe most of them belong to)."""
    base = skeleton.position[active][owner_local]
    vec = points - base
    d = np.sqrt(np.einsum("ij,ij->i", vec, vec))
    toward = vec / np.maximum(d, 1e-12)[:, None]
    m = len(active)
    mean = np.stack([np.bincount(owner_local, weights=toward[:, c], minlength=m) for c in range(3)], axis=1)
    # azimuths relative to the cluster's own mean, so a cluster that straddles +-180 deg is not split in
    # two (a cluster all round its node, with no mean direction, keeps absolute azimuths)
    level = np.hypot(mean[:, 0], mean[:, 2]) < 1e-12
    mx, mz = np.where(level, 1.0, mean[:, 0])[owner_local], np.where(level, 0.0, mean[:, 2])[owner_local]
    az = np.arctan2(toward[:, 2] * mx - toward[:, 0] * mz, toward[:, 0] * mx + toward[:, 2] * mz)
    el = np.arcsin(np.clip(toward[:, 1], -1.0, 1.0))
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
    directions = unit(v_cluster + how.alpha * skeleton.heading[nodes] + how.beta * GRAVITY)
    lengths = np.minimum(step, SURFACE_SHARE * to_surface[node_local] + 0.02)
    votes = np.zeros((len(keys), int(labels.max()) + 1))
    np.add.at(votes, (group, labels), 1.0)
    return nodes, directions, lengths, np.argmax(votes, axis=1)


def grow_crown(modeler: Modeler, lobes: list[Lobe], rng: np.random.Generator, per_lobe: int = 1500,
               max_nodes: int = 6000, tip: str = "", style: CrownStyle = FINE) -> int:
    """Grow the modeled tree into ``lobes`` (Zhang et al. section 5) and commit the branches to its
    L-string (undoable). Every node of the tree, drawn or grown, may grow toward the attractors of the
    lobes (each attractor joins its nearest node), so every lobe fills from the branches nearest to it;
    a lobe with no wood near it is first reached by an axis grown straight to it from the nearest node
    (where nothing is drawn yet, a trunk from the base into the lowest lobe). When ``max_nodes`` binds,
    the lobes share it by unfilled volume. ``tip`` ends every new branch (a leaf in the game). Branch
    pieces are ``style.twig`` of a lobe's size long, so a crown looks alike at any scale; ``style`` also
    gives the fork angle, straightness and rise (engine/modeling/crown_style.py). Returns the number of
    branch pieces added."""
    inside = [lobe.sample_inside(per_lobe, rng) for lobe in lobes]
    attractors = np.concatenate([lobe.vertices for lobe in lobes] + inside)
    labels = np.concatenate([np.full(len(lobe.vertices), k) for k, lobe in enumerate(lobes)]
                            + [np.full(len(p), k) for k, p in enumerate(inside)]).astype(np.int64)
    step = style.twig * float(np.mean([np.ptp(lobe.vertices, axis=0).max() for lobe in lobes]))
    size = step / style.twig
    kill = step / 2 if style.reach is None else style.reach * size
    how = LobeGrowth(t_deg=style.fork, step=step, kill=kill, stop=step / 4, alpha=style.straight, beta=-style.rise)
    segs = modeler.segments() if len(modeler.lstring) else None
    if segs is None or len(segs) == 0:  # nothing drawn yet: a trunk from the base into the lowest lobe
        lowest = min(lobes, key=lambda lobe: lobe.vertices[:, 1].min())
        entry = lowest.vertices.mean(axis=0)
        entry[1] = lowest.vertices[:, 1].min() + 0.2 * np.ptp(lowest.vertices[:, 1])
        pieces = max(1, int(np.ceil(np.linalg.norm(entry) / step)))
        start = _bridged(Skeleton.from_trunk(np.linspace(np.zeros(3), entry, pieces + 1)), lobes, step)
        grown = grow_into_lobes(start, lobes, attractors, replace(how, max_nodes=max(max_nodes, len(start.parent))),
                                labels, rng)
        crown = skeleton_lstrings(grown, np.array([0]), INITIAL_FRAME[None], tip=_tip(tip))[0]
        kept = modeler.lstring  # modules that draw nothing yet (a new sapling's apex) stay
        modeler.commit(concat(_OPEN, crown, _CLOSE, kept) if len(kept) else crown)
        return len(grown.parent) - 1
    m = len(segs)
    start = _bridged(Skeleton(segs.end.copy(), segs.parent.copy(), segs.frame[:, :, 0].copy(), np.ones(m, bool)),
                     lobes, step)
    grown = grow_into_lobes(start, lobes, attractors, replace(how, max_nodes=m + max_nodes), labels, rng)
    if len(grown.parent) == m:
        return 0
    modeler.commit(_graft(modeler.lstring, segs, grown, tip))
    return len(grown.parent) - m


def _bridged(skeleton: Skeleton, lobes: list[Lobe], step: float) -> Skeleton:
    """The skeleton with a straight axis grown to every lobe that no node is in (a node just outside a
    lobe, in a neighbouring lobe, cannot grow into it: a branch never leaves the lobe it is in, so the
    top one of six lobes round a tree filled 28 %, with the axis 86 %):
    from the node nearest to the lobe to a point a quarter of the way from the lobe's nearest surface
    point to its centre, in pieces of about ``step``; only the axis' tip grows on (an empty lobe far from
    the wood is filled from its own entry, not starved by the crown next to it)."""
    for lobe in lobes:
        pos = skeleton.position
        gap, near = _kdtree(lobe.vertices).query(pos)
        if lobe.contains(pos).any():
            continue
        node = int(np.argmin(gap))
        surface_point = lobe.vertices[near[node]]
        entry = surface_point + 0.25 * (lobe.vertices.mean(axis=0) - surface_point)
        pieces = max(1, int(np.ceil(np.linalg.norm(entry - pos[node]) / step)))
        chain = np.linspace(pos[node], entry, pieces + 1)[1:]
        n = len(skeleton.parent)
        heading = np.broadcast_to(unit(entry - pos[node]), chain.shape)
        parent = np.concatenate([skeleton.parent, [node], n + np.arange(pieces - 1)])
        skeleton = Skeleton(np.concatenate([pos, chain]), parent, np.concatenate([skeleton.heading, heading]),
                            np.concatenate([skeleton.active, np.arange(pieces) == pieces - 1]))
    return skeleton


_OPEN, _CLOSE = parse_lstring("["), parse_lstring("]")


def _tip(tip: str):
    """The tip's modules (None for no tip), without brackets round the whole of it: a tip ends its branch,
    so a ']' or the string's end follows it and its own brackets draw nothing (two of every tip's four
    modules in '[&(45)L(1)]': dropped, the same module budget holds 15 % more crown)."""
    if not tip:
        return None
    ls = parse_lstring(tip)
    whole = len(ls) >= 2 and ls.sym[0] == ord("[") and brackets.branch_ends(ls.sym, np.array([1]))[0] == len(ls) - 1
    return ls.select(np.arange(len(ls)) % (len(ls) - 1) != 0) if whole else ls


TWIG = 0.024  # diameter of a crown branch's last piece: twice the species' pipe radius per leaf (TIP
# 0.012 in both), widening toward the tree by the pipe law as the tree's own wood does


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
    for node in range(m, len(parent)):  # parents first
        if parent[node] >= m:
            first[node] = first[parent[node]]
    # the pipe law below a drawn node: the branches leaving it together are no wider than it (their
    # cross-sections sum to at most its own), so the crown never swells or outgrows the drawn wood;
    # grown wood thickens with what it carries (the pipe model counts the crown's tips), so branches
    # leaving it keep their own widths (capped by a young sapling's stem, a crown was invisible twigs)
    roots = m + np.flatnonzero(parent[m:] < m)
    source = grown.parent[roots]
    area = np.bincount(source, weights=raw[roots] ** 2, minlength=m)
    scale = np.ones(len(parent))
    drawn = (ls.sym[segs.module[source]] == DRAWN) & (ls.nparams[segs.module[source]] == F_PARAMS)
    source_d = 2.0 * segs.radius_end[source]
    cap = np.minimum(1.0, source_d / np.sqrt(np.maximum(area[source], 1e-300)))
    scale[roots] = np.where(drawn, cap, 1.0)
    diameters = raw * scale[first]
    sources = np.unique(parent[m:][parent[m:] < m])
    is_tip = np.bincount(segs.parent[segs.parent >= 0], minlength=m)[sources] == 0
    at = segs.module[sources]
    ends = brackets.branch_ends(ls.sym, at)
    parts, last = [], 0
    index = np.arange(len(ls))
    crowns = skeleton_lstrings(detached, sources, segs.frame[sources], diameters, _tip(tip))
    for k in np.argsort(at, kind="stable"):
        pos = int(at[k]) + 1
        crown = crowns[k]
        parts.append(ls.select((index >= last) & (index < pos)))
        if is_tip[k]:  # the crown continues a tip's axis (one smooth joint); what followed the tip on
            rest = ls.select((index >= pos) & (index < ends[k]))  # its branch (buds, leaves, an apex)
            if len(rest):  # stays at the tip in a bracket of its own
                parts += [_OPEN, rest, _CLOSE]
            parts.append(crown)
            last = int(ends[k])
        else:
            parts += [_OPEN, crown, _CLOSE]
            last = pos
    parts.append(ls.select(index >= last))
    return concat(*parts)
