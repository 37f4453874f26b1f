import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from arbor.engine.base.errors import LSysError
from arbor.engine.lsystem.derive import derive
from arbor.engine.lsystem.lstring import parse_lstring
from arbor.engine.lsystem.lsys import load_lsystem, parse_lsystem


def test_headers_defines_and_ignore():
    system = parse_lsystem(
        "// a comment\n# another\n#define a 2\n#define b a * 3\n#ignore: + -\n"
        "n: 4\ndelta: 22.5\nstep: 0.5\nseed: 9\nbudget: 1000\nw: F(b)\np1: F(x) : x > a -> F(x - 1)\n"
    )
    assert system.constants == {"a": 2.0, "b": 6.0}
    assert (system.iterations, system.angle, system.step, system.seed, system.budget) == (4, 22.5, 0.5, 9, 1000)
    assert system.ignore[ord("+")] and not system.ignore[ord("F")]
    assert derive(system).to_text() == "F(2)"


def test_unicode_arrow_and_epsilon_and_labels():
    system = parse_lsystem("ω: ABA\np1 : A → ε\nP2: B -> BB")
    assert derive(system, 1).to_text() == "BB"


def test_seed003_tree_matches_the_paper(lsys_dir):
    system = load_lsystem(lsys_dir / "seed003_tree.lsys")
    assert system.axiom.to_text() == "!(0.2)F(5)/(45)A"
    step1 = derive(system, 1)
    expected = parse_lstring(
        "!(0.3464)F(5.545)/(45)!(0.1)F(5)[&(18.95)F(5)A]/(94.74)[&(18.95)F(5)A]/(132.63)[&(18.95)F(5)A]"
    )
    assert np.array_equal(step1.sym, expected.sym)
    assert step1.params == pytest.approx(expected.params)


@pytest.mark.parametrize(
    "source, line, col, words",
    [
        ("w: F\np1: F -> F(x)", 2, 12, "unknown name 'x'"),
        ("w: F\np1: F(x) : x > -> F", 2, 16, "expected a number"),
        ("w: F\np1: F -> F[+F", 2, 11, "never closed"),
        ("w: F\np1: F -> F]", 2, 11, "without a matching"),
        ("w: F\n#define", 2, 8, "constant name"),
        ("w: F\n#include x", 2, 2, "unknown directive"),
        ("n: 2", 1, 1, "no axiom"),
        ("w: F\nhello", 2, 1, "expected 'w: axiom'"),
        ("w: F\np1: F(x,x) -> F", 2, 5, "used twice"),
        ("w: F\np1: F -> (0.5) F | (z) G", 2, 21, "unknown name 'z'"),
        ("w: F\nn: 2.5", 2, 7, "whole number"),
        ("w: F\nn: 1e309", 2, 9, "finite"),
        ("w: F\np1: A B -> F", 2, 5, "exactly one module"),
        ("w: F\np1: F -> F(1,", 2, 14, "expected a number"),
    ],
)
def test_errors_name_file_line_column(source, line, col, words):
    with pytest.raises(LSysError) as info:
        parse_lsystem(source, file="shared.lsys")
    err = info.value
    assert (err.file, err.line, err.col) == ("shared.lsys", line, col), str(err)
    assert words in err.message


def test_load_reports_binary_file(tmp_path):
    path = tmp_path / "bad.lsys"
    path.write_bytes(b"\xff\xfe\x00garbage")
    with pytest.raises(LSysError) as info:
        load_lsystem(path)
    assert info.value.file == str(path)


FRAGMENTS = [
    "w:", "p1:", "->", "→", "F", "A(x)", "(", ")", ",", "x", "1.5", "+", "*", ":", "<", ">", "[", "]", "|",
    "(0.5)", "#define", "#ignore:", "n:", " ", "\n", "rand()", "sqrt(", "^", "%", "!", "&&", "1e309", "ε",
]


@given(st.lists(st.one_of(st.sampled_from(FRAGMENTS), st.text(max_size=3)), max_size=30))
@settings(max_examples=500, deadline=None)
def test_fuzzed_sources_raise_only_our_error(parts):
    source = "".join(parts)
    try:
        system = parse_lsystem(source, file="fuzz.lsys")
    except LSysError as err:
        assert err.file == "fuzz.lsys" and err.line >= 1 and err.col >= 1
        return
    derive(system, 2, budget=10_000)


def test_missing_file_is_a_clear_error(tmp_path):
    with pytest.raises(LSysError) as info:
        load_lsystem(tmp_path / "nope.lsys")
    assert "cannot read" in info.value.message and info.value.file.endswith("nope.lsys")


def test_a_source_declares_its_unit_in_metres_per_turtle_unit():
    assert parse_lsystem("unit: 0.01 // F(1) is a centimetre\nw: F\n").unit == 0.01
    assert parse_lsystem("w: F\n").unit is None  # the scene's unit (engine/base/units.py)
    for bad in ("0", "-1", "5000"):
        with pytest.raises(LSysError, match="metres per turtle unit"):
            parse_lsystem(f"unit: {bad}\nw: F\n")
