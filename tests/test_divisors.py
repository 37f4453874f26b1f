import numpy as np
import pytest

from arbor.engine.base.errors import LSysError
from arbor.engine.forest.divisors import (
    PropagationRule,
    branch_differences,
    convolution,
    divisors,
    leaf_changes,
    new_branches,
    sigma,
    sigma_alt,
    sigma_mod,
    sigma_star,
)


def test_values_computed_by_hand():
    assert divisors(12) == (1, 2, 3, 4, 6, 12)
    assert sigma(0, 12) == 6 and sigma(1, 12) == 28 and sigma(2, 6) == 1 + 4 + 9 + 36
    assert sigma(3, 2) == 9 and sigma(1, 1) == 1 and sigma(1, 7) == 8
    assert sigma_mod(1, 1, 3, 12) == 1 + 4  # divisors = 1 (mod 3)
    assert sigma_mod(1, 0, 2, 12) == 2 + 4 + 6 + 12  # even divisors
    assert sigma_alt(1, 12) == 1 - 2 + 3 - 4 - 6 - 12
    assert sigma_alt(0, 9) == 3  # all divisors of 9 are odd
    assert sigma_star(1, 12) == 4 + 12  # 12/d odd for d = 4, 12
    assert sigma_star(1, 9) == sigma(1, 9)
    with pytest.raises(ValueError):
        divisors(0)


@pytest.mark.parametrize("n", list(range(2, 80)))
def test_the_identity_quoted_in_seed_001(n):
    s1 = lambda k: sigma(1, k)  # noqa: E731
    assert 12 * convolution(s1, s1, n) == 5 * sigma(3, n) + (1 - 6 * n) * sigma(1, n)


def test_convolution_grows_polynomially_not_exponentially():
    s1 = lambda k: sigma(1, k)  # noqa: E731
    w = np.array([convolution(s1, s1, n) for n in range(2, 40)], dtype=float)
    n = np.arange(2, 40)
    ratio = w / n.astype(float) ** 3
    assert ratio.max() < 1.0  # bounded by a cubic: sigma_3(N) <= zeta(3) N^3


def test_algorithm_2_counts():
    rules = [PropagationRule(lambda k: sigma(0, k)), PropagationRule(lambda k: sigma(1, k), 2)]
    n_dv = branch_differences(rules, 8)
    assert n_dv[0] == sigma(0, 1)  # the first level takes its own function
    assert n_dv[1] == sigma(1, 4) - sigma(0, 2)  # later levels: difference with the previous level
    assert n_dv[-1] == sigma(1, 14)  # the trunk step takes D(B k) alone
    rng = np.random.default_rng(0)
    draws = np.array([new_branches(n_dv, rng) for _ in range(200)])
    assert (draws >= 1).all() and (draws <= np.abs(n_dv) + 1).all() and len(np.unique(draws[:, 1])) > 1
    leaves = leaf_changes(rules, 8)
    assert leaves[0] == sigma(0, 7) and leaves[2] == sigma(1, 2 * 5) - sigma(0, 5)


def test_host_functions_drive_an_lsystem(lsys_dir):
    from arbor.engine.lsystem.derive import derive
    from arbor.engine.lsystem.lsys import load_lsystem, parse_lsystem

    counts = {0: 2, 1: 3, 2: 1}
    host = {"children": (lambda i: np.vectorize(lambda v: counts.get(int(v), 1))(i).astype(float), 1, 1)}
    source = (lsys_dir / "divisor_tree.lsys").read_text()
    tree = parse_lsystem(source, "divisor_tree.lsys", overrides={"LEVELS": 3}, host=host)
    result = derive(tree, 3)
    assert result.count("A") == 2 * 3 * 1  # children multiply level by level
    with pytest.raises(LSysError, match="needs the program to supply the function children"):
        load_lsystem(lsys_dir / "divisor_tree.lsys")  # the file cannot call what the host did not give


def test_divisor_propagation_grows_far_slower_than_fixed_branching():
    from arbor.engine.forest.divisors import children_function, children_table
    from benchmarks.propagation import counts

    rules = [PropagationRule(lambda k: sigma(0, k)), PropagationRule(lambda k: sigma_alt(0, k), 2)]
    table = children_table(rules, 6, seed=3)
    assert table.min() >= 1 and table.max() <= 4
    divisor = counts({"children": children_function(table)}, 6)
    fixed = counts({"children": children_function(np.full(7, 3))}, 6)
    assert fixed[-1][0] == 1 + (3**6 - 1) // 2  # the trunk, then 1 + 3 + 9 + ... new ones: exponential
    assert divisor[-1][0] * 5 < fixed[-1][0] and divisor[-1][1] * 5 < fixed[-1][1]
