"""How the process allocates big arrays: keep freed blocks for reuse instead of fresh pages."""

from __future__ import annotations

import ctypes
import sys

_M_TRIM_THRESHOLD, _M_TOP_PAD, _M_MMAP_THRESHOLD = -1, -2, -3
MMAP_THRESHOLD = 32 * 2**20
TRIM_THRESHOLD = 64 * 2**20


def keep_freed_memory() -> bool:
    """Ask glibc's allocator to serve arrays under 32 MB from its heap and keep up to 64 MB freed.

    Numpy's temporaries of a few MB (a 100k-module tree's text, its parameters) are otherwise each
    mapped fresh from the system and returned on free, so every use pays its page faults again:
    measured, a 100k-module load goes from 79 to 54 ms. Returns False where there is no glibc
    (other systems keep their own allocator's behaviour); the cost is at most 64 MB held for reuse."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        mallopt = ctypes.CDLL(None).mallopt  # (the process's own symbols: glibc's allocator, if it is glibc)
    except (OSError, AttributeError):
        return False
    return bool(mallopt(_M_MMAP_THRESHOLD, MMAP_THRESHOLD)) and bool(mallopt(_M_TRIM_THRESHOLD, TRIM_THRESHOLD))
