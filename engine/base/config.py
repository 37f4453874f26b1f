"""Settings files (TOML) into dataclasses, strictly: they are edited by hand and shared."""

from __future__ import annotations

import math
import re
from dataclasses import fields
from pathlib import Path

from arbor.engine.base.errors import LSysError, SettingsError
from arbor.engine.base.reader import read_user_toml

_HEADER = re.compile(r"\s*\[\[?([^\]]*)\]\]?\s*(#.*)?$")


def read_toml(path: str | Path, error: type[LSysError]) -> tuple[str, dict]:
    """A TOML file a user wrote: its text and its data, read by the one reader for users' files
    (:func:`arbor.engine.base.reader.read_user_toml`: a regular file, size, nesting and work bounded); any
    problem is ``error`` naming the file, line and column."""
    return read_user_toml(path, error)


def toml_position(text: str, table: str = "", key: str | None = None) -> tuple[int, int]:
    """1-based line and column of ``key`` in ``[table]`` of a TOML ``text`` (of the table's header when
    ``key`` is None; ``""`` is the top level), or (1, 1) when it is not there.

    tomllib gives no positions, so the lines are scanned: enough for hand-edited settings files, where a
    key is written ``key = ...`` or ``"key" = ...`` on its own line.
    """
    current = ""
    for number, line in enumerate(text.splitlines(), 1):
        header = _HEADER.match(line)
        if header:
            current = re.sub(r"[\s\"']", "", header.group(1))
            if key is None and current == table:
                return number, line.index("[") + 1
        elif key is not None and current == table and re.match(rf"\s*([\"']?){re.escape(key)}\1\s*=", line):
            return number, len(line) - len(line.lstrip()) + 1
    return 1, 1


def fill_dataclass(target, data: dict, file: str, what: str = "setting", error: type[LSysError] = SettingsError,
                   text: str = "", table: str = "") -> None:
    """Set ``target``'s fields from ``data`` (the table ``table`` of the TOML ``text``).

    Unknown keys, values of the wrong type and non-finite numbers raise ``error`` naming the file, the
    key and (given the text) the key's line and column; whole numbers are accepted where a float is expected.
    """
    kinds = {f.name: type(getattr(target, f.name)) for f in fields(target)}
    for key, value in data.items():
        where = toml_position(text, table, key)
        if key not in kinds:
            raise error(f"unknown {what} {key!r}", file, *where)
        want = kinds[key]
        if want is float and isinstance(value, int) and not isinstance(value, bool):
            value = float(value)
        if not isinstance(value, want) or (want is not bool and isinstance(value, bool)):
            raise error(f"{what} {key!r} must be a {'number' if want is float else want.__name__}", file, *where)
        if want is float and not math.isfinite(value):
            raise error(f"{what} {key!r} must be a finite number", file, *where)
        setattr(target, key, value)
