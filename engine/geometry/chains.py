"""Sums along parent-pointer chains (segments grow from earlier segments), shared by mesher and sim.

Every element has a parent index (-1 for a root) that comes before it, as a drawn piece comes after
the piece it grows from in a bracketed string; so one compiled pass in index order finishes every
parent before its children.
"""

# numba caches these kernels on disk under this module's name (arbor.engine...) and reloads them while
# this file is unchanged: renaming the module needs a change here too, or the cache names a module gone.

from __future__ import annotations

import numba
import numpy as np


@numba.njit(cache=True, nogil=True)
def _path_sums(par: np.ndarray, values: np.ndarray, out: np.ndarray) -> None:
    for i in range(len(par)):
        p = par[i]
        if p >= i:
            raise ValueError("a parent must come before its children")
        out[i] = values[i] + out[p] if p >= 0 else values[i]


def chain_sum(par: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Sum of ``values`` (n,) over each element's path from its root, itself included."""
    values = np.asarray(values)
    out = np.empty(len(values), np.result_type(values.dtype, np.int64))
    _path_sums(np.asarray(par, np.int64), values, out)
    return out

