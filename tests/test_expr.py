import math

import numpy as np
import pytest

from arbor.engine.base.errors import LSysError
from arbor.engine.lsystem.expr import EvalContext, compile_expression, evaluate


def ev(text, **vars):
    n = max((len(v) for v in vars.values()), default=1)
    cols = {k: np.asarray(v, float) for k, v in vars.items()}
    expr = compile_expression(text, {"k": 2.0}, set(vars))
    return evaluate(expr, EvalContext(cols, n, np.random.default_rng(1)))


def test_precedence_and_power():
    assert ev("1 + 2 * 3")[0] == 7
    assert ev("2 ^ 3 ^ 2")[0] == 512  # right associative
    assert ev("-2 ^ 2")[0] == -4
    assert ev("2 ^ -1")[0] == 0.5
    assert ev("(1 + 2) * k")[0] == 6


def test_columns_and_functions():
    out = ev("max(x, 2) + sqrt(y) * cos(0)", x=[1, 3], y=[4, 9])
    assert out.tolist() == [4.0, 6.0]
    assert ev("atan2(1, 1)")[0] == pytest.approx(math.pi / 4)
    assert ev("floor(x) + abs(-x) + min(1, 2, 0.5)", x=[2.5])[0] == pytest.approx(5.0)


def test_logic():
    assert ev("x > 1 and not x >= 3", x=[0, 2, 3]).tolist() == [0, 1, 0]
    assert ev("x < 1 || x == 3", x=[0, 2, 3]).tolist() == [1, 0, 1]
    assert ev("!(x != 2)", x=[0, 2]).tolist() == [0, 1]


def test_rand_is_seeded_and_in_range():
    a = ev("rand(2, 4)", x=np.zeros(1000))
    b = ev("rand(2, 4)", x=np.zeros(1000))
    assert np.array_equal(a, b)
    assert a.min() >= 2 and a.max() < 4 and a.std() > 0.3


@pytest.mark.parametrize(
    "text, col",
    [("1 +", 4), ("foo + 1", 1), ("sqrt(1, 2)", 1), ("(1 + 2", 7), ("1 $ 2", 3), ("open(1)", 1)],
)
def test_errors_have_columns(text, col):
    with pytest.raises(LSysError) as info:
        compile_expression(text, {}, set(), file="x.lsys", line=3)
    assert info.value.file == "x.lsys" and info.value.line == 3 and info.value.col == col
    assert str(info.value).startswith(f"x.lsys:3:{col}:")


def test_no_python_names_reachable():
    for text in ("__import__", "os", "eval(1)", "x.__class__"):
        with pytest.raises(LSysError):
            compile_expression(text, {}, {"x"})
