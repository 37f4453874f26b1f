"""Shoot units made: a finished run of bare leafy nodes on one axis becomes one module that keeps its drawing.

A node of the living tree costs about ten modules for as long as it lives: its turns and internode
``+(h)^(u)/(r)I(...)`` and its leaf bracket ``[/(roll)&(pitch)L(...)]`` (a leaf bud ``V`` in winter, opened
again every spring). Once the nodes of a run on one axis are old (``OLD_TAUS`` elongation time constants:
fully grown) and bear nothing but their leaf (no bud, no branch, no blossom: only the run's last node may
carry those), the run becomes one shoot unit (engine/life/form/shoot_units.py: its parameters) between two
sets of turns: ``+(a)^(b)/(c)I(unit...)+(a')^(b')/(c')``. The first set turns the frame before the run onto
the run's chord, the second from the chord back to the frame the run ended in, so everything after the run
(its last node's branches, the rest of the axis) stands exactly where it stood. Where the axis ends after
the run the second set goes; where a node or another run follows, it becomes one set with that one's turns.
The unit is drawn along the chord with its leaves where its nodes stood; a run bent so that a node stands
further than ``STRAIGHT`` of its length from the chord is split in halves until none does. Runs are made in
winter, when every leaf site holds a bud (the units' leaves then open with the spring flush, as the buds
would). A node that may be in a unit but joins no run (its neighbours carry branches or buds) becomes a unit
of one site in the growing season: its internode takes its leaf site, the turns stay (exact: a node costs 4
modules instead of 9). Units are nodes to the next winter's runs: the season's one-site units and a past
winter's units join the nodes beside them (up to about ``MAX_SITES`` sites), so old wood keeps becoming fewer,
longer pieces. Vectorised: a few numpy passes and one turtle pass over the string.
"""

from __future__ import annotations

import numpy as np

from arbor.engine.geometry.turtle import interpret, set_radii
from arbor.engine.life.form import shoot_units
from arbor.engine.life.form.interpret import Clocks, radii, render_view, saturate, turtle_config
from arbor.engine.lsystem import brackets
from arbor.engine.lsystem.lstring import LString

OLD_TAUS = 6.0  # an internode this many elongation time constants old is fully grown (99.75 %)
TAIL_GROUPS = 0  # groups besides its leaf a unit's nodes may carry (a branch's foot stays a node: girth steps)
MAX_SITES = 12  # leaf sites a unit holds (at most this, or a little more where a unit of several sites joins)
STRAIGHT = 0.03  # a unit's nodes stand at most this share of its length from the chord it is drawn along
INTERNODE, LEAF, LEAF_BUD = ord("I"), ord("L"), ord("V")
YAW, PITCH, ROLL, DOWN = ord("+"), ord("^"), ord("/"), ord("&")
UNIT_TURNS = np.array([YAW, PITCH, ROLL], np.uint8)
AXIS_END, FOLD = 1, 2  # what follows a run: the axis' end, or something turned to (_after_runs)
_TURN = np.zeros(256, bool)
_TURN[UNIT_TURNS] = True


def form_units(ls: LString, now: float, const: dict[str, float], runs: bool = True) -> tuple[LString, int]:
    """``ls`` with its old runs of leafy nodes made into shoot units (module docstring), at length time
    ``now`` (``runs`` False: units of one site only, no turtle pass); returns the new string and how many
    modules it saved."""
    out = _runs_made(ls, now, const) if runs else ls
    out = _singles_made(out, now, const)
    return out, len(ls) - len(out)


def _runs_made(ls: LString, now: float, const: dict[str, float]) -> LString:
    """``ls`` with its runs of two or more nodes made into units."""
    nodes = _nodes(ls, now, const)
    if nodes is None:
        return ls
    joins = _joins(nodes)
    if not joins.any():
        return ls
    states = _states(ls, nodes, joins, now, const)
    head, tail = _straight_runs(joins, states)
    if len(head) == 0:
        return ls
    unit, along = _unit_params(ls, nodes, states, head, tail, now, const)
    kind, target = _after_runs(ls, nodes["end"][tail])
    then = np.searchsorted(nodes["node"][head], target)  # a run that follows another: one set of turns between
    then = np.minimum(then, len(head) - 1)
    chained = (kind == FOLD) & (nodes["node"][head][then] == target)
    unit[then[chained], :3] = _frames_between(along[chained], along[then[chained]])
    target[chained] = nodes["start"][head][then[chained]]  # (the turns up to the next run's go)
    kind[chained] = AXIS_END  # (its closing turns are in the next unit's opening ones)
    fold = kind == FOLD
    turns = np.zeros((len(head), 3))  # the turns from the unit's frame to the one what follows it starts in
    turns[fold] = _frames_between(along[fold], states["next_frame"][tail[fold]])
    return _rebuilt(ls, nodes, head, tail, unit, kind, target, turns)


