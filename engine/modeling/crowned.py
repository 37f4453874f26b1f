"""The crown's lobes as part of the tree (issue 48): the lobes a crown grew into stay with the tree (its
world keeps them, saves and loads them), so Shape and Crown find them again after Done, a save and load
or a restart (Zhang et al.'s and TreeSketch's lobe editing works on a crown one comes back to)."""

from __future__ import annotations

from dataclasses import dataclass

from arbor.engine.lsystem.lstring import LString
from arbor.engine.modeling.crown_style import CrownStyle
from arbor.engine.modeling.lobes import Lobe

MAX_LOBES = 16  # lobes of one crown (what a save keeps: engine/life/keep/save_crown.py)
MAX_LOBE_VERTICES = 4096  # points of one lobe's mesh ...
MAX_LOBE_FACES = 8192  # ... and its triangles


def too_big(lobes: tuple[Lobe, ...] | list[Lobe]) -> str | None:
    """Why a crown of ``lobes`` could not be kept with its tree (more lobes, or a lobe of more points or
    triangles, than a save holds), None when it can."""
    if len(lobes) > MAX_LOBES:
        return f"{len(lobes)} lobes, at most {MAX_LOBES}"
    for k, lobe in enumerate(lobes, 1):
        if len(lobe.vertices) > MAX_LOBE_VERTICES or len(lobe.faces) > MAX_LOBE_FACES:
            return (f"lobe {k} has {len(lobe.vertices):,} points and {len(lobe.faces):,} triangles, at most "
                    f"{MAX_LOBE_VERTICES:,} and {MAX_LOBE_FACES:,}")
    return None


@dataclass(frozen=True, eq=False)
class CrownRecord:
    """The lobes a crown grew into, ``base`` the tree before that crown (None when it is not known: a
    tree saved after it grew on), ``grown`` the L-string the crown made (None: not known) and ``style``
    how it grew."""

    lobes: tuple[Lobe, ...]
    base: LString | None = None
    grown: LString | None = None
    style: CrownStyle | None = None  # how it grew (the crown panel; None: the defaults; saved as crown_style)

    def base_for(self, ls: LString) -> LString:
        """What a lobe edit regrows the crown from on the tree ``ls``: the tree before the crown while
        ``ls`` is the crown as it grew; else ``ls`` itself (it grew on, or strokes were drawn on it since:
        all kept, the crown grows on from it into the edited lobes)."""
        return self.base if self.base is not None and self.grown is ls else ls
