"""Where Arbor's data (assets/) is: beside engine/ in a checkout, the installed `arbor.assets` when installed."""

from __future__ import annotations

import importlib.util
from pathlib import Path

CHECKOUT = Path(__file__).resolve().parents[2]


def assets_dir() -> Path:
    """The assets folder, in a checkout (``pip install -e``) or installed (``pip install .``)."""
    here = CHECKOUT / "assets"
    if (here / "lsystems" / "game_tree.lsys").is_file():  # ours, not some other package's "assets"
        return here
    spec = importlib.util.find_spec("arbor.assets")
    if spec is not None and spec.submodule_search_locations:
        return Path(next(iter(spec.submodule_search_locations)))
    return here
