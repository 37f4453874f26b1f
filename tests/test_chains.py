import numpy as np
import pytest

from engine.geometry.chains import (
    LEVEL_LIMIT,
    Levels,
    chain_sum,
    quat_mul,
    quat_to_rows,
    rows_to_quat,
    scan,
    to_rows,
    tree_depths,
)


def random_forest(rng, n, deep=0):
    """Parents precede children (as in a bracketed string); ``deep`` appends one long chain."""
    par = np.array([-1] + [int(rng.integers(-1, i)) for i in range(1, n)], dtype=np.int64)
    if deep:
        chain = np.arange(n - 1, n + deep - 1, dtype=np.int64)
        par = np.concatenate([par, chain])
    return par


def random_rotations(rng, n):
    q, _ = np.linalg.qr(rng.normal(size=(n, 3, 3)))
    q[:, :, 0] *= np.linalg.det(q)[:, None]  # proper rotations only
    return q


def matrices(rows):
    return rows.T.reshape(-1, 3, 3)


@pytest.mark.parametrize("deep", [0, LEVEL_LIMIT + 57])
def test_scans_match_a_sequential_walk(deep):
    rng = np.random.default_rng(4)
    par = random_forest(rng, 400, deep)
    n = len(par)
    rots = random_rotations(rng, n)
    values = rng.normal(size=n)
    expected_rot, expected_sum = rots.copy(), values.copy()
    for i in range(n):  # parents come first
        if par[i] >= 0:
            expected_rot[i] = expected_rot[par[i]] @ rots[i]
            expected_sum[i] = expected_sum[par[i]] + values[i]
    products = scan(par, rows_to_quat(to_rows(rots)), quat_mul)
    np.testing.assert_allclose(matrices(quat_to_rows(products)), expected_rot, atol=1e-9)
    np.testing.assert_allclose(chain_sum(par, values), expected_sum, atol=1e-9)


def test_levels_sort_parents_before_children_and_count_depths():
    rng = np.random.default_rng(5)
    par = random_forest(rng, 300, 20)
    depth = tree_depths(par)
    for i in range(len(par)):
        assert depth[i] == (0 if par[i] < 0 else depth[par[i]] + 1)
    levels = Levels.of(par)
    assert np.all(levels.parent < np.arange(len(par)))  # every parent sits earlier in level order
    np.testing.assert_array_equal(levels.order[levels.where], np.arange(len(par)))


def test_quaternions_compose_like_matrices_and_round_trip():
    rng = np.random.default_rng(7)
    a, b = random_rotations(rng, 200), random_rotations(rng, 200)
    qa, qb = rows_to_quat(to_rows(a)), rows_to_quat(to_rows(b))
    np.testing.assert_allclose(matrices(quat_to_rows(qa)), a, atol=1e-12)
    np.testing.assert_allclose(matrices(quat_to_rows(quat_mul(qa, qb))), a @ b, atol=1e-12)
    half_turns = np.array([np.diag([1.0, -1, -1]), np.diag([-1.0, 1, -1]), np.diag([-1.0, -1, 1])])
    np.testing.assert_allclose(matrices(quat_to_rows(rows_to_quat(to_rows(half_turns)))), half_turns, atol=1e-12)
