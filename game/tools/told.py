"""What the modeler's toasts say changed: counts with their nouns in the singular or plural, and what an
undo took away or a redo put back (branch pieces, leaves, growth points, the crown's lobes); undo and
redo of the modeling mode, which say so."""

from __future__ import annotations

import numpy as np

from arbor.engine.life.world.commands import Redo, Undo
from arbor.engine.lsystem.lstring import LString
from arbor.game.strings import text

TOLD = (("FI", "branch piece"), ("L", "leaf"), ("A", "growth point"), ("K", "blossom"))  # symbols, noun
PLURALS = {"leaf": "leaves"}


def counted(count: int, noun: str) -> str:
    """'1 growth point', '3 growth points', '2 leaves'."""
    return f"{count} {noun if count == 1 else PLURALS.get(noun, noun + 's')}"


def _counts(ls: LString) -> dict[str, int]:
    return {noun: int(np.isin(ls.sym, [ord(c) for c in symbols]).sum()) for symbols, noun in TOLD}


def change_told(before: LString, after: LString, lobes_before: int, lobes_after: int) -> str:
    """What a step from ``before`` to ``after`` changed, in words: the modules taken away or put back by
    kind, and the crown's lobes when their number changed ('14 branch pieces and 2 leaves taken away, the
    crown in 1 lobe')."""
    old, new = _counts(before), _counts(after)
    gone = [counted(old[n] - new[n], n) for n in old if old[n] > new[n]]
    back = [counted(new[n] - old[n], n) for n in old if new[n] > old[n]]
    parts = []
    if gone:
        parts.append(text("messages.change_removed", things=" and ".join(gone)))
    if back:
        parts.append(text("messages.change_added", things=" and ".join(back)))
    if lobes_before != lobes_after:
        parts.append(text("messages.change_lobes", lobes=counted(lobes_after, "lobe")) if lobes_after
                     else text("messages.change_no_lobes"))
    if not parts:
        changed = int(np.count_nonzero(before.sym[:len(after)] != after.sym[:len(before)]))
        parts.append(text("messages.change_same", count=counted(max(changed, abs(len(before) - len(after)), 1),
                                                                  "module")))
    return ", ".join(parts)


class HistoryTold:
    """Mixin of the modeling mode (game/screens/modeler.py): undo and redo that say what they changed. It
    uses the mode's ``follow``, ``modeler``, ``crown_tool`` and ``state``."""

    def undo(self) -> None:
        """Take back the last stroke (and say so, or that there is nothing to take back)."""
        self._step_history(Undo(), "undone", "undo_none")

    def redo(self) -> None:
        """Put back the last undone stroke (and say so, or that there is nothing to put back)."""
        self._step_history(Redo(), "redone", "redo_none")

    def _step_history(self, command: Undo | Redo, done: str, none: str) -> None:
        self.follow()
        if self.modeler is None:
            self.state.say(text(f"messages.{none}"))
            return
        before, lobes = self.modeler.lstring, len(self.crown_tool.state().lobes)
        if self.state.world.apply(command):
            what = change_told(before, self.modeler.lstring, lobes, len(self.crown_tool.state().lobes))
            self.state.say(text(f"messages.{done}", what=what))
        else:
            self.state.say(text(f"messages.{none}"))
