"""Benchmarks: `python -m benchmarks.<name>` prints figures; performance goals live here, not in tests."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import TypeVar

import numpy as np

T = TypeVar("T")


def median_ms(fn: Callable[[], T], runs: int = 20) -> tuple[float, T]:
    """Median wall time of ``runs`` calls in milliseconds, and the last call's result."""
    times, out = [], None
    for _ in range(runs):
        start = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - start)
    return float(np.median(times)) * 1e3, out
