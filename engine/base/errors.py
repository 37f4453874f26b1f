"""Error types raised by the engine for bad (possibly hostile) input."""

from __future__ import annotations


class LSysError(Exception):
    """A problem in an .lsys source, an L-string text or a save file.

    Carries the file name, 1-based line and column so a player who shared a broken file can be told
    exactly where it is broken. ``str()`` gives ``file:line:col: message``.
    """

    def __init__(self, message: str, file: str = "<string>", line: int = 1, col: int = 1) -> None:
        self.message = message
        self.file = file
        self.line = line
        self.col = col
        super().__init__(f"{file}:{line}:{col}: {message}")

