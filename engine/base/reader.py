"""The one reader for every file a user hands us (saves, postcards, .lsys sources, settings, kiosk.toml,
experiments, sweeps, device profiles, species presets, recordings).

Such a file is untrusted: it may be a FIFO (reading it would block the start), a device (``/dev/zero``
reads without end), a link to a file elsewhere, huge, or TOML nested so deeply that the standard
library's reader runs out of stack. So a file is read only when it is a regular file itself (opened with
O_NOFOLLOW | O_NONBLOCK, checked with fstat), at most ``limit`` bytes; TOML's nesting and the work its
reading costs are bounded by counting before ``tomllib`` starts; and every problem is one
:class:`~arbor.engine.base.errors.LSysError` (of the caller's kind) naming the file, line and column.
"""

from __future__ import annotations

import errno
import os
import re
import stat
import tomllib
from pathlib import Path

from arbor.engine.base.errors import LSysError

MAX_DEPTH = 32  # arrays and inline tables nested in one another: our files need 4 at most
TOML_LIMIT = 1024 * 1024  # bytes of a TOML file a person writes (an experiment, a sweep, a profile)
MAX_WORK = 2_000_000  # reading work TOML may be given (at most 1.6 s on this machine): see :func:`reading_work`
_COSTLY = (b",", b"[", b"{", b"=", b"\\")  # a value, a table, a key or an escape: about 8-34 us each
COSTLY_WORK, LINE_WORK = 32, 2
# What can hold a bracket that is not one: strings of the four kinds and comments; else a bracket. A string
# left open runs to the end of its line (its text, for the triple-quoted kinds) instead of failing to match:
# a failed match would be tried again from every quote in it (a hostile line of quotes: quadratic time).
_TOKENS = re.compile(r'"""(?:[^"\\]|\\.|"(?!""))*(?:"""+)?' r"|'''(?:(?!''').)*(?:'''+)?"
                     r'|"(?:[^"\\\n]|\\.)*"?' r"|'[^'\n]*'?|#[^\n]*|[\[\]{}]", re.S)
_DOTTED = re.compile(r"^[ \t]*(?:[A-Za-z0-9_-]+|\"[^\"\n]*\"|'[^'\n]*')(?:[ \t]*\.[ \t]*(?:[A-Za-z0-9_-]+"
                     r"|\"[^\"\n]*\"|'[^'\n]*'))+", re.M)