def _after_runs(ls: LString, at: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """What follows runs whose last node's groups end at ``at``, past any turns there (a node's, or an older
    unit's closing ones): AXIS_END (the axis ends: no turns are needed) or FOLD (anything else: one set of
    turns from the unit's frame to the frame that starts in); and per run where that is (``len(ls)`` at the
    string's end)."""
    n = len(ls)
    sym = np.concatenate([ls.sym, np.zeros(1, ls.sym.dtype)])
    npar = np.concatenate([ls.nparams, np.zeros(1, ls.nparams.dtype)])
    cur = np.minimum(at, n)
    for _ in range(16):
        turn = _TURN[sym[cur]] & (npar[cur] == 1) & (cur < n)
        if not turn.any():
            break
        cur = cur + turn
    axis_end = (cur >= n) | (sym[cur] == brackets.CLOSE)
    return np.where(axis_end, AXIS_END, FOLD), cur


def _singles_made(ls: LString, now: float, const: dict[str, float]) -> LString:
    """``ls`` with every other node that may be in a unit made a unit of its own: its internode takes its
    leaf site (no turns change: the unit is the piece itself, its leaf at its end turned as its bracket
    turned it), whatever else it carries (a branch, a bud) stays after it."""
    nodes = _nodes(ls, now, const, units=False)
    if nodes is None or not nodes["ok"].any():
        return ls
    ok = np.flatnonzero(nodes["ok"])
    node, bud = nodes["node"][ok], nodes["leaf_bud"][ok]
    opened = nodes["leaf_open"][ok]
    rolled = ls.sym[opened + 1] == ROLL
    roll = np.where(rolled, ls.params[ls.offsets[np.where(rolled, opened + 1, node)]], 0.0)
    pitch = ls.params[ls.offsets[bud - 1]]
    k = len(ok)
    leaf = np.stack([np.ones(k), np.ones(k), *_unit_leaves(nodes["leaf_state"][ok], now), roll, np.zeros(k), pitch],
                    axis=1)  # pieces, sites, leaves' birth and vigour, share in leaf, roll, roll step, pitch
    delta = np.zeros(len(ls) + 1, np.int64)
    np.add.at(delta, opened, 1)
    np.add.at(delta, brackets.match(ls.sym)[opened] + 1, -1)
    params = np.insert(ls.params, np.repeat(ls.offsets[node] + 5, leaf.shape[1]), leaf.ravel())
    npar = ls.nparams.copy()
    npar[node] = shoot_units.UNIT_PARAMS
    grown = LString.from_arrays(ls.sym, npar, params)
    return grown.select(np.cumsum(delta[:-1]) == 0)


def _nodes(ls: LString, now: float, const: dict[str, float], units: bool = True) -> dict[str, np.ndarray] | None:
    """Every old plain internode (and with ``units``, every old shoot unit) with its turns before it
    and its bracket groups after it: where its turns start, where its groups end, its one bare leaf group
    (open bracket and leaf bud), and whether it may be part of a unit."""
    sym, npar, off, params = ls.sym, ls.nparams, ls.offsets, ls.params
    unit = (sym == INTERNODE) & (npar == shoot_units.UNIT_PARAMS) & units
    node = np.flatnonzero(((sym == INTERNODE) & (npar == 5)) | unit)
    node = node[now - params[off[node]] > OLD_TAUS * const["TAU"]]  # (only old ones may be in a unit)
    if len(node) < 1 + units:
        return None
    single = unit[node]  # a unit: its leaf sites are in it, no leaf group after it
    sites = np.where(single, np.rint(params[off[node] + shoot_units.SITES * single]), 1).astype(np.int64)
    pad = 6
    psym = np.concatenate([sym, np.zeros(pad, sym.dtype)])
    pnpar = np.concatenate([npar, np.zeros(pad, npar.dtype)])
    rolled = (node >= 3) & (psym[node - 1] == ROLL) & (pnpar[node - 1] == 1)
    start = np.where(rolled, node - 3, node - 2)
    ok = start >= 0
    s = np.maximum(start, 0)
    ok &= (psym[s] == YAW) & (pnpar[s] == 1) & (psym[s + 1] == PITCH) & (pnpar[s + 1] == 1)
    match = np.concatenate([brackets.match(sym), np.full(pad, -1)])
    cur = node + 1
    leafy_groups, other_groups = np.zeros(len(node), np.int64), np.zeros(len(node), np.int64)
    leaf_open, leaf_bud = np.full(len(node), -1), np.full(len(node), -1)
    for _ in range(12):
        is_open = psym[cur] == brackets.OPEN
        if not is_open.any():
            break
        c = np.where(is_open, cur, 0)
        close = np.where(is_open, match[c], 0)
        inner = close - c - 1
        a = c + 1
        two = is_open & (inner == 2) & (psym[a] == DOWN) & (pnpar[a] == 1) & _site(psym, pnpar, params, off, a + 1)
        three = is_open & (inner == 3) & (psym[a] == ROLL) & (pnpar[a] == 1) & (psym[a + 1] == DOWN)
        three &= (pnpar[a + 1] == 1) & _site(psym, pnpar, params, off, a + 2)
        leafy = two | three
        leaf_open = np.where(leafy, c, leaf_open)
        leaf_bud = np.where(two, a + 1, np.where(three, a + 2, leaf_bud))
        leafy_groups += leafy
        other_groups += is_open & ~leafy
        cur = np.where(is_open, close + 1, cur)
    ok &= psym[cur] != brackets.OPEN  # (a node with more groups than looked at stays as it is)
    state = _leaf_state(ls, np.maximum(leaf_bud, 0))
    kept = params[off[node] + shoot_units.KEPT * single]
    state[single] = np.where((kept[single] > 0)[:, None], np.stack(
        [params[off[node[single]] + shoot_units.LEAF_BIRTH], params[off[node[single]] + shoot_units.LEAF_SIZE],
         kept[single]], axis=1), [0.0, 1.0, 0.0])
    ok &= np.where(single, (leafy_groups == 0) & ((kept == 0) | (kept == 1)), leafy_groups == 1)
    return {"node": node, "start": start, "end": cur, "ok": ok, "other": other_groups, "leaf_open": leaf_open,
            "leaf_bud": leaf_bud, "order": params[off[node] + 2], "unit": single, "sites": np.maximum(sites, 0),
            "leaf_state": state, "turns_only": _turns_between(ls, np.concatenate([[0], cur[:-1]]), start)}


def _turns_between(ls: LString, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Per pair: whether modules ``lo`` up to ``hi`` are all turns (``+``, ``^``, ``/`` with one parameter; none
    counts too)."""
    turn = _TURN[ls.sym] & (ls.nparams == 1)
    count = np.concatenate([[0], np.cumsum(turn)])
    safe_lo, safe_hi = np.clip(lo, 0, len(ls)), np.clip(hi, 0, len(ls))
    return (hi >= lo) & (count[safe_hi] - count[safe_lo] == hi - lo)


def _site(sym: np.ndarray, npar: np.ndarray, params: np.ndarray, off: np.ndarray, at: np.ndarray) -> np.ndarray:
    """Per index ``at`` (of the padded symbols): a leaf site a unit can take, a leaf bud ``V`` or a leaf on
    the tree that is not falling ``L(birth, vigour, 0)``."""
    bud = (sym[at] == LEAF_BUD) & (npar[at] == 0)
    leaf = (sym[at] == LEAF) & (npar[at] == 3)
    last = len(off) - 1
    falling = params[np.minimum(off[np.minimum(at, last)] + 2 * leaf, len(params) - 1)] if len(params) else 0.0
    return bud | (leaf & (falling == 0))


def _leaf_state(ls: LString, leaf: np.ndarray) -> np.ndarray:
    """Per leaf site (module indices): its leaves' birth, vigour and share in leaf: (birth, vigour, 1) for a
    leaf, (0, 1, 0) for a leaf bud; (k, 3)."""
    on = ls.sym[leaf] == LEAF
    at = ls.offsets[leaf]
    birth = np.where(on, ls.params[np.where(on, at, 0)], 0.0)
    vigour = np.where(on, ls.params[np.where(on, at + 1, 0)], 1.0)
    return np.stack([birth, vigour, on.astype(float)], axis=1)


def _heads(joins: np.ndarray) -> np.ndarray:
    """For every node, the index (in the node list) of the first node of its run."""
    return np.maximum.accumulate(np.where(~joins, np.arange(len(joins)), 0))


def _joins(nodes: dict[str, np.ndarray]) -> np.ndarray:
    """Per node: whether it joins the node before it into a run (both may be in a unit, on one axis, the one
    before bearing nothing but its leaf), about MAX_SITES leaf sites a run."""
    ok, other = nodes["ok"], nodes["other"]
    order = nodes["order"]
    state = nodes["leaf_state"]
    same = np.all(state[1:] == state[:-1], axis=1)  # (their leaves unfold and fall as one)
    joins = ok & (other <= TAIL_GROUPS) & np.concatenate([[False], ok[:-1] & (other[:-1] == 0) & nodes["turns_only"][1:]
                                                          & (order[:-1] == order[1:]) & same])
    sites = nodes["sites"]
    total = np.cumsum(sites)
    head = _heads(joins)
    block = np.maximum(total - (total[head] - sites[head]) - 1, 0) // MAX_SITES  # (a run's sites so far)
    return joins & (block == np.concatenate([[-1], block[:-1]]))


def _states(ls: LString, nodes: dict[str, np.ndarray], joins: np.ndarray, now: float,
            const: dict[str, float]) -> dict[str, np.ndarray]:
    """The turtle's state going into each node's turns, its internode, what follows it, its leaf bud and the
    next node's internode (_after_runs; one pass; rows of the node list, only for the nodes of runs)."""
    member = joins | np.concatenate([joins[1:], [False]])
    rows = np.flatnonzero(member)
    single = nodes["unit"][rows]
    after = _after_runs(ls, nodes["end"][rows])[1]
    where = [nodes["start"][rows], nodes["node"][rows], nodes["node"][rows] + 1,
             np.where(single, nodes["node"][rows], nodes["leaf_bud"][rows]), np.minimum(after, len(ls) - 1)]
    view = render_view(ls, Clocks(now, now, 0.0), const)
    turtle = interpret(view, turtle_config(const), probes=np.concatenate(where))
    probes, segs = turtle.probes, turtle.segments
    set_radii(segs, radii(ls, segs, Clocks(now, now, 0.0), const))
    seg = np.searchsorted(segs.module, nodes["node"])
    r0, r1 = segs.radius[seg], segs.radius_end[seg]
    piece = np.linalg.norm(segs.end[seg] - segs.start[seg], axis=1)
    carries = np.zeros(len(segs) + 1, bool)
    carries[segs.parent[segs.continues]] = True
    parent = np.where(segs.continues[seg], segs.parent[seg], -1)  # the piece whose taper ends at this one
    p = np.maximum(parent, 0)
    below = np.where(parent >= 0, np.linalg.norm(segs.end[p] - segs.start[p], axis=1), 0.0)
    child = np.full(len(segs) + 1, -1)
    child[segs.parent[segs.continues]] = np.flatnonzero(segs.continues)
    k, out = len(rows), {"volume": np.pi * piece * (r0 * r0 + r0 * r1 + r1 * r1) / 3.0, "radius_end": r1,
                         "tapers": carries[seg], "foot": r0, "below": below, "below_foot": segs.radius[p],
                         "seg": seg, "parent_seg": parent, "child_seg": child[seg]}
    for j, name in enumerate(("turns", "node", "after", "leaf", "next")):
        pos, frame = np.zeros((len(joins), 3)), np.zeros((len(joins), 3, 3))
        pos[rows], frame[rows] = probes.position[j * k:(j + 1) * k], probes.frame[j * k:(j + 1) * k]
        out[name], out[name + "_frame"] = pos, frame
    return out


def _straight_runs(joins: np.ndarray, states: dict[str, np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """First and last node (rows of the node list) of every run that becomes a unit: at least two nodes,
    each node's start within STRAIGHT of the run's length from the chord it is drawn along (a run that
    bends more is split in halves until it does not)."""
    joins = joins.copy()
    for _ in range(6):
        head = _heads(joins)
        size = np.bincount(head, minlength=len(joins))
        last = head + size[head] - 1
        a, b = states["node"][head], states["after"][last]
        chord = b - a
        length = np.maximum(np.linalg.norm(chord, axis=1), 1e-12)
        off = np.linalg.norm(np.cross(states["node"] - a, chord), axis=1) / length
        bent = joins & (off > STRAIGHT * length)
        if not bent.any():
            break
        split = np.flatnonzero(np.bincount(head[bent], minlength=len(joins)) > 0)
        joins[split + size[split] // 2] = False
    head = _heads(joins)
    size = np.bincount(head, minlength=len(joins))
    first = np.flatnonzero(size >= 2)
    return first, first + size[first] - 1


def _frames_between(before: np.ndarray, after: np.ndarray) -> np.ndarray:
    """Turns +(a)^(b)/(c) (degrees, (k, 3)) that take turtle frames ``before`` to ``after`` (k, 3, 3; columns
    H, L, U): the turtle turns a frame F to F Rz(a) Ry(-b) Rx(c)."""
    m = np.einsum("kji,kjl->kil", before, after)
    a = np.degrees(np.arctan2(m[:, 1, 0], m[:, 0, 0]))
    b = np.degrees(np.arcsin(np.clip(m[:, 2, 0], -1.0, 1.0)))
    c = np.degrees(np.arctan2(m[:, 2, 1], m[:, 2, 2]))
    return np.stack([a, b, c], axis=1)


def _onto(frames: np.ndarray, heading: np.ndarray) -> np.ndarray:
    """``frames`` turned the shortest way so that their H lies along ``heading`` (unit vectors)."""
    h = frames[:, :, 0]
    axis = np.cross(h, heading)
    sin = np.linalg.norm(axis, axis=1)
    cos = np.einsum("ki,ki->k", h, heading)
    k = axis / np.maximum(sin, 1e-12)[:, None]
    out = np.empty_like(frames)
    for col in range(3):
        v = frames[:, :, col]
        out[:, :, col] = (v * cos[:, None] + np.cross(k, v) * sin[:, None]
                          + k * np.einsum("ki,ki->k", k, v)[:, None] * (1.0 - cos)[:, None])
    return out


def _wrap(deg: np.ndarray) -> np.ndarray:
    return (deg + 180.0) % 360.0 - 180.0


def _unit_params(ls: LString, nodes: dict[str, np.ndarray], states: dict[str, np.ndarray], head: np.ndarray,
                 tail: np.ndarray, now: float, const: dict[str, float]) -> np.ndarray:
    """Per run: its two sets of turns and its unit's 13 parameters, (runs, 19), and the frame the unit is
    drawn in (runs, 3, 3)."""
    node = nodes["node"]
    size = tail - head + 1
    member = np.repeat(head, size) + np.arange(int(size.sum())) - np.repeat(np.cumsum(size) - size, size)
    run = np.repeat(np.arange(len(head)), size)
    r = len(head)
    before, first, last = states["turns_frame"][head], states["node_frame"][head], states["after_frame"][tail]
    chord = states["after"][tail] - states["node"][head]
    length = np.linalg.norm(chord, axis=1)
    along = _onto(first, chord / np.maximum(length, 1e-12)[:, None])
    site_of, i, frame, leaf_pitch = _site_frames(ls, nodes, states, member, run)
    site_run = run[site_of]
    m = np.einsum("kji,kjl->kil", along[site_run], frame)
    roll = np.degrees(np.arctan2(m[:, 1, 0], -m[:, 2, 0]))
    step = _circular_mean(_wrap(np.diff(roll)), site_run[1:], site_run[1:] == site_run[:-1], r)
    roll0 = _circular_mean(_wrap(roll - i * step[site_run]), site_run, np.ones(len(site_run), bool), r)
    sites = np.bincount(site_run, minlength=r)
    pitch = np.bincount(site_run, leaf_pitch, minlength=r) / np.maximum(sites, 1)
    params, off = ls.params, ls.offsets[node[head]]
    order = params[off + 2]
    full = const["IL"] * const["IO"] ** order * saturate(now - params[off], const["TAU"])
    wood = _woods(states, head, tail, np.bincount(run, states["volume"][member], minlength=r), length)
    unit = np.stack([params[off], params[off + 1], order, params[off + 3], wood,
                     length / np.maximum(full, 1e-12), sites.astype(float),
                     *_unit_leaves(nodes["leaf_state"][head], now), roll0, step, pitch], axis=1)
    return np.concatenate([_frames_between(before, along), unit, _frames_between(along, last)], axis=1), along


def _site_frames(ls: LString, nodes: dict[str, np.ndarray], states: dict[str, np.ndarray], member: np.ndarray,
                 run: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Every leaf site of the runs' members (``member``: rows of the node list, ``run``: their run): its
    member (index into ``member``), its number in its run's unit (1, 2, ...), its leaf's frame and pitch: a
    node's as its leaf bracket turns it, a unit's site ``j`` turned ``roll + j x roll step`` about the unit
    and pitched from it (engine/life/form/shoot_units.py)."""
    k = nodes["sites"][member]
    site_of = np.repeat(np.arange(len(member)), k)
    first = np.cumsum(k) - k
    j = np.arange(int(k.sum())) - first[site_of] + 1
    head_first = first[np.searchsorted(run, run)]  # (sites before each member's run)
    i = (first - head_first)[site_of] + j
    unit = nodes["unit"][member][site_of]
    mod = nodes["node"][member][site_of]
    at = np.where(unit, ls.offsets[mod], 0)
    last = len(ls.params) - 1
    roll = ls.params[np.minimum(at + shoot_units.ROLL, last)] + j * ls.params[np.minimum(at + shoot_units.ROLL_STEP,
                                                                                        last)]
    unit_pitch = ls.params[np.minimum(at + shoot_units.LEAF_PITCH, last)]
    turned = shoot_units.turns(shoot_units.turns(states["node_frame"][member][site_of], 0, roll), 1, unit_pitch)
    frame = np.where(unit[:, None, None], turned, states["leaf_frame"][member][site_of])
    bud_pitch = ls.params[ls.offsets[np.maximum(nodes["leaf_bud"][member][site_of] - 1, 0)]]
    return site_of, i.astype(float), frame, np.where(unit, unit_pitch, bud_pitch)


def _wood(volume: np.ndarray, length: np.ndarray, end: np.ndarray, tapers: np.ndarray, below: np.ndarray,
          below_foot: np.ndarray, foot: np.ndarray) -> np.ndarray:
    """The wood cross-section at a unit's foot that keeps its run's wood ``volume`` over ``length``: a frustum
    tapering to the radius ``end`` of the piece after it (a cylinder where nothing continues it), with the
    piece below it (``below`` long, ``below_foot`` its foot radius, 0 long where there is none), whose taper
    ends at the unit's foot (``foot`` before)."""
    end = np.where(tapers, end, 0.0)
    same = ~tapers  # a cylinder: its end is its foot
    a = np.where(same, 3.0 * length, length) + below
    b = length * end + below * below_foot
    c = length * end * end + below * below_foot * below_foot
    target = 3.0 * volume / np.pi + below * (below_foot ** 2 + below_foot * foot + foot ** 2)
    r = (-b + np.sqrt(np.maximum(b * b - 4.0 * a * (c - target), 0.0))) / (2.0 * np.maximum(a, 1e-12))
    return r * r


def _woods(states: dict[str, np.ndarray], head: np.ndarray, tail: np.ndarray, volume: np.ndarray,
           length: np.ndarray) -> np.ndarray:
    """Each unit's foot cross-section (:func:`_wood`), where units follow one another on an axis solved
    together: a unit's taper ends at the next unit's new foot, and a unit below another keeps its own volume
    (a few sweeps settle it)."""
    seg = states["seg"]
    where = np.full(int(seg.max(initial=0)) + 2, -1)
    where[seg[head]] = np.arange(len(head))
    after = where[np.maximum(states["child_seg"][tail], 0)]
    after = np.where(states["child_seg"][tail] >= 0, after, -1)
    tails = np.full(len(where), -1)
    tails[seg[tail]] = np.arange(len(head))
    below_unit = np.where(states["parent_seg"][head] >= 0, tails[np.maximum(states["parent_seg"][head], 0)], -1)
    below = np.where(below_unit >= 0, 0.0, states["below"][head])
    wood = np.zeros(len(head))
    for _ in range(12):
        foot = np.sqrt(wood)
        end = np.where(after >= 0, foot[np.maximum(after, 0)], states["radius_end"][tail])
        wood = _wood(volume, length, end, states["tapers"][tail], below, states["below_foot"][head],
                     states["foot"][head])
        if after.max(initial=-1) < 0:
            break
    return wood


def _unit_leaves(state: np.ndarray, now: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A unit's leaves' birth, vigour and share in leaf from its first site's state (:func:`_leaf_state`):
    a bare site's leaves are born at the next flush (``now`` until then)."""
    leafy = state[:, 2] > 0
    return np.where(leafy, state[:, 0], now), state[:, 1], state[:, 2]


def _circular_mean(deg: np.ndarray, group: np.ndarray, use: np.ndarray, count: int) -> np.ndarray:
    """Per group, the circular mean (degrees) of ``deg`` where ``use``."""
    rad = np.radians(deg[use])
    s = np.bincount(group[use], np.sin(rad), minlength=count)
    c = np.bincount(group[use], np.cos(rad), minlength=count)
    return np.degrees(np.arctan2(s, c))


def _rebuilt(ls: LString, nodes: dict[str, np.ndarray], head: np.ndarray, tail: np.ndarray, unit: np.ndarray,
             kind: np.ndarray, target: np.ndarray, turns: np.ndarray) -> LString:
    """``ls`` with each run's modules (its nodes' turns, internodes and leaf groups) replaced by its unit after
    its opening turns; the turns after the run up to ``target`` go, and where ``kind`` is FOLD one set
    (``turns``) takes the frame from the unit to ``target``."""
    first, last = nodes["start"][head], nodes["node"][tail]
    leaf_open = nodes["leaf_open"][tail][~nodes["unit"][tail]]  # (a unit's leaf is in it)
    leaf_close = brackets.match(ls.sym)[leaf_open]
    fold = kind == FOLD
    delta = np.zeros(len(ls) + 1, np.int64)
    for lo, hi in ((first, last + 1), (leaf_open, leaf_close + 1), (nodes["end"][tail], target)):
        np.add.at(delta, lo, 1)
        np.add.at(delta, hi, -1)
    keep = np.cumsum(delta[:-1]) == 0
    kept = ls.select(keep)
    seen = np.concatenate([[0], np.cumsum(keep)])  # kept modules before each module
    r, nfold = len(head), int(fold.sum())
    block_sym = np.concatenate([UNIT_TURNS, [INTERNODE]]).astype(ls.sym.dtype)
    block_npar = np.array([1, 1, 1, shoot_units.UNIT_PARAMS], dtype=ls.nparams.dtype)
    at = np.concatenate([np.repeat(seen[first], 4), np.repeat(seen[target[fold]], 3)])
    sym = np.insert(kept.sym, at, np.concatenate([np.tile(block_sym, r), np.tile(UNIT_TURNS, nfold)]))
    npar = np.insert(kept.nparams, at, np.concatenate([np.tile(block_npar, r), np.ones(3 * nfold, ls.nparams.dtype)]))
    where = np.concatenate([seen[first], seen[target[fold]]])  # (np.insert keeps equal places in this order)
    param_at = np.where(where < len(kept), kept.offsets[np.minimum(where, max(len(kept) - 1, 0))], len(kept.params))
    count = np.concatenate([np.full(r, 16), np.full(nfold, 3)])
    params = np.insert(kept.params, np.repeat(param_at, count), np.concatenate([unit[:, :16].ravel(),
                                                                               turns[fold].ravel()]))
    return LString.from_arrays(sym, npar, params)
