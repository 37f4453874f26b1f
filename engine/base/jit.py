"""numba's first use, without the scipy import numba makes for it.

The first kernel numba compiles or loads from its cache imports ``numba.np.arraymath``, whose import asks
whether a BLAS is there by importing ``scipy.linalg.cython_blas``: all of scipy.linalg, with the numpy
submodules scipy's array-API layer clones (numpy.f2py, numpy.testing, numpy.ma): about 150 ms of CPU, a
tenth of a warm start, for a check that needs only to know that scipy is installed. No Arbor kernel uses
BLAS (np.dot, np.linalg). ``defer_blas_check()``, called before any kernel runs (game.first_start does), has
numba's arraymath answer the check by finding scipy, not importing it; a numba function that does call
np.dot still imports scipy itself when it is compiled (numba.np.linalg's own check is left as it was).
"""

from __future__ import annotations

import importlib.util
import sys


def _scipy_installed() -> None:
    """numba's BLAS check, answered without importing scipy: ImportError when scipy is not installed."""
    if importlib.util.find_spec("scipy") is None:
        raise ImportError("scipy 0.16+ is required for linear algebra")


def defer_blas_check() -> None:
    """Import numba's array maths with its BLAS check answered by finding scipy (a no-op once it is
    imported: call it before the first kernel runs)."""
    if "numba.np.arraymath" in sys.modules:
        return
    import numba.np.linalg as linalg

    check = getattr(linalg, "ensure_blas", None)
    if check is None:  # a numba without this check: nothing to defer
        return
    linalg.ensure_blas = _scipy_installed
    try:
        import numba.np.arraymath  # noqa: F401  (binds the check above as its own, once)
    finally:
        linalg.ensure_blas = check
