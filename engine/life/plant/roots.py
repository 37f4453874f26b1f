"""Roots: a second L-system (assets/lsystems/roots.lsys) grown below ground by the water the tree takes up.

The root clock runs while the water meter is above a fifth, faster the fuller it is (so watering grows
roots); each time it passes the rules' step the roots' L-string is rewritten once, inside its own module
budget. A larger root system drains the water meter more slowly (``drain_relief`` at most, reached at
``full_length`` scene units of roots; [roots] in rules.toml): a well-rooted tree needs water less often.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from arbor.engine.base.assets import assets_dir
from arbor.engine.geometry.turtle import Segments, TurtleConfig, TurtleResult, interpret
from arbor.engine.lsystem.derive import Deriver
from arbor.engine.lsystem.lstring import LString
from arbor.engine.lsystem.lsys import LSystem, load_lsystem

ROOTS_LSYS = assets_dir() / "lsystems" / "roots.lsys"
PIECE = ord("F")
_cached: LSystem | None = None


def root_system() -> LSystem:
    """The roots' L-system (read once)."""
    global _cached
    if _cached is None:
        _cached = load_lsystem(ROOTS_LSYS)
    return _cached


@dataclass
class Roots:
    """One tree's roots: their L-string and the root time of its last rewrite."""

    seed: int = 0
    lstring: LString | None = None
    last_rewrite: float = 0.0
    system: LSystem = field(default_factory=root_system)

    def __post_init__(self) -> None:
        self.deriver = Deriver(self.system, seed=self.seed)
        if self.lstring is None:
            self.lstring = self.system.axiom

    def grow(self, root_time: float, step: float) -> bool:
        """Rewrite once if the root clock has passed one step since the last rewrite; True if it did."""
        if root_time - self.last_rewrite < step:
            return False
        self.lstring, _ = self.deriver.step(self.lstring, {"T": root_time, "DT": root_time - self.last_rewrite})
        self.last_rewrite = root_time
        return True

    def length(self) -> float:
        """Total length of the roots (scene units): the sum of their pieces."""
        ls = self.lstring
        pieces = (ls.sym == PIECE) & (ls.nparams >= 1)
        return float(ls.params[ls.offsets[pieces]].sum()) if pieces.any() else 0.0

    def share(self, full_length: float) -> float:
        """How much of a full root system the tree has (0..1)."""
        return min(self.length() / max(full_length, 1e-9), 1.0)

    def turtle(self) -> TurtleResult:
        """The roots as the turtle draws them, below the tree's foot (wood only)."""
        return interpret(self.lstring, TurtleConfig(angle=self.system.angle, leaves_at_tips=0, pipe_model=False))

    def segments(self) -> Segments:
        """The roots as turtle segments."""
        return self.turtle().segments

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """Lowest and highest corner of the roots."""
        segs = self.segments()
        if not len(segs):
            return np.zeros(3), np.zeros(3)
        pts = np.concatenate([segs.start, segs.end])
        return pts.min(axis=0), pts.max(axis=0)
