"""Error types raised by the engine for bad (possibly hostile) input, one per kind of file."""

from __future__ import annotations


class LSysError(Exception):
    """A problem in a file the engine reads: an .lsys source, an L-string text, a save file, or one of
    the kinds below (every caller that reports a bad file catches this one).

    Carries the file name, 1-based line and column so a player who shared a broken file can be told
    exactly where it is broken. ``str()`` gives ``file:line:col: message``; a file that has no lines (a
    picture: the message says the byte) gives line 0 and ``file: message``.
    """

    def __init__(self, message: str, file: str = "<string>", line: int = 1, col: int = 1) -> None:
        self.message = message
        self.file = file
        self.line = line
        self.col = col
        super().__init__(f"{file}:{line}:{col}: {message}" if line > 0 else f"{file}: {message}")


class RulesError(LSysError):
    """A problem in the game rules (assets/rules.toml, a pace's overrides)."""


class ExperimentError(LSysError):
    """A problem in a lab experiment file (its trees, regimes and rule overrides)."""


class SweepError(LSysError):
    """A problem in a sweep file (its factors, levels, seeds and responses)."""


class SettingsError(LSysError):
    """A problem in a settings file read into a dataclass (kiosk.toml, a species preset)."""
