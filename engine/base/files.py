"""Crash-safe file writing (nothing already saved is ever left half-written), reading only regular files,
setting bad files aside under names of their own, and a folder lock (one writer per saves folder)."""

from __future__ import annotations

import atexit
import contextlib
import errno
import glob
import os
from pathlib import Path

__all__ = ["FolderBusyError", "FolderLock", "atomic_write", "remove_stale_temp_files", "set_aside"]


def atomic_write(path: str | Path, data: bytes) -> None:
    """Write ``data`` to a temp file beside ``path``, fsync it, then rename it over ``path``.

    A crash at any moment leaves either the old file or the new one, never a mix.
    """
    path = Path(path)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    remove_stale_temp_files(path.parent, glob.escape(path.name), own=False)  # (writes a kill -9 cut short)
    if not path.parent.is_dir():  # say so by the folder's name, not the temp file's (an error a user reads)
        raise FileNotFoundError(errno.ENOENT, f"no such folder (to write {path.name} in)", str(path.parent))
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


def remove_stale_temp_files(folder: Path, name: str = "*", own: bool = True) -> int:
    """Delete the temp files (``.NAME.PID.tmp``, NAME matching the glob ``name``) that a write cut short
    left behind: a killed process's (a dead pid), and (``own``) our own from an earlier failed write.
    Returns how many; never raises (a folder that cannot be listed or written keeps them)."""
    removed = 0
    try:
        candidates = list(Path(folder).glob(f".{name}.*.tmp"))
    except OSError:
        return 0
    for tmp in candidates:
        parts = tmp.name.rsplit(".", 2)
        pid = int(parts[1]) if len(parts) == 3 and parts[1].isdigit() else None
        if pid is not None and ((pid != os.getpid() and _pid_alive(pid)) or (pid == os.getpid() and not own)):
            continue  # (a live process may be writing it now)
        try:
            tmp.unlink()
            removed += 1
        except OSError:
            pass
    return removed


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


LOCK_NAME = ".arbor.lock"  # in a saves folder: the pid of the process that has it open


class FolderBusyError(OSError):
    """Another live process holds a folder's lock; ``pid`` is that process (0 when it cannot be read)."""

    def __init__(self, folder: Path, pid: int) -> None:
        super().__init__(errno.EBUSY, f"in use by another Arbor (pid {pid or 'unknown'})", str(folder))
        self.folder, self.pid = folder, pid


class FolderLock:
    """An advisory lock on a folder for as long as this process lives (or until :meth:`release`): a file
    ``.arbor.lock`` holding the holder's pid, locked with ``flock``. The operating system drops the lock
    when the holder dies, even by kill -9, so a stale lock (a dead pid in the file) is simply taken over:
    a watchdog's restart never waits for one. A folder where the lock file cannot be made (read-only) is
    not locked: nothing can be written there, so nothing can be lost (``held`` is False)."""

    def __init__(self, folder: str | Path) -> None:
        self.folder = Path(folder)
        self.fd: int | None = None

    @property
    def held(self) -> bool:
        """True while this process holds the lock."""
        return self.fd is not None

    def acquire(self) -> FolderLock:
        """Take the lock and write our pid into it; raises :class:`FolderBusyError` naming the live holder."""
        for _ in range(8):  # (a holder releasing meanwhile removes the file we opened: open the new one)
            fd = self._try_acquire()
            if fd is None:
                return self  # a folder nothing can be written to: no lock needed
            if _is_file_at(fd, self.folder / LOCK_NAME):
                os.ftruncate(fd, 0)
                os.pwrite(fd, f"{os.getpid()}\n".encode("ascii"), 0)
                self.fd = fd
                atexit.register(self.release)  # a start that fails (no display) leaves no lock file behind
                return self
            os.close(fd)
        raise FolderBusyError(self.folder, 0)

    def _try_acquire(self) -> int | None:
        """Open the lock file and lock it: its descriptor, None for a folder that cannot be written."""
        import fcntl

        path = self.folder / LOCK_NAME
        try:
            self.folder.mkdir(parents=True, exist_ok=True)
            fd = os.open(path, os.O_RDWR | os.O_CREAT | getattr(os, "O_NOFOLLOW", 0), 0o644)
        except OSError as exc:
            if exc.errno in (errno.EROFS, errno.EACCES, errno.EPERM, errno.ENOENT):
                return None
            raise
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            pid = _pid_in(fd)
            os.close(fd)
            raise FolderBusyError(self.folder, pid) from None
        except OSError as exc:  # a file system without flock: the pid alone says who holds it
            if exc.errno not in (errno.ENOLCK, errno.EOPNOTSUPP, errno.EINVAL):
                os.close(fd)
                raise
            pid = _pid_in(fd)
            if pid and pid != os.getpid() and _pid_alive(pid):
                os.close(fd)
                raise FolderBusyError(self.folder, pid) from None
        return fd

    def release(self) -> None:
        """Give the lock up and remove its file (while still holding it: a process that opened the file
        meanwhile finds it gone once it holds it, and opens the next). A holder that died leaves the file;
        the next holder takes it over."""
        if self.fd is not None:
            path = self.folder / LOCK_NAME
            if _is_file_at(self.fd, path):
                with contextlib.suppress(OSError):
                    path.unlink()
            os.close(self.fd)
            self.fd = None


def _is_file_at(fd: int, path: Path) -> bool:
    """Whether ``path`` still names the file open as ``fd`` (not removed nor replaced since it was opened)."""
    try:
        here, there = os.fstat(fd), os.stat(path, follow_symlinks=False)
    except OSError:
        return False
    return (here.st_dev, here.st_ino) == (there.st_dev, there.st_ino)


def _pid_in(fd: int) -> int:
    """The pid written in a lock file (0 when it holds none)."""
    text = os.pread(fd, 32, 0).decode("ascii", "replace").strip()
    return int(text) if text.isdigit() else 0


def _pid_alive(pid: int) -> bool:
    """Whether a process with this pid exists (signal 0 is sent to nobody; it only checks)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:  # it exists, owned by someone else
        return True
    return True
