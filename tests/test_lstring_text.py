"""The whole-array text writer and reader: exact on big, repetitive trees, and never fooled by keys."""

import numpy as np
import pytest

from arbor.engine.base.errors import LSysError
from arbor.engine.lsystem import text
from arbor.engine.lsystem.lstring import LString, parse_lstring


def _repetitive(n: int, pool: int, seed: int) -> LString:
    """A tree-like L-string: n modules whose parameters come from a small pool of awkward values."""
    rng = np.random.default_rng(seed)
    values = np.concatenate([rng.normal(0, 1e3, pool - 8) * 10.0 ** rng.integers(-20, 20, pool - 8),
                             [0.0, -0.0, np.inf, -np.inf, np.nan, 1e16, 5e-324, 0.1]])
    counts = rng.integers(0, 6, n)
    return LString.from_arrays(rng.choice(np.frombuffer(b"FA+-[]&^/L", np.uint8), n), counts,
                               rng.choice(values, int(counts.sum())))


def test_big_repetitive_text_round_trips_exactly_wrapped_or_not():
    ls = _repetitive(20_000, 300, 1)
    for wrap in (0, 100):
        written = ls.to_text(wrap)
        assert parse_lstring(written).equals(ls)
    lines = ls.to_text(100).split("\n")
    assert len(lines) > 100 and max(map(len, lines)) < 100 + 200  # a break before a module, every ~100
    assert all(line[0] not in "(),0123456789" for line in lines[1:])


def test_groups_match_numpy_unique():
    rng = np.random.default_rng(2)
    for size, distinct in ((10, 3), (5000, 40), (100_000, 800)):
        keys = rng.integers(-(2**63), 2**63 - 1, distinct, dtype=np.int64)[rng.integers(0, distinct, size)]
        first, ids = text.groups(keys)
        assert np.array_equal(keys[first[ids]], keys)  # each key's group holds that key
        assert len(np.unique(keys[first])) == len(first)  # and groups are distinct
        assert len(first) == len(np.unique(keys))
    keys = rng.integers(0, 2**62, 10_000)  # mostly distinct: each its own group, no table built
    assert np.array_equal(text.groups(keys)[1], np.arange(10_000))


def test_a_key_collision_never_gives_a_wrong_number(monkeypatch):
    """With a key that ignores the first 8 characters, 1.2345678901 and 2.2345678901 share a key:
    the reader must notice and read them the careful way."""
    monkeypatch.setattr(text, "_GOLDEN", np.uint64(0))
    ls = parse_lstring("F(1.2345678901,2.2345678901)" * 10)
    assert ls.params[:2].tolist() == [1.2345678901, 2.2345678901]
    assert text.parse_arrays("F(1.2345678901,2.2345678901)" * 10, 255) is None


def test_long_numbers_are_read_too():
    digits = "0." + "1" * 60
    assert parse_lstring(f"F({digits},2)").params.tolist() == [float(digits), 2.0]


def test_text_is_written_and_read_in_parts_exactly_as_whole(monkeypatch):
    """Parts of a few modules (writer) and a few bytes (reader) give the text and the L-string that one
    part gives, line breaks included; a malformed module in a later part still sends the text to the
    careful reader, which names it."""
    ls = _repetitive(3_000, 50, 3)
    whole = {wrap: ls.to_text(wrap) for wrap in (0, 37)}
    monkeypatch.setattr(text, "CHUNK", 7)
    monkeypatch.setattr(text, "READ_CHUNK", 64)
    for wrap, written in whole.items():
        assert ls.to_text(wrap) == written
        parts = text.parse_arrays(written, 255)
        assert parts is not None and LString.from_arrays(*parts).equals(ls)
    at = whole[0].rfind(")", 0, len(whole[0]) - 200) + 1  # between two modules, in the last part
    broken = whole[0][:at] + "F(1,,2)" + whole[0][at:]
    assert text.parse_arrays(broken, 255) is None
    with pytest.raises(LSysError, match=f"1:{at + 5}: expected a number"):
        parse_lstring(broken)
