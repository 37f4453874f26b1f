"""Crash-safe file writing: nothing already saved is ever left half-written."""

from __future__ import annotations

import errno
import os
import stat
from pathlib import Path


def atomic_write(path: str | Path, data: bytes) -> None:
    """Write ``data`` to a temp file beside ``path``, fsync it, then rename it over ``path``.

    A crash at any moment leaves either the old file or the new one, never a mix.
    """
    path = Path(path)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        with open(_new_file(tmp), "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    finally:
        if tmp.exists() or tmp.is_symlink():
            tmp.unlink()
    try:
        dir_fd = os.open(path.parent, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(dir_fd)
    finally:
        os.close(dir_fd)


def _new_file(tmp: Path) -> int:
    """A new regular file at ``tmp``, never opened through a link planted there (O_EXCL | O_NOFOLLOW):
    whatever sits at the temp name (a stale temp file, a symlink to a file elsewhere) is removed first,
    the link itself and never what it points to."""
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0)
    try:
        return os.open(tmp, flags, 0o644)
    except FileExistsError:
        tmp.unlink()
        return os.open(tmp, flags, 0o644)


def read_regular(path: str | Path, limit: int) -> bytes:
    """At most ``limit + 1`` bytes of ``path`` if it is a regular file itself: a symlink (to a file
    outside the folder, say), a FIFO (which would block the start) or a device is an OSError, not read."""
    fd = os.open(path, os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_NONBLOCK", 0))
    try:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            raise OSError(errno.EINVAL, "not a regular file (a save must be a plain file)")
        with os.fdopen(os.dup(fd), "rb") as fh:
            return fh.read(limit + 1)
    finally:
        os.close(fd)


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
