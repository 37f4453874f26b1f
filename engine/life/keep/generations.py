"""Earlier generations of the autosave: ``autosave.1.arbor`` (the last one) ... ``autosave.5.arbor``.

Before each autosave the file about to be replaced becomes generation 1 and the older ones move one
down (the oldest dropped), so one careless key (a replanted tree, a bad load) and the next autosave
never lose a garden: Settings -> Restore brings an earlier one back. Each move is an atomic rename;
the copy of the current file is written beside its place first and renamed in.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

KEEP = 5  # generations kept besides the autosave itself


def generation(path: Path, n: int) -> Path:
    """Generation ``n`` (1 = the newest) of the save ``path``: ``autosave.arbor`` -> ``autosave.N.arbor``."""
    return path.with_name(f"{path.stem}.{n}{path.suffix}")


def generations(path: Path, keep: int = KEEP) -> list[Path]:
    """The generations of ``path`` that exist, newest first."""
    return [g for g in (generation(path, n) for n in range(1, keep + 1)) if g.exists()]


def rotate(path: Path, keep: int = KEEP) -> None:
    """Keep the file ``path`` as generation 1 before it is overwritten (older ones move down, the oldest
    goes); nothing happens when there is no file yet or it is the same as generation 1."""
    if not path.exists():
        return
    first = generation(path, 1)
    if first.exists() and first.read_bytes() == path.read_bytes():
        return
    for n in range(keep - 1, 0, -1):
        older = generation(path, n)
        if older.exists():
            os.replace(older, generation(path, n + 1))
    part = first.with_name(f".{first.name}.{os.getpid()}.tmp")
    shutil.copyfile(path, part)
    os.replace(part, first)
