import numpy as np
import pytest

from arbor.engine.geometry.chains import chain_sum


def random_forest(rng, n, deep=0):
    """Parents precede children (as in a bracketed string); ``deep`` appends one long chain."""
    par = np.array([-1] + [int(rng.integers(-1, i)) for i in range(1, n)], dtype=np.int64)
    if deep:
        chain = np.arange(n - 1, n + deep - 1, dtype=np.int64)
        par = np.concatenate([par, chain])
    return par


@pytest.mark.parametrize("deep", [0, 300])
def test_chain_sums_match_a_walk_to_the_root(deep):
    rng = np.random.default_rng(4)
    par = random_forest(rng, 400, deep)
    values = rng.normal(size=len(par))
    for i in range(len(par)):  # every path summed from scratch, root first
        path, j = [], i
        while j >= 0:
            path.append(j)
            j = par[j]
        assert chain_sum(par, values)[i] == pytest.approx(sum(values[path[::-1]]), abs=1e-9)


def test_a_parent_after_its_child_is_refused():
    with pytest.raises(ValueError, match="before"):
        chain_sum(np.array([-1, 2, 0]), np.ones(3))
