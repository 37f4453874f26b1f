"""ABOP context neighbours of every module in one O(n) pass each way (a numba kernel).

Left: the previous module on the path to the root, skipping whole branches ``[...]`` to the left and
passing out of the enclosing branch at its '['. Right: the next module on the same axis, skipping
whole branches; the axis ends at the ']' closing its branch. Symbols in the #ignore set are passed
over. A stack of "the last module on the path" per open branch makes each pass one loop; numba
compiles it (cached on disk) the first time a system with contexts derives, so nothing else pays for
it. Measured against the best whole-array numpy version (benchmarks/context_numpy.py): see
``python -m benchmarks.context``.
"""

from __future__ import annotations

import numpy as np


def neighbours(sym: np.ndarray, skip: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Left and right context neighbour of every module (-1 where there is none); ``skip`` is a
    boolean table indexed by symbol (the #ignore set)."""
    from arbor.engine.lsystem.context_kernel import walk

    left = np.empty(len(sym), np.int64)
    right = np.empty(len(sym), np.int64)
    walk(np.ascontiguousarray(sym, np.uint8), np.ascontiguousarray(skip, np.bool_), left, right)
    return left, right
