"""L-string text written and read with whole-array operations (no Python object per module).

The text is ABOP-style, ``F(5)[+(25.7)F(2.5)]``. Trees repeat their numbers (constants, angles,
birth times), so both ways work on the distinct numbers: each is formatted once (and parsed once in
each part of the text read), and the rest is gathering bytes. Equal values are grouped with a small hash
table probed by numpy, not by sorting.
"""

from __future__ import annotations

import numpy as np

OPEN, CLOSE, COMMA = 40, 41, 44
MAX_FAST_NUMBER = 48  # longer number texts (legal, but never written by us) go the careful way
_GOLDEN = np.uint64(0x9E3779B97F4A7C15)

CLASS = np.zeros(256, np.uint8)  # bit 1: a symbol, 2: a blank, 4: a number's character, 8: ( , )
CLASS[33:127] = 1
CLASS[[OPEN, CLOSE, COMMA]] = 8
CLASS[[9, 10, 13, 32]] = 2
CLASS[np.frombuffer(b"0123456789+-.eEinfa", np.uint8)] |= 4
_HEADS = bytes(b for c in range(256) for b in (c, OPEN))  # every symbol followed by '('


def groups(keys: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Equal 64-bit ``keys`` grouped: for each group the index of one of its keys, and for each key
    its group. Trees repeat their numbers, so groups are mostly far fewer than keys; when a sample
    of the keys is mostly distinct, every key is its own group (grouping would only cost).

    Like ``np.unique(keys, return_index=True, return_inverse=True)``, but each key finds its group
    in an open-addressing hash table (a few vectorised probes), not by sorting all the keys."""
    keys = np.ascontiguousarray(keys).view(np.uint64)
    sample = keys[:: max(1, len(keys) // 2048)]
    if len(np.unique(sample)) >= 0.5 * len(sample):  # (also no keys at all)
        return np.arange(len(keys)), np.arange(len(keys))
    ordered = np.sort(keys)
    distinct = ordered[np.r_[True, ordered[1:] != ordered[:-1]]]
    bits = max(4, (4 * len(distinct)).bit_length())  # the table at most a quarter full
    mask = (1 << bits) - 1
    table = np.full(1 << bits, -1, np.int64)
    slot, pending = _slots(distinct, bits), np.arange(len(distinct))
    while len(pending):  # insert: claim free slots (one of several claimants wins), the rest move on
        free = pending[table[slot[pending]] < 0]
        table[slot[free]] = free
        pending = pending[table[slot[pending]] != pending]
        slot[pending] = (slot[pending] + 1) & mask
    slot = _slots(keys, bits)
    ids = table[slot]
    todo = np.flatnonzero(distinct[ids] != keys)
    while len(todo):  # keys not in their first slot: every key is in the table, before an empty slot
        slot[todo] = (slot[todo] + 1) & mask
        ids[todo] = table[slot[todo]]
        todo = todo[distinct[ids[todo]] != keys[todo]]
    first = np.empty(len(distinct), np.int64)
    first[ids] = np.arange(len(keys))
    return first, ids


def _slots(keys: np.ndarray, bits: int) -> np.ndarray:
    return ((keys * _GOLDEN) >> np.uint64(64 - bits)).astype(np.int64)


def format_number(v: float) -> str:
    """Shortest text that parses back to exactly ``v`` (integers without a trailing '.0')."""
    if v.is_integer() and abs(v) < 1e16 and not (v == 0.0 and np.signbit(v)):
        return str(int(v))
    return repr(v)


def number_texts(values: np.ndarray) -> tuple[list[str], np.ndarray]:
    """``format_number`` of each group of equal values (bit for bit: -0.0 stays apart from 0.0) and,
    for every value, the index of its text (see ``groups``)."""
    values = np.asarray(values, dtype=np.float64)
    first, ids = groups(values.view(np.int64))
    distinct = values[first]
    whole = (distinct == np.round(distinct)) & (np.abs(distinct) < 1e16) & ~(np.signbit(distinct) & (distinct == 0))
    out = np.empty(len(distinct), dtype=object)
    out[whole] = distinct[whole].astype(np.int64).astype(str).tolist()
    rest = np.flatnonzero(~whole)
    if len(rest):
        out[rest] = list(map(repr, distinct[rest].tolist()))
    return out.tolist(), ids


def lstring_text(sym: np.ndarray, nparams: np.ndarray, offsets: np.ndarray, params: np.ndarray,
                 wrap: int = 0) -> str:
    """The text of an L-string given as arrays (see ``LString.to_text``): gathered from a small
    source of pieces (``"F("``, ``"25.7,"``, ...), one index run per piece; a module's last
    parameter's ',' then becomes ')'. Written CHUNK modules at a time into one buffer, so the memory
    beside the text stays the same whatever the tree's size."""
    n, total = len(sym), len(params)
    texts, ids = number_texts(params)
    text_len = np.fromiter(map(len, texts), np.int64, len(texts)) + 1
    blob = ",".join(texts).encode("ascii") + b","
    pieces = _Pieces(np.frombuffer(blob + _HEADS, np.uint8), len(blob), np.cumsum(text_len) - text_len, text_len)
    size = n + int(np.count_nonzero(nparams)) + int(np.bincount(ids, minlength=len(texts)) @ text_len)
    out = np.empty(size + (size // wrap + 1 if wrap > 0 else 0), np.uint8)
    used = plain = 0  # bytes written, and the same without line breaks
    for lo in range(0, n, CHUNK):
        hi = min(n, lo + CHUNK)
        p_lo, p_hi = int(offsets[lo]), (int(offsets[hi]) if hi < n else total)
        part, heads = pieces.text(sym[lo:hi], nparams[lo:hi], offsets[lo:hi] - p_lo, ids[p_lo:p_hi])
        if wrap > 0:  # a break before head i when the next head starts in another run of wrap characters
            starts = plain + heads
            if hi < n:
                starts = np.append(starts, plain + len(part))
            breaks = heads[np.flatnonzero(np.diff(starts // wrap))]
            plain += len(part)
            part = np.insert(part, breaks, ord("\n"))
        out[used:used + len(part)] = part
        used += len(part)
    return str(memoryview(out)[:used], "latin-1")  # symbols are ASCII when they came from text


CHUNK = 1 << 14  # modules written a pass
READ_CHUNK = 1 << 20  # bytes read a pass, at most


class _Pieces:
    """The source of a text's pieces: every distinct number's text and a ',' (``at``, ``length``), then
    every symbol followed by '(' (from ``heads``)."""

    def __init__(self, source: np.ndarray, heads: int, at: np.ndarray, length: np.ndarray) -> None:
        self.source, self.heads, self.at, self.length = source, heads, at, length

    def text(self, sym: np.ndarray, nparams: np.ndarray, offsets: np.ndarray,
             ids: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The text of these modules (``ids``: their parameters' number texts) and where each starts."""
        n, total = len(sym), len(ids)
        has = nparams > 0
        head, param = offsets + np.arange(n), np.arange(total) + np.repeat(np.arange(n), nparams) + 1
        start, length = np.empty(n + total, np.int64), np.empty(n + total, np.int64)
        start[head], length[head] = self.heads + 2 * sym.astype(np.int64), 1 + has
        start[param], length[param] = self.at[ids], self.length[ids]
        out = self.source[_gather_runs(start, length)]
        at = np.cumsum(length) - length
        last = param[offsets[has] + nparams[has].astype(np.int64) - 1]
        out[at[last] + length[last] - 1] = CLOSE
        return out, at[head]


def _gather_runs(start: np.ndarray, length: np.ndarray) -> np.ndarray:
    """Indices ``start[0] .. start[0] + length[0] - 1, start[1] ...`` (all lengths >= 1) by one
    cumulative sum of steps: 1 inside a run, a jump at each run's first index."""
    at = np.cumsum(length) - length
    small = len(start) == 0 or max(int(start.max()) + int(length.max()), int(length.sum())) < 2**31
    kind = np.int32 if small else np.int64
    step = np.ones(int(length.sum()), kind)
    if len(start):
        step[0] = start[0]
        step[at[1:]] = start[1:] - (start[:-1] + length[:-1] - 1)
    return np.cumsum(step, dtype=kind)


def parse_arrays(text: str, max_params: int) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """Well-formed L-string text as (symbols, parameter counts, values), or None for anything
    unusual (then the careful reader decides and names the error).

    Well-formed: ASCII; parentheses never nested, each right after a module symbol; between them
    only numbers and single commas, no blanks; outside them only symbols and blanks. Read in parts
    of READ_CHUNK bytes (a sixteenth of a shorter text), each ending just after a ')' (so outside any
    parentheses): a part is well-formed on its own exactly when its place in the whole text is, and
    the memory beside the text and the result stays a small share of them."""
    try:
        data = text.encode("ascii")
    except UnicodeEncodeError:
        return None
    parts, start = [], 0
    chunk = min(READ_CHUNK, max(len(data) // 16, 1 << 16))  # a sixteenth of the text, up to READ_CHUNK
    while start < len(data) or not parts:
        end = data.find(b")", start + chunk) + 1 or len(data)
        part = _parse_part(data[start:end] if start or end < len(data) else data, max_params)
        if part is None:
            return None
        parts.append(part)
        start = end
    if len(parts) == 1:
        return parts[0]
    sym, counts, values = (np.concatenate([p[k] for p in parts]) for k in range(3))
    return sym, counts, values


def _parse_part(data: bytes, max_params: int) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """parse_arrays on one part of the text."""
    raw, cls = np.frombuffer(data, np.uint8), np.frombuffer(data.translate(_CLASS_BYTES), np.uint8)
    if not cls.all():
        return None  # a control character
    delim = np.flatnonzero(cls == 8)
    kind = raw[delim]
    if len(delim) and (kind[0] != OPEN or kind[-1] != CLOSE
                       or not np.where(kind[:-1] == CLOSE, kind[1:] == OPEN, kind[1:] != OPEN).all()):
        return None  # not "( number , number ... )" groups, one after another
    opens, closes = np.flatnonzero(kind == OPEN), np.flatnonzero(kind == CLOSE)
    open_at, close_at = delim[opens], delim[closes]
    if len(open_at) and (open_at[0] == 0 or not (cls[open_at - 1] & 1).all()):
        return None  # a '(' that does not follow a module symbol
    run_at = np.concatenate([[0], close_at + 1])  # runs of text outside the groups
    run_len = np.concatenate([open_at, [len(raw)]]) - run_at
    outside = _gather_runs(run_at[run_len > 0], run_len[run_len > 0])
    symbols = outside[(cls[outside] & 1).view(bool)]
    counts = np.zeros(len(symbols), np.int64)
    if len(open_at) == 0:
        return raw[symbols], counts.astype(np.uint8), np.zeros(0)
    counts[raw[np.minimum(symbols + 1, len(raw) - 1)] == OPEN] = closes - opens  # delimiters in a group - 1
    left = np.flatnonzero(kind[:-1] != CLOSE)  # each number lies between delimiter left and left + 1
    starts, lengths = delim[left] + 1, delim[left + 1] - delim[left] - 1
    if counts.max() > max_params or lengths.min() == 0:
        return None
    values = _numbers(raw, starts, lengths)
    return None if values is None else (raw[symbols], counts.astype(np.uint8), values)


def _numbers(raw: np.ndarray, starts: np.ndarray, lengths: np.ndarray) -> np.ndarray | None:
    """The numbers at ``starts`` / ``lengths`` (None if one is not a number). Each number's text is
    read as a few little-endian 8-byte words (bytes past its end zeroed); rows of words are keyed,
    each distinct row checked and parsed once, and every row compared with the one parsed for it
    (a key collision cannot give a wrong value)."""
    count = -(-int(lengths.max()) // 8)
    if count * 8 > MAX_FAST_NUMBER:
        return None
    aligned = np.concatenate([raw, np.zeros(16 * count + 16 - len(raw) % 8, np.uint8)]).view("<u8")
    words = np.empty((len(starts), count), "<u8")
    at, shift = starts >> 3, ((starts & 7) * 8).astype(np.uint64)
    back = np.uint64(64) - shift  # (a shift by 64 gives 0 in numpy)
    low = aligned[at] >> shift
    for j in range(count):  # word j: the rest of aligned word at + j and the start of the next
        high = aligned[at + j + 1]
        words[:, j] = (low | (high << back)) & _LOW_BYTES[np.clip(lengths - 8 * j, 0, 8)]
        low = high >> shift
    key = words[:, 0].copy()
    for j in range(1, count):
        key = key * _GOLDEN + words[:, j]
    first, ids = groups(key)
    if count > 1 and len(first) < len(ids) and not (words == words[first][ids]).all():
        return None  # two different numbers with one key: let the careful reader parse them
    texts = words[first].view(np.uint8)
    if not (CLASS[texts] & 4 | (texts == 0)).all():
        return None
    try:
        return np.array(list(map(float, texts.view(f"S{8 * count}").ravel().tolist())))[ids]
    except ValueError:
        return None


_LOW_BYTES = np.array([(1 << (8 * k)) - 1 for k in range(9)], np.uint64)  # masks keeping k low bytes
_CLASS_BYTES = CLASS.tobytes()
