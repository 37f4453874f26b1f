"""How a tree shares its vigour among its shoots: the extended Borchert-Honda model of Palubicki et al.
2009 ("Self-organizing tree models for image synthesis", section 4.2).

The light every growing apex catches is summed down the tree: an internode's ``Q`` is the light of all
the shoots above it. The vigour then flows back up from the base (where it is the whole tree's ``Q``): at
every branch point the continuing axis ``m`` and the lateral ``l`` share it as

    v_m = v * lam * Q_m / (lam * Q_m + (1 - lam) * Q_l)
    v_l = v * (1 - lam) * Q_l / (lam * Q_m + (1 - lam) * Q_l)

with the species' apical control ``lam``. At ``lam`` = 0.5 each apex gets exactly its own light (the
shares telescope); above 0.5 the main axes draw vigour from the laterals (strong apical control, a
conical crown), below it the laterals win (a spreading crown). The total is always the tree's light.

In an L-string a lateral is a bracketed group; the continuing axis is everything after the group up to
the end of the axis that holds it. The product of shares along every apex's path is a prefix sum of
log-shares over the string (no Python loop over modules).
"""

from __future__ import annotations

import numpy as np

from arbor.engine.lsystem.brackets import OPEN, branch_ends, depths, match

TINY = 1e-30  # a share of nothing: its logarithm stays finite


def borchert_honda(sym: np.ndarray, apex: np.ndarray, light: np.ndarray, lam: float) -> np.ndarray:
    """The vigour (in units of light) each apex at string positions ``apex`` (ascending) receives, given
    the ``light`` each catches and the apical control ``lam`` (0..1)."""
    light = np.clip(np.asarray(light, dtype=np.float64), 0.0, None)
    n = len(sym)
    if len(apex) == 0 or abs(lam - 0.5) < 1e-12:
        return light.copy()
    caught = np.zeros(n + 1)
    caught[np.asarray(apex) + 1] = light
    total = np.cumsum(caught)  # total[i]: light of the apices before position i
    opens = np.flatnonzero(sym == OPEN)
    if len(opens) == 0:
        return light.copy()
    d = depths(sym)
    close = match(sym, d)[opens]
    end = branch_ends(sym, close, d, depth=d[opens] - 1)  # where the axis holding each lateral ends
    lateral = total[close] - total[opens]
    main = total[end] - total[close + 1]
    weigh_l, weigh_m = (1.0 - lam) * lateral, lam * main
    shared = weigh_l + weigh_m
    some = shared > 0
    share_l = np.where(some, weigh_l / np.where(some, shared, 1.0), 1.0)
    share_m = np.where(some, weigh_m / np.where(some, shared, 1.0), 1.0)
    log_l, log_m = np.log(np.maximum(share_l, TINY)), np.log(np.maximum(share_m, TINY))
    delta = np.zeros(n + 1)
    np.add.at(delta, opens, log_l)  # inside the lateral: its share
    np.add.at(delta, close + 1, log_m - log_l)  # after it, on the axis that holds it: the axis' share
    np.add.at(delta, end, -log_m)  # beyond that axis: neither
    path = np.cumsum(delta)[np.asarray(apex)]
    return total[-1] * np.exp(path)


def apical_control(young: float, height: float, fade: float) -> float:
    """The Borchert-Honda ``lam`` of a tree ``height`` m tall whose sapling's is ``young``: apical control weakens
    as the tree grows (Brown, McAlpine & Kormanik 1967, "Apical dominance and form in woody plants: a
    reappraisal"; Wilson 2000, "Apical control of branch growth and angle in woody plants"): the young excurrent
    leader's lead over its laterals (``young`` - 0.5) halves by ``fade`` m and goes on fading, so the older crown
    shares its vigour by the light each shoot catches (0.5) and broadens."""
    return 0.5 + (young - 0.5) * fade / (fade + max(height, 0.0))
