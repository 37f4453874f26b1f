"""Crash-safe file writing: nothing already saved is ever left half-written."""

from __future__ import annotations

import os
from pathlib import Path


def atomic_write(path: str | Path, data: bytes) -> None:
    """Write ``data`` to a temp file beside ``path``, fsync it, then rename it over ``path``.

    A crash at any moment leaves either the old file or the new one, never a mix.
    """
    path = Path(path)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        with open(tmp, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()
    try:
        dir_fd = os.open(path.parent, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(dir_fd)
    finally:
        os.close(dir_fd)


def set_aside(path: str | Path, suffix: str = ".broken") -> Path:
    """Rename ``path`` to the first free ``NAME.broken``, ``NAME.2.broken``, ... beside it and return the
    new path: a second bad file never overwrites the first one kept (a hard link claims the name
    atomically, so two processes cannot pick the same one). Raises OSError (a read-only folder)."""
    path = Path(path)
    for n in range(1, 10_000):
        kept = path.with_name(f"{path.name}{'' if n == 1 else f'.{n}'}{suffix}")
        try:
            os.link(path, kept, follow_symlinks=False)
        except FileExistsError:
            continue
        except OSError:  # no hard links here (some USB sticks): a plain rename to a free name
            if kept.exists() or kept.is_symlink():
                continue
            os.rename(path, kept)
            return kept
        os.unlink(path)
        return kept
    raise FileExistsError(f"too many kept copies of {path.name}")
