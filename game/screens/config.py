"""Where a game finds its data and keeps its saves (read by the game and its save keeper)."""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path

from arbor.game.paths import ASSETS, default_saves


@dataclass
class GameConfig:
    """Where the game finds its data and keeps its saves."""

    lsystem: Path = ASSETS / "lsystems" / "game_tree.lsys"
    rules: Path = ASSETS / "rules.toml"
    saves: Path = field(default_factory=default_saves)
    autosave_seconds: float = 60.0  # real seconds between autosaves
    resume: bool = True
    seed: int | None = None
    pace: str | None = field(default_factory=lambda: os.environ.get("ARBOR_PACE") or None)  # None: rules.toml's
