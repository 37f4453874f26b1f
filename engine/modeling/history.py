"""Undo and redo for editors whose whole state is one value (an L-string, a list of lobes)."""

from __future__ import annotations


class Undoable:
    """Mixin: ``undo_stack``/``redo_stack`` of past values of the attribute named by ``HISTORY_OF``.

    At most ``UNDO_LIMIT`` steps are kept (the oldest go first): a kiosk edits all day long.
    """

    HISTORY_OF = ""
    UNDO_LIMIT = 64
    undo_stack: list
    redo_stack: list

    def commit(self, new) -> None:
        """Make ``new`` the current value, undoably (a new change drops what was undone)."""
        self.undo_stack.append(getattr(self, self.HISTORY_OF))
        del self.undo_stack[: -self.UNDO_LIMIT]
        self.redo_stack.clear()
        setattr(self, self.HISTORY_OF, new)

    def undo(self) -> bool:
        """Take back the last change; False when there is none."""
        if not self.undo_stack:
            return False
        self.redo_stack.append(getattr(self, self.HISTORY_OF))
        setattr(self, self.HISTORY_OF, self.undo_stack.pop())
        return True

    def redo(self) -> bool:
        """Put back the last undone change; False when there is none."""
        if not self.redo_stack:
            return False
        self.undo_stack.append(getattr(self, self.HISTORY_OF))
        setattr(self, self.HISTORY_OF, self.redo_stack.pop())
        return True
