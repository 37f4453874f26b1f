"""The crown's lobes as part of the tree (issue 48): the lobes a crown grew into stay with the tree (its
world keeps them, saves and loads them), so Shape and Crown find them again after Done, a save and load
or a restart (Zhang et al.'s and TreeSketch's lobe editing works on a crown one comes back to)."""

from __future__ import annotations

from dataclasses import dataclass

from arbor.engine.lsystem.lstring import LString
from arbor.engine.modeling.lobes import Lobe


@dataclass(frozen=True, eq=False)
class CrownRecord:
    """The lobes a crown grew into, ``base`` the tree before that crown (None when it is not known: a
    tree saved after it grew on) and ``grown`` the L-string the crown made (None: not known)."""

    lobes: tuple[Lobe, ...]
    base: LString | None = None
    grown: LString | None = None

    def base_for(self, ls: LString) -> LString:
        """What a lobe edit regrows the crown from on the tree ``ls``: the tree before the crown while
        ``ls`` is the crown as it grew; else ``ls`` itself (it grew on, or strokes were drawn on it since:
        all kept, the crown grows on from it into the edited lobes)."""
        return self.base if self.base is not None and self.grown is ls else ls
