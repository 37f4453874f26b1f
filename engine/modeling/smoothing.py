"""Hand jitter taken out of a stroke before its shape is read: a penalized least-squares (Whittaker)
smoother whose strength is chosen from the stroke itself by generalized cross-validation, computed in
the discrete cosine basis, after D. Garcia, "Robust smoothing of gridded data in one and higher
dimensions with missing values" (Computational Statistics & Data Analysis 54, 2010).

A stroke's points z minimise |z - y|^2 + s |D2 z|^2 (D2: second differences, the bending); in the DCT
basis the solution is each coefficient times 1 / (1 + s lambda_k^2), so the GCV score of every s costs
one pass over the coefficients. Jitter (uncorrelated from point to point) is what GCV finds it can
drop; a drawn bend, seen by many neighbouring points, it keeps. The straight line through the points
(least squares) is taken out first and put back after: a straight stroke stays straight to its ends.
"""

from __future__ import annotations

import numpy as np

MIN_POINTS = 8  # fewer points are kept as drawn (too few to tell a bend from jitter)
LOG_S = np.linspace(-4.0, 12.0, 65)  # log10 of the smoothing strengths tried, then refined round the best


def _gcv(log_s: float, lam2: np.ndarray, power: np.ndarray, n: int) -> float:
    """Garcia's GCV score of strength 10**log_s: residual sum of squares over (1 - trace / n)^2."""
    gain = 1.0 / (1.0 + 10.0 ** log_s * lam2)
    rss = float((gain - 1.0) ** 2 @ power)
    return rss / max(1.0 - float(gain.sum()) / n, 1e-12) ** 2


def smoothed(points: np.ndarray) -> np.ndarray:
    """``points`` (n, d) without hand jitter (see module docstring); fewer than MIN_POINTS as they are."""
    from scipy.fft import dct, idct  # (scipy.fft loads in ~30 ms, only once a stroke is drawn)

    points = np.asarray(points, dtype=np.float64)
    n = len(points)
    if n < MIN_POINTS:
        return points
    line = np.stack([np.ones(n), np.linspace(-1.0, 1.0, n)], 1)
    trend = line @ np.linalg.lstsq(line, points, rcond=None)[0]
    coefficients = dct(points - trend, type=2, norm="ortho", axis=0)
    lam2 = (2.0 - 2.0 * np.cos(np.arange(n) * np.pi / n)) ** 2  # eigenvalues of D2'D2 (reflected ends)
    power = (coefficients ** 2).sum(axis=1)
    k = int(np.argmin([_gcv(x, lam2, power, n) for x in LOG_S]))
    step = LOG_S[1] - LOG_S[0]
    fine = np.linspace(LOG_S[k] - step, LOG_S[k] + step, 21)
    best = fine[int(np.argmin([_gcv(x, lam2, power, n) for x in fine]))]
    gain = 1.0 / (1.0 + 10.0 ** best * lam2)
    return trend + idct(gain[:, None] * coefficients, type=2, norm="ortho", axis=0)
