import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from arbor.engine.base.errors import LSysError
from arbor.engine.lsystem.lstring import LString, parse_lstring, replace_modules

SYMBOLS = "FfAB+-&^/\\|$[]!'%XL"
floats = st.floats(allow_nan=True, allow_infinity=True, width=64)


@st.composite
def lstrings(draw):
    n = draw(st.integers(0, 40))
    syms = draw(st.lists(st.sampled_from(SYMBOLS), min_size=n, max_size=n))
    counts = draw(st.lists(st.integers(0, 3), min_size=n, max_size=n))
    values = draw(st.lists(floats, min_size=sum(counts), max_size=sum(counts)))
    return LString.from_arrays(
        np.array([ord(s) for s in syms], np.uint8), np.array(counts, np.uint8), np.array(values, np.float64)
    )


@given(lstrings())
@settings(max_examples=300, deadline=None)
def test_text_round_trip_is_exact(ls):
    back = parse_lstring(ls.to_text())
    assert back.equals(ls)


def test_text_format_is_readable():
    ls = parse_lstring("F(5) [ +(25.7)F(0.1,2) ] A")
    assert ls.to_text() == "F(5)[+(25.7)F(0.1,2)]A"
    assert ls.module(3) == ("F", (0.1, 2.0))
    assert parse_lstring("F(-0.0)").to_text() == "F(-0.0)"
    assert parse_lstring(repr(math.pi).join(["F(", ")"])).params[0] == math.pi


def test_memory_layout_is_flat():
    ls = parse_lstring("F(1)" * 1000)
    assert ls.nbytes <= 18 * 1000
    assert ls.sym.dtype == np.uint8 and ls.params.dtype == np.float64


@pytest.mark.parametrize(
    "text, col", [("F(1,", 2), ("F(abc)", 3), ("F)", 2), ("F(1)(2)", 5), ("Fé", 2), ("F(1e999x)", 3)]
)
def test_bad_text_names_column(text, col):
    with pytest.raises(LSysError) as info:
        parse_lstring(text, file="save.tree", line=7)
    assert (info.value.file, info.value.line, info.value.col) == ("save.tree", 7, col)


@given(st.text(max_size=60))
@settings(max_examples=300, deadline=None)
def test_random_text_only_raises_our_error(text):
    try:
        parse_lstring(text)
    except LSysError as err:
        assert err.line >= 1 and err.col >= 1


def test_the_array_reader_agrees_with_the_careful_reader_on_mangled_text():
    """Text the writer wrote, then mangled at random: wherever the whole-array reader accepts it, the
    module-by-module reader reads the same modules; wherever the careful reader refuses, so does it."""
    from arbor.engine.lsystem.lstring import _parse_fast, _parse_slow

    rng = np.random.default_rng(7)
    alphabet = [*list("FA+-[]()(),,,.5e-0 9infa\n"), "(1)", "1e5", "nan", "--", ")(", "é"]
    accepted = 0
    for _ in range(3000):
        n = int(rng.integers(1, 12))
        counts = rng.integers(0, 3, n)
        ls = LString.from_arrays(rng.choice(np.frombuffer(b"FA+[]X", np.uint8), n), counts,
                                 rng.normal(0, 100, int(counts.sum())).round(3))
        text = ls.to_text()
        for _ in range(int(rng.integers(0, 3))):
            at = int(rng.integers(0, len(text) + 1))
            cut = int(rng.integers(0, 2))
            text = text[:at] + str(rng.choice(alphabet)) + text[at + cut:]
        fast = _parse_fast(text)
        try:
            slow = _parse_slow(text, "<t>", 1)
        except LSysError:
            assert fast is None, text
            continue
        if fast is not None:
            accepted += 1
            assert fast.equals(slow), text
    assert accepted > 1000  # most texts still take the fast road


def test_replace_modules_keeps_the_others_and_sets_the_chosen():
    """Modules picked get their symbol and values (counts change); every other module keeps its own."""
    rng = np.random.default_rng(4)
    counts = rng.integers(0, 5, 500)
    ls = LString.from_arrays(rng.choice(np.frombuffer(b"FAI+[]", np.uint8), 500), counts,
                             rng.normal(size=int(counts.sum())))
    idx = np.sort(rng.choice(500, 120, replace=False))
    values = rng.normal(size=(120, 2))
    out = replace_modules(ls, idx, ord("X"), values)
    picked = dict(zip(idx.tolist(), values.tolist(), strict=True))
    for i in range(500):
        expected = ("X", tuple(picked[i])) if i in picked else ls.module(i)
        assert out.module(i) == expected
