"""Where Arbor finds its data (assets/) and keeps player saves, in a checkout and when installed."""

from __future__ import annotations

import importlib.util
import os
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def _assets() -> Path:
    """The assets folder: beside the packages in a checkout, or the installed `arbor_assets` package."""
    here = ROOT / "assets"
    if here.is_dir():
        return here
    spec = importlib.util.find_spec("arbor_assets")
    if spec is not None and spec.submodule_search_locations:
        return Path(next(iter(spec.submodule_search_locations)))
    return here


def default_saves() -> Path:
    """saves/ in a checkout; otherwise the user's data folder (never inside site-packages)."""
    if (ROOT / "saves").is_dir() and (ROOT / "pyproject.toml").is_file():
        return ROOT / "saves"
    base = os.environ.get("XDG_DATA_HOME") or str(Path.home() / ".local" / "share")
    return Path(base) / "arbor" / "saves"


ASSETS = _assets()
