"""L-strings in memory: a symbol array plus parameters stored apart from the symbols (the tamagotchi thesis, 2.1).

A module is one printable ASCII symbol with zero or more float parameters. An :class:`LString` holds

* ``sym``     uint8[n]   the symbols (ASCII codes),
* ``nparams`` uint8[n]   how many parameters each module has,
* ``offsets`` int64[n]   where each module's parameters start in ``params``,
* ``params``  float64[m] all parameter values, in module order.

That is 18 bytes for a module with one parameter, with no Python object per module.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np

from arbor.engine.base.errors import LSysError
from arbor.engine.lsystem.text import lstring_text, parse_arrays

MAX_PARAMS = 255
_FORBIDDEN = set("(),")


def valid_symbol(ch: str) -> bool:
    """True for characters that can be module symbols: printable ASCII except ``( ) ,``."""
    return len(ch) == 1 and 33 <= ord(ch) <= 126 and ch not in _FORBIDDEN


@dataclass
class LString:
    """An L-string: symbols and parameters in flat numpy arrays (see module docstring)."""

    sym: np.ndarray
    nparams: np.ndarray
    offsets: np.ndarray
    params: np.ndarray

    @classmethod
    def from_arrays(cls, sym: np.ndarray, nparams: np.ndarray, params: np.ndarray) -> LString:
        """Build an L-string from symbols, parameter counts and the flat parameter array."""
        sym = np.ascontiguousarray(sym, dtype=np.uint8)
        nparams = np.ascontiguousarray(nparams, dtype=np.uint8)
        offsets = np.zeros(len(sym), dtype=np.int64)
        if len(sym) > 1:
            np.cumsum(nparams[:-1], dtype=np.int64, out=offsets[1:])
        params = np.ascontiguousarray(params, dtype=np.float64)
        if int(nparams.sum(dtype=np.int64)) != len(params):
            raise ValueError("parameter counts do not add up to the parameter array length")
        return cls(sym, nparams, offsets, params)

    @classmethod
    def empty(cls) -> LString:
        """The empty L-string."""
        return cls.from_arrays(np.zeros(0, np.uint8), np.zeros(0, np.uint8), np.zeros(0))

    def __len__(self) -> int:
        return len(self.sym)

    @property
    def nbytes(self) -> int:
        """Memory held by the arrays, in bytes."""
        return self.sym.nbytes + self.nparams.nbytes + self.offsets.nbytes + self.params.nbytes

    def count(self, symbol: str) -> int:
        """How many modules have ``symbol``."""
        return int(np.count_nonzero(self.sym == ord(symbol)))

    def module(self, i: int) -> tuple[str, tuple[float, ...]]:
        """Module ``i`` as (symbol, parameters) — for tests and tools, not for hot paths."""
        k, o = int(self.nparams[i]), int(self.offsets[i])
        return chr(self.sym[i]), tuple(float(v) for v in self.params[o : o + k])

    def param_column(self, idx: np.ndarray, j: int) -> np.ndarray:
        """Parameter ``j`` of each module in ``idx`` (callers make sure each has more than j)."""
        return self.params[self.offsets[idx] + j]

    def select(self, keep: np.ndarray) -> LString:
        """A new L-string of the modules where boolean mask ``keep`` is true (order kept)."""
        if len(self.params) == 0:  # no module has parameters (their counts add up to none)
            return BareLString(self.sym[keep])
        pkeep = np.repeat(keep, self.nparams)
        return LString.from_arrays(self.sym[keep], self.nparams[keep], self.params[pkeep])

    def equals(self, other: LString) -> bool:
        """Exact equality of modules and parameter values (the sign of zero counts; NaN equals NaN)."""
        return (
            np.array_equal(self.sym, other.sym)
            and np.array_equal(self.nparams, other.nparams)
            and np.array_equal(self.params, other.params, equal_nan=True)
            and np.array_equal(_zero_signs(self.params), _zero_signs(other.params))
        )

    def to_text(self, wrap: int = 0) -> str:
        """Readable ABOP-style text, e.g. ``F(5)[+(25.7)F(2.5)]``; floats round-trip exactly. With
        ``wrap``, a line break goes before the first module that starts in each run of ``wrap``
        characters (the reader skips blanks between modules)."""
        return lstring_text(self.sym, self.nparams, self.offsets, self.params, wrap)

    def __str__(self) -> str:
        return self.to_text()


class BareLString(LString):
    """An L-string whose modules have no parameters: its ``nparams`` and ``offsets`` (zeros, 9 bytes a
    module against the symbols' 1) are made only when something reads them. A plain L-system's step
    writes its symbols in about the time of a memcpy; filling those zeros took longer than the step.
    Readers see ordinary arrays, made once and kept (writes to them stay)."""

    def __init__(self, sym: np.ndarray, nparams: np.ndarray | None = None, offsets: np.ndarray | None = None,
                 params: np.ndarray | None = None) -> None:
        self.sym = sym
        self._nparams, self._offsets = nparams, offsets
        self.params = np.zeros(0) if params is None else params

    @property
    def nparams(self) -> np.ndarray:  # type: ignore[override]
        """How many parameters each module has (zeros until someone writes them)."""
        if self._nparams is None:
            self._nparams = np.zeros(len(self.sym), np.uint8)
        return self._nparams

    @nparams.setter
    def nparams(self, value: np.ndarray) -> None:
        self._nparams = value

    @property
    def offsets(self) -> np.ndarray:  # type: ignore[override]
        """Where each module's parameters start in ``params``."""
        if self._offsets is None:
            self._offsets = np.zeros(len(self.sym), np.int64)
        return self._offsets

    @offsets.setter
    def offsets(self, value: np.ndarray) -> None:
        self._offsets = value


def concat(*parts: LString) -> LString:
    """The L-strings one after the other (array splicing, no text round trip)."""
    return LString.from_arrays(
        np.concatenate([p.sym for p in parts]),
        np.concatenate([p.nparams for p in parts]),
        np.concatenate([p.params for p in parts]),
    )


def params_where(params: np.ndarray, mask: np.ndarray, at: np.ndarray, default: float = 0.0) -> np.ndarray:
    """``params[at]`` where ``mask`` holds, ``default`` elsewhere; never indexes ``params`` where the mask
    is false (so an L-string with no parameters at all, a hostile save's ``F``, is no IndexError)."""
    out = np.full(len(mask), default, dtype=np.float64)
    out[mask] = params[at[mask]]
    return out


def ragged_arange(starts: np.ndarray, counts: np.ndarray) -> np.ndarray:
    """Concatenation of arange(s, s + c) for each (s, c), without a Python loop."""
    counts = np.asarray(counts, dtype=np.int64)
    total = int(counts.sum())
    if total == 0:
        return np.zeros(0, dtype=np.int64)
    ends = np.cumsum(counts)
    shift = np.repeat(np.asarray(starts, dtype=np.int64) - (ends - counts), counts)
    return shift + np.arange(total, dtype=np.int64)


def replace_modules(ls: LString, idx: np.ndarray, symbol: int | np.ndarray, values: np.ndarray) -> LString:
    """A copy of ``ls`` where modules ``idx`` become ``symbol`` (one, or one each) with parameters
    ``values`` (k, m).

    Other modules keep their symbols and parameters. Vectorised; used to build render views.
    """
    if len(idx) == 0:
        return LString(ls.sym.copy(), ls.nparams.copy(), ls.offsets.copy(), ls.params.copy())
    values = np.asarray(values, dtype=np.float64).reshape(len(idx), -1)
    sym = ls.sym.copy()
    sym[idx] = symbol
    nparams = ls.nparams.copy()
    nparams[idx] = values.shape[1]
    out = LString.from_arrays(sym, nparams, np.empty(int(nparams.sum(dtype=np.int64))))
    keep = np.ones(len(ls), dtype=bool)
    keep[idx] = False  # the other modules' parameters, in order, by a byte mask per parameter each side
    out.params[np.repeat(keep, nparams)] = ls.params[np.repeat(keep, ls.nparams)]
    if values.shape[1]:
        out.params[out.offsets[idx][:, None] + np.arange(values.shape[1])] = values
    return out


def _zero_signs(values: np.ndarray) -> np.ndarray:
    return np.signbit(values) & (values == 0)


_MODULE = re.compile(r"\s*([^\s(),])(?:\(([^()]*)\))?")
_NUMBER = re.compile(r"\s*[+-]?(?:(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?|inf|nan)\s*")


def parse_lstring(text: str, file: str = "<string>", line: int = 1) -> LString:
    """Parse L-string text (numbers only as parameters) back into an :class:`LString`.

    The inverse of :meth:`LString.to_text`. Whitespace between modules is allowed. Text our writer
    could have written is checked and read with whole-array operations (engine/lsystem/text.py);
    anything else is read module by module to name the file, line and column of the first error
    (untrusted input: saves are shared between players).
    """
    parsed = _parse_fast(text)
    return parsed if parsed is not None else _parse_slow(text, file, line)


def _parse_fast(text: str) -> LString | None:
    """Well-formed text as an L-string, or None for anything unusual (see ``text.parse_arrays``)."""
    parsed = parse_arrays(text, MAX_PARAMS)
    return None if parsed is None else LString.from_arrays(*parsed)


def _parse_slow(text: str, file: str, line: int) -> LString:
    """Module by module, naming the first error's line and column."""
    syms: list[int] = []
    counts: list[int] = []
    values: list[float] = []
    pos, _n = 0, len(text)
    for m in _MODULE.finditer(text):
        if m.start() != pos:
            break
        ch = m.group(1)
        if not valid_symbol(ch):
            raise _err(text, m.start(1), f"{ch!r} cannot be a module symbol", file, line)
        syms.append(ord(ch))
        args = m.group(2)
        if args is None:
            counts.append(0)
        else:
            counts.append(_parse_args(text, m.start(2), args, values, file, line))
        pos = m.end()
    if text[pos:].strip():
        rest = pos + len(text[pos:]) - len(text[pos:].lstrip())
        raise _err(text, rest, f"unexpected {text[rest]!r}: expected a module symbol", file, line)
    return LString.from_arrays(np.array(syms, np.uint8), np.array(counts, np.uint8), np.array(values, np.float64))


def _parse_args(text: str, start: int, args: str, values: list[float], file: str, line: int) -> int:
    parts = args.split(",")
    if len(parts) > MAX_PARAMS:
        raise _err(text, start, f"more than {MAX_PARAMS} parameters", file, line)
    at = start
    for part in parts:
        if not _NUMBER.fullmatch(part):
            raise _err(text, at, f"expected a number, found {part.strip()[:20]!r}", file, line)
        values.append(float(part))
        at += len(part) + 1
    return len(parts)


def _err(text: str, pos: int, message: str, file: str, line: int) -> LSysError:
    line_no = line + text.count("\n", 0, pos)
    col = pos - (text.rfind("\n", 0, pos) + 1) + 1
    return LSysError(message, file, line_no, col)
