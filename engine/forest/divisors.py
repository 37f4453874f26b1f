"""Divisor functions and their convolution sums: the branch and leaf propagation pattern of Jung et al.
(section 4.2, eq. 3-4, Algorithm 2).

Eq. 4's divisor functions (exact integer arithmetic):

* ``sigma(a, n)``            sigma_a(n)       = sum of d^a over the divisors d of n;
* ``sigma_mod(a, b, m, n)``  sigma_{a,b}(n;m) = the same over divisors d = b (mod m);
* ``sigma_alt(a, n)``        ~sigma_a(n)      = sum of (-1)^(d-1) d^a;
* ``sigma_star(a, n)``       sigma*_a(n)      = sum of d^a over divisors d with n/d odd.

Eq. 3's convolution sum W(N) = sum_{k=1}^{N-1} D_b(B k) D_l(L (N-k)) grows polynomially, not
exponentially, which is what keeps the branch count of a tree predictable (the paper's Fig. 6).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

DivisorFunction = Callable[[int], int]


@lru_cache(maxsize=4096)
def divisors(n: int) -> tuple[int, ...]:
    """All positive divisors of n >= 1, ascending."""
    if n < 1:
        raise ValueError("divisors are defined for n >= 1")
    small, large = [], []
    d = 1
    while d * d <= n:
        if n % d == 0:
            small.append(d)
            if d * d != n:
                large.append(n // d)
        d += 1
    return tuple(small + large[::-1])


def sigma(a: int, n: int) -> int:
    """sigma_a(n): the sum of the a-th powers of the divisors of n."""
    return sum(d**a for d in divisors(n))


def sigma_mod(a: int, b: int, m: int, n: int) -> int:
    """sigma_{a,b}(n; m): the sum of d^a over divisors d of n with d = b (mod m)."""
    return sum(d**a for d in divisors(n) if d % m == b % m)


def sigma_alt(a: int, n: int) -> int:
    """The alternating divisor sum: sum of (-1)^(d-1) d^a over divisors d of n."""
    return sum((-1) ** (d - 1) * d**a for d in divisors(n))


def sigma_star(a: int, n: int) -> int:
    """sigma*_a(n): the sum of d^a over divisors d of n whose cofactor n/d is odd."""
    return sum(d**a for d in divisors(n) if (n // d) % 2 == 1)


FUNCTIONS: dict[str, Callable[..., int]] = {
    "sigma": sigma, "sigma_mod": sigma_mod, "sigma_alt": sigma_alt, "sigma_star": sigma_star,
}


def convolution(db: DivisorFunction, dl: DivisorFunction, n: int, b: int = 1, l_mult: int = 1) -> int:
    """Eq. 3: W(N) = sum_{k=1}^{N-1} D_b(B k) * D_l(L (N - k))."""
    return sum(db(b * k) * dl(l_mult * (n - k)) for k in range(1, n))


@dataclass(frozen=True)
class PropagationRule:
    """One level's choice in Algorithm 2: a divisor function and its increasing coefficient."""

    function: DivisorFunction
    coefficient: int = 1

    def __call__(self, k: int) -> int:
        return self.function(self.coefficient * k)


def branch_differences(rules: list[PropagationRule], steps: int) -> np.ndarray:
    """n_dv for every growth step k = 1..N-1 (Algorithm 2): the trunk (last step) takes D(B k); the
    other steps take the difference between this level's and the previous level's function."""
    out = np.zeros(steps - 1, dtype=np.int64)
    for k in range(1, steps):
        level = min(k, len(rules)) - 1
        current = rules[level](k)
        if k == steps - 1 or level == 0:
            out[k - 1] = current
        else:
            out[k - 1] = current - rules[level - 1](k)
    return out


def new_branches(n_dv: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """n_br in {1, ..., |n_dv| + 1} for each step, drawn uniformly (Algorithm 2)."""
    return rng.integers(1, np.abs(n_dv) + 2)


def leaf_changes(rules: list[PropagationRule], steps: int) -> np.ndarray:
    """n_lf at each step: positive creates that many leaves, negative lets that many fall."""
    out = np.zeros(steps - 1, dtype=np.int64)
    for k in range(1, steps):
        level = min(k, len(rules)) - 1
        previous = rules[level - 1](steps - k) if level > 0 else 0
        out[k - 1] = rules[level](steps - k) - previous
    return out


def children_table(rules: list[PropagationRule], steps: int, seed: int, max_children: int = 4) -> np.ndarray:
    """Children per level for a divisor-driven tree: Algorithm 2's n_br, drawn once per level from a
    seeded RNG and capped at ``max_children`` (so one tree keeps one pattern, and seeds vary it)."""
    n_br = new_branches(branch_differences(rules, steps + 1), np.random.default_rng(seed))
    return np.minimum(n_br, max_children)


def children_function(table: np.ndarray) -> tuple[Callable[[np.ndarray], np.ndarray], int, int]:
    """The table as a host function children(level) for an L-system (vectorised over a column)."""
    padded = np.append(table, 1).astype(np.float64)

    def children(level):
        idx = np.clip(np.asarray(level, dtype=np.int64), 0, len(padded) - 1)
        return padded[idx]

    return children, 1, 1