def open_regular(path: str | Path) -> int:
    """A read-only descriptor of ``path`` if it is a regular file itself; OSError otherwise (a link, a
    FIFO, a device, a folder), without ever waiting on a FIFO or following a link."""
    fd = os.open(path, os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_NONBLOCK", 0))
    mode = os.fstat(fd).st_mode
    if not stat.S_ISREG(mode):
        os.close(fd)
        if stat.S_ISDIR(mode):
            raise OSError(errno.EISDIR, "Is a directory")
        raise OSError(errno.EINVAL, "not a regular file")
    return fd


def read_regular(path: str | Path, limit: int) -> bytes:
    """At most ``limit + 1`` bytes of ``path`` if it is a regular file itself: a symlink (to a file
    outside the folder, say), a FIFO (which would block the start) or a device is an OSError, not read."""
    fd = open_regular(path)
    try:
        with os.fdopen(os.dup(fd), "rb") as fh:  # read(n) allocates n bytes first: ask for no more than the file
            return fh.read(min(limit, os.fstat(fd).st_size) + 1)
    finally:
        os.close(fd)


def why_unreadable(exc: OSError) -> str:
    """One line saying why a user's file could not be read (what to do about a link or a FIFO)."""
    if exc.errno == errno.ELOOP:
        return "it is a link (give the file itself, not a link to it)"
    if exc.errno == errno.EINVAL:
        return "not a regular file (a FIFO or a device: give a plain file)"
    return exc.strerror or str(exc)


def read_user_bytes(path: str | Path, limit: int, error: type[LSysError] = LSysError) -> bytes:
    """The bytes of the user's file ``path``: a regular file itself of at most ``limit`` bytes, else
    ``error`` naming the file."""
    try:
        raw = read_regular(path, limit)
    except OSError as exc:
        raise error(f"cannot read: {why_unreadable(exc)}", str(path)) from None
    if len(raw) > limit:
        raise error(f"too large (more than {limit:,} bytes)", str(path))
    return raw


def decode_text(raw: bytes, file: str, error: type[LSysError] = LSysError) -> str:
    """``raw`` as UTF-8 text (a BOM allowed); bytes that are not UTF-8 are ``error`` at their line and
    column."""
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        head = raw[:exc.start]
        line, col = head.count(b"\n") + 1, exc.start - (head.rfind(b"\n") + 1) + 1
        raise error(f"cannot read: not UTF-8 text ({exc.reason} at byte {exc.start})", file, line, col) from None


def read_user_text(path: str | Path, limit: int, error: type[LSysError] = LSysError) -> str:
    """The UTF-8 text of the user's file ``path`` (see :func:`read_user_bytes`)."""
    return decode_text(read_user_bytes(path, limit, error), str(path), error)


def reading_work(text: bytes) -> int:
    """A bound of the time the standard library's TOML reader takes on ``text``, in units of 0.2-0.8 us
    (measured on shapes from lists of numbers to table headers): it is pure Python and spends 8-34 us on
    every value, key, table header or escape (a 33 MB journal took 65 s), about 0.5 us on a line and
    less on other bytes. Counted with bytes.count, before any parsing, so a hostile file cannot make a
    start hang in TOML."""
    return len(text) + LINE_WORK * text.count(b"\n") + COSTLY_WORK * sum(text.count(c) for c in _COSTLY)


def position(text: str, at: int) -> tuple[int, int]:
    """1-based line and column of the character ``at`` of ``text``."""
    return text.count("\n", 0, at) + 1, at - (text.rfind("\n", 0, at) + 1) + 1


def nesting_problem(text: str, depth: int = MAX_DEPTH) -> tuple[int, str] | None:
    """Where (character index) and how ``text`` nests deeper than ``depth`` arrays, inline tables or
    dotted key parts, or None when it does not (strings and comments are skipped; a file with no more
    than ``depth`` brackets is not scanned)."""
    if text.count("[") + text.count("{") > depth:
        level = 0
        for match in _TOKENS.finditer(text):
            token = match.group()
            if token in "[{":
                level += 1
                if level > depth:
                    return match.start(), f"arrays or tables nested more than {depth} deep"
            elif token in "]}":
                level = max(level - 1, 0)
    if text.count(".") > depth:
        for match in _DOTTED.finditer(text):
            if match.group().count(".") >= depth:
                return match.start(), f"a dotted key of more than {depth} parts"
    return None


def loads_toml(text: str, file: str, error: type[LSysError] = LSysError, depth: int = MAX_DEPTH,
               work: int = MAX_WORK) -> dict:
    """``tomllib.loads(text)`` for the user's file ``file``, bounded: nesting deeper than ``depth`` and
    more than ``work`` units of reading (:func:`reading_work`) are refused before parsing; any problem
    is ``error`` at its line and column."""
    cost = reading_work(text.encode("utf-8", "surrogatepass"))
    if cost > work:
        raise error(f"too complex to read in time ({cost:,} units of work, at most {work:,})", file)
    problem = nesting_problem(text, depth)
    if problem is not None:
        raise error(f"nested too deeply: {problem[1]}", file, *position(text, problem[0]))
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        match = re.search(r"line (\d+), column (\d+)", str(exc))
        line, col = (int(match.group(1)), int(match.group(2))) if match else (1, 1)
        last = text.count("\n") + 1 if "end of document" in str(exc) else line  # (an open 'literal' reads on)
        opened = _first_unclosed(text, last)
        if opened is not None:  # (the TOML reader says only "Illegal character '\n'" at the line's end)
            quote, line, col = opened
            raise error(f"the text opened with {quote} at column {col} is not closed: end it with {quote} on the "
                        "same line", file, line, col) from None
        raise error(f"not valid TOML: {exc}", file, line, col) from None
    except (RecursionError, MemoryError):  # a shape the count above missed: still one clear line
        raise error(f"nested too deeply (at most {depth} levels)", file) from None


def read_user_toml(path: str | Path, error: type[LSysError] = LSysError, limit: int = TOML_LIMIT,
                   depth: int = MAX_DEPTH) -> tuple[str, dict]:
    """The text and data of the user's TOML file ``path``: a regular file itself, at most ``limit``
    bytes, nested at most ``depth`` deep, bounded in reading work; else ``error`` with file:line:column."""
    text = read_user_text(path, limit, error)
    return text, loads_toml(text, str(path), error, depth)


def _first_unclosed(text: str, last: int) -> tuple[str, int, int] | None:
    """(quote, line, column) of the first of the first ``last`` lines of ``text`` that opens a one-line
    string and does not close it, or None (the scan stops at a multi-line string)."""
    for number, line in enumerate(text.splitlines()[:last], 1):
        if '"""' in line or "'''" in line:  # a multi-line string: its lines are not one-line texts
            return None
        opened = unclosed_quote(line)
        if opened is not None:
            return opened[0], number, opened[1]
    return None


def unclosed_quote(line: str) -> tuple[str, int] | None:
    """(the quote, its 1-based column) of a string ``line`` opens and does not close, or None (a comment
    ends the scan; a line with a multi-line string's triple quote is left to the TOML reader)."""
    if '"""' in line or "'''" in line:
        return None
    quote, start, k = "", 0, 0
    while k < len(line):
        c = line[k]
        if quote:
            if c == "\\" and quote == '"':
                k += 1
            elif c == quote:
                quote = ""
        elif c in "\"'":
            quote, start = c, k
        elif c == "#":
            return None
        k += 1
    return (quote, start + 1) if quote else None
