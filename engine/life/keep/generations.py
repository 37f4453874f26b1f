"""Earlier generations of the autosave: ``autosave.1.arbor`` (the last one) ... ``autosave.5.arbor``.

Before each autosave the file about to be replaced becomes generation 1 and the older ones move one
down (the oldest dropped), so one careless key (a replanted tree, a bad load) and the next autosave
never lose a garden: Settings -> Restore brings an earlier one back. Each move is an atomic rename;
the copy of the current file is written beside its place first and renamed in. A link or a FIFO
planted under any of these names is never followed or read (it would hang an import or a quit).
"""

from __future__ import annotations

import os
import stat
from pathlib import Path

from arbor.engine.base.files import atomic_write
from arbor.engine.base.reader import open_regular

KEEP = 5  # generations kept besides the autosave itself


def generation(path: Path, n: int) -> Path:
    """Generation ``n`` (1 = the newest) of the save ``path``: ``autosave.arbor`` -> ``autosave.N.arbor``."""
    return path.with_name(f"{path.stem}.{n}{path.suffix}")


def generations(path: Path, keep: int = KEEP) -> list[Path]:
    """The generations of ``path`` that exist, newest first."""
    return [g for g in (generation(path, n) for n in range(1, keep + 1)) if g.exists()]


def _regular(path: Path) -> bool:
    """Whether ``path`` itself (not what a link there points to) is a regular file."""
    try:
        return stat.S_ISREG(os.lstat(path).st_mode)
    except OSError:
        return False


def _same(first: Path, path: Path) -> bool:
    """Whether the regular files ``first`` and ``path`` hold the same bytes (read without following links
    or waiting on a FIFO; a file that cannot be read so is not the same)."""
    try:
        a, b = open_regular(first), open_regular(path)
    except OSError:
        return False
    with os.fdopen(a, "rb") as fa, os.fdopen(b, "rb") as fb:
        if os.fstat(fa.fileno()).st_size != os.fstat(fb.fileno()).st_size:
            return False
        return fa.read() == fb.read()


def rotate(path: Path, keep: int = KEEP) -> None:
    """Keep the file ``path`` as generation 1 before it is overwritten (older ones move down, the oldest
    goes); nothing happens when there is no file yet or it is the same as generation 1. Only a regular
    file is copied and compared (never through a link, never waiting on a FIFO planted under a
    generation's name: such a name is only renamed down the line like any generation)."""
    if not _regular(path):
        return
    first = generation(path, 1)
    if _regular(first) and _same(first, path):
        return
    for n in range(keep - 1, 0, -1):
        older = generation(path, n)
        if older.exists() or older.is_symlink():
            os.replace(older, generation(path, n + 1))
    try:
        source = open_regular(path)
    except OSError:
        return
    with os.fdopen(source, "rb") as fh:
        atomic_write(first, fh.read())  # (a temp file beside it, renamed in)
