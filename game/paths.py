"""Where Arbor finds its data (assets/) and keeps player saves, in a checkout and when installed."""

from __future__ import annotations

import os
from pathlib import Path

from arbor.engine.base.assets import assets_dir
from arbor.engine.base.files import FolderBusyError, FolderLock
from arbor.game.errors import UserError

ROOT = Path(__file__).resolve().parent.parent


def default_saves() -> Path:
    """saves/ in a checkout; otherwise the user's data folder (never inside site-packages)."""
    if (ROOT / "saves").is_dir() and (ROOT / "pyproject.toml").is_file():
        return ROOT / "saves"
    base = os.environ.get("XDG_DATA_HOME") or str(Path.home() / ".local" / "share")
    return Path(base) / "arbor" / "saves"


def lock_saves(folder: Path) -> FolderLock:
    """Hold ``folder``'s lock for this process's life (two games writing one folder would lose each
    other's trees): a second Arbor on the same folder ends in one line naming the process that has it.
    A lock left by a process that died (kill -9, a crash, a watchdog's restart) is taken over."""
    try:
        return FolderLock(folder).acquire()
    except FolderBusyError as busy:
        raise UserError(f"the saves folder {folder} is in use by another Arbor (pid {busy.pid or 'unknown'}): "
                        "close that one first, or start this one with --saves ANOTHER_FOLDER") from None


ASSETS = assets_dir()
