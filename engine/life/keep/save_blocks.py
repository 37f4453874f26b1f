"""Reading a save's TOML without making TOML (or the UTF-8 decoder) walk its L-strings.

A save keeps each L-string in a multi-line literal string (``lstring = '''...'''``). A literal string
holds its text as it is, but the TOML reader still checks it character by character (about 35 ms for
a 100k-module tree), and decoding a file with any non-ASCII character in it (an ``ε`` in the embedded
.lsys) turns 2 MB of L-string into a wide string first. So the blocks are cut out of the file's bytes
(the text between the quotes, which needs no unescaping), each replaced by a marker that keeps its line
breaks (error positions stay right); the rest is decoded and read by TOML, and the blocks go back
where the markers are, as text. Anything unusual (a marker found elsewhere, a block TOML would end
differently, a block that is not ASCII) and the whole file is decoded and read by TOML as it is.
"""

from __future__ import annotations

import secrets
import tomllib

from arbor.engine.base.reader import COSTLY_WORK, LINE_WORK, MAX_WORK, nesting_problem, position, reading_work

__all__ = ["COSTLY_WORK", "LINE_WORK", "MAX_WORK", "TooDeepError", "TooMuchWorkError", "loads", "reading_work"]

_KEYS = (b"\nlstring = '''\n", b"\nroots = '''\n", b"\ncrown_base = '''\n")  # at a line start, as written


class TooMuchWorkError(ValueError):
    """The text TOML would have to read is too much work (checked before it starts)."""

    def __init__(self, work: int) -> None:
        super().__init__(f"too complex to load in time: reading it outside its L-strings is {work:,} units of work, "
                         f"at most {MAX_WORK:,} (every byte 1, every line {LINE_WORK}, every value, key, table or "
                         f"escape {COSTLY_WORK}: a long journal, family or list)")
        self.work = work


class TooDeepError(ValueError):
    """The text nests arrays, tables or keys deeper than any save does (checked before TOML reads it,
    whose reader would run out of stack): ``line`` and ``col`` say where."""

    def __init__(self, what: str, line: int, col: int) -> None:
        super().__init__(f"nested too deeply: {what}")
        self.line, self.col = line, col


def loads(raw: bytes) -> tuple[dict, str]:
    """``tomllib.loads`` of the UTF-8 file ``raw``, faster for saves with big L-strings; also the text
    that line numbers refer to (the L-strings' lines kept as empty lines). Raises UnicodeDecodeError
    and TOMLDecodeError as decoding and reading the whole file would, and :class:`TooMuchWorkError`
    (before reading) when the text TOML would read is more than MAX_WORK."""
    lifted, blocks = _lift(raw)
    _check_work(lifted)
    if blocks:
        try:
            text = lifted.decode("utf-8")
            data = tomllib.loads(text)
            texts = {marker: block.decode("ascii") for marker, block in blocks.items()}
        except (UnicodeDecodeError, tomllib.TOMLDecodeError):
            pass  # let the whole file name the problem where it is
        else:
            if _put_back(data, texts) == len(blocks):
                return data, text
        _check_work(raw)  # (with no blocks lifted, the text just checked is the whole file: not twice)
    text = raw.decode("utf-8")
    return tomllib.loads(text), text


def _check_work(text: bytes) -> None:
    work = reading_work(text)
    if work > MAX_WORK:
        raise TooMuchWorkError(work)
    decoded = text.decode("utf-8", "replace")
    problem = nesting_problem(decoded)
    if problem is not None:
        raise TooDeepError(problem[1], *position(decoded, problem[0]))


def _lift(raw: bytes) -> tuple[bytes, dict[str, bytes]]:
    nonce = secrets.token_hex(8)
    out, blocks, pos = [], {}, 0
    while True:
        found = [at for at in (raw.find(key, pos) for key in _KEYS) if at >= 0]
        if not found:
            break
        body_at = raw.index(b"\n", min(found) + 1) + 1  # after the key's line
        end = raw.find(b"'''", body_at)
        if end < 0 or raw.startswith(b"'", end + 3):
            break  # an unclosed block, or one ending in quotes: TOML decides
        body = raw[body_at:end]
        marker = f"@arbor-block-{nonce}-{len(blocks)}@"
        blocks[marker] = body
        out += [raw[pos:body_at], marker.encode("ascii"), b"\n" * body.count(b"\n")]
        pos = end
    out.append(raw[pos:])
    return b"".join(out), blocks


def _put_back(data, blocks: dict[str, str]) -> int:
    """Replace marker values by their blocks everywhere in ``data``; returns how many were replaced."""
    found = 0
    items = data.items() if isinstance(data, dict) else enumerate(data) if isinstance(data, list) else ()
    for key, value in items:
        if isinstance(value, str) and value.rstrip("\n") in blocks:
            data[key] = blocks[value.rstrip("\n")]
            found += 1
        elif isinstance(value, dict | list):
            found += _put_back(value, blocks)
    return found
