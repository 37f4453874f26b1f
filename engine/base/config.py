"""Settings files (TOML) into dataclasses, strictly: they are edited by hand and shared."""

from __future__ import annotations

import math
from dataclasses import fields


def fill_dataclass(target, data: dict, file: str, what: str = "setting") -> None:
    """Set ``target``'s fields from ``data``.

    Unknown keys, values of the wrong type and non-finite numbers raise an LSysError naming the file
    and the key; whole numbers are accepted where a float is expected.
    """
    from arbor.engine.base.errors import LSysError

    kinds = {f.name: type(getattr(target, f.name)) for f in fields(target)}
    for key, value in data.items():
        if key not in kinds:
            raise LSysError(f"unknown {what} {key!r}", file)
        want = kinds[key]
        if want is float and isinstance(value, int) and not isinstance(value, bool):
            value = float(value)
        if not isinstance(value, want) or (want is not bool and isinstance(value, bool)):
            raise LSysError(f"{what} {key!r} must be a {'number' if want is float else want.__name__}", file)
        if want is float and not math.isfinite(value):
            raise LSysError(f"{what} {key!r} must be a finite number", file)
        setattr(target, key, value)
