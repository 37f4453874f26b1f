"""The compiled loops behind context.neighbours (imported only when a system has contexts)."""

# numba caches these kernels on disk under this module's name (arbor.engine...) and reloads them while
# this file is unchanged: renaming the module needs a change here too, or the cache names a module gone.

from __future__ import annotations

import numba
import numpy as np

OPEN, CLOSE = 91, 93  # '[' and ']'


@numba.njit(cache=True, nogil=True)
def walk(sym: np.ndarray, skip: np.ndarray, left: np.ndarray, right: np.ndarray) -> None:
    """Fill ``left`` and ``right`` (see context.neighbours): forwards, the last good module on the
    path, saved at '[' and restored at ']'; backwards, the next good module on the axis, saved at ']'
    (the axis inside ends there) and restored at '['. Unbalanced brackets read as closed at the end."""
    n = len(sym)
    stack = np.empty(n + 1, np.int64)
    top, last = 0, -1
    for i in range(n):
        s = sym[i]
        left[i] = last
        if s == OPEN:
            stack[top] = last
            top += 1
        elif s == CLOSE:
            if top > 0:
                top -= 1
                last = stack[top]
        elif not skip[s]:
            last = i
    top, nxt = 0, -1
    for i in range(n - 1, -1, -1):
        s = sym[i]
        right[i] = nxt
        if s == CLOSE:
            stack[top] = nxt
            top += 1
            nxt = -1
        elif s == OPEN:
            if top > 0:
                top -= 1
                nxt = stack[top]
        elif not skip[s]:
            nxt = i
