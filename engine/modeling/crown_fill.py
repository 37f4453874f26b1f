"""A crown within a module budget, and how well it fills its lobes (the measure the modeler is judged by).

``grow_within`` grows the crown and, when the L-string it writes is bigger than the room the budget
leaves, grows it again with longer pieces (fewer nodes fill the lobes), and at last with proportionally
fewer nodes (the lobes share them by volume, see crown.grow_into_lobes). ``lobe_fill`` is the share of
each lobe's volume lying within a tenth of the lobe's size from the wood (any drawn or grown segment).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

import numpy as np
from scipy.spatial import cKDTree

from arbor.engine.geometry.turtle import Segments
from arbor.engine.lsystem.lstring import LString
from arbor.engine.modeling.crown import grow_crown
from arbor.engine.modeling.crown_style import DEFAULT_STYLE, CrownStyle
from arbor.engine.modeling.lobes import Lobe
from arbor.engine.modeling.modeler import Modeler

MAX_CROWN_MODULES = 24000  # one crown's bound even without a tree budget
LONGER = 1.0  # a try over the budget by a factor f is grown again with pieces (and reach) f**LONGER as long
MIN_LONGER = 0.03  # ... and at least this much longer (a try just over the budget went to the node bound)
MAX_STEP = 0.45  # of a lobe's size: the longest pieces
FILL_REACH = 0.1  # of a lobe's size: a place this close to the wood counts as filled


def grow_within(base: LString, lobes: list[Lobe], room: int, seed: int,
                segments_of: Callable[[LString], Segments] | None = None, tip: str = "", per_lobe: int = 250,
                style: CrownStyle = DEFAULT_STYLE, tries: int = 5) -> tuple[LString, int, bool]:
    """The crown grown from ``base`` into ``lobes`` adding at most ``room`` modules: a try that is too
    big is grown again with longer pieces, and at last with proportionally fewer nodes (at most
    ``tries``); ``style`` is how it grows (its first try's pieces ``style.twig`` of a lobe's size long).
    Returns the L-string, the branch pieces added and whether the budget limited them."""
    room = min(room, MAX_CROWN_MODULES)
    nodes, step, reach = MAX_CROWN_MODULES // 4, style.twig, style.twig / 2
    for k in range(tries):
        if room <= 0 or nodes < 2 or not lobes:
            break
        scratch = Modeler(lstring=base, segments_of=segments_of)
        added = grow_crown(scratch, lobes, np.random.default_rng(seed), per_lobe=per_lobe, max_nodes=nodes, tip=tip,
                           style=replace(style, twig=step, reach=reach))
        extra = len(scratch.lstring) - len(base)
        if extra <= room:
            return scratch.lstring, added, added >= nodes - 2 or nodes < MAX_CROWN_MODULES // 4
        # too big: longer pieces that use up the attractors a little farther away fill the lobes with
        # fewer nodes; the node bound is the last resort, shared fairly among the lobes
        grow = min(max((extra / room) ** LONGER, 1.0 + MIN_LONGER), MAX_STEP / step)
        if grow > 1.01 and k < tries - 2:
            step, reach = step * grow, reach * grow
        else:
            nodes = int(added * room / extra * 0.95)
    return base, 0, bool(lobes)


def lobe_fill(lobes: list[Lobe], segs: Segments, samples: int = 3000, seed: int = 0) -> list[float]:
    """For each lobe, the share of its volume within FILL_REACH of its size from any segment (sampled:
    ``samples`` uniform points inside, distances to points spaced along the segments)."""
    rng = np.random.default_rng(seed)
    out = []
    for lobe in lobes:
        size = float(np.ptp(lobe.vertices, axis=0).max())
        reach = FILL_REACH * size
        length = np.linalg.norm(segs.end - segs.start, axis=1)
        per = np.maximum(np.ceil(length / (0.25 * reach)).astype(np.int64), 1)
        seg = np.repeat(np.arange(len(segs)), per)
        frac = (np.arange(len(seg)) - np.repeat(np.cumsum(per) - per, per) + 0.5) / np.repeat(per, per)
        wood = segs.start[seg] + frac[:, None] * (segs.end[seg] - segs.start[seg])
        points = lobe.sample_inside(samples, rng)
        dist = cKDTree(wood).query(points)[0] if len(wood) else np.full(len(points), np.inf)
        out.append(float((dist <= reach).mean()))
    return out
