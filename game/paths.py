"""Where Arbor finds its data (assets/) and keeps player saves, in a checkout and when installed."""

from __future__ import annotations

import os
from pathlib import Path

from arbor.engine.base.assets import assets_dir

ROOT = Path(__file__).resolve().parent.parent


def default_saves() -> Path:
    """saves/ in a checkout; otherwise the user's data folder (never inside site-packages)."""
    if (ROOT / "saves").is_dir() and (ROOT / "pyproject.toml").is_file():
        return ROOT / "saves"
    base = os.environ.get("XDG_DATA_HOME") or str(Path.home() / ".local" / "share")
    return Path(base) / "arbor" / "saves"


ASSETS = assets_dir()
