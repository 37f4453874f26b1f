"""A position-tracking cursor over one line of untrusted text, shared by all our small parsers."""

from __future__ import annotations

import re

from arbor.engine.base.errors import LSysError

_NUMBER = re.compile(r"(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")
_NAME = re.compile(r"[A-Za-z_][A-Za-z_0-9]*")


class Cursor:
    """Reads one line of text left to right and reports errors at the current column."""

    def __init__(self, text: str, file: str = "<string>", line: int = 1, col0: int = 0) -> None:
        self.text = text
        self.pos = 0
        self.file = file
        self.line = line
        self.col0 = col0  # column offset of text[0] within the real line

    def error(self, message: str, pos: int | None = None) -> LSysError:
        """Build (not raise) an error pointing at ``pos`` (default: the current position)."""
        at = self.pos if pos is None else pos
        return LSysError(message, self.file, self.line, self.col0 + at + 1)

    def skip_ws(self) -> None:
        """Skip spaces and tabs."""
        text, pos = self.text, self.pos
        while pos < len(text) and text[pos] in " \t\r":
            pos += 1
        self.pos = pos

    def at_end(self) -> bool:
        """True when only whitespace is left."""
        self.skip_ws()
        return self.pos >= len(self.text)

    def peek(self, n: int = 1) -> str:
        """The next ``n`` characters after whitespace ('' at the end)."""
        self.skip_ws()
        return self.text[self.pos : self.pos + n]

    def accept(self, token: str) -> bool:
        """Consume ``token`` if it comes next."""
        if self.peek(len(token)) == token:
            self.pos += len(token)
            return True
        return False

    def expect(self, token: str, what: str | None = None) -> None:
        """Consume ``token`` or raise an error saying it was expected."""
        if not self.accept(token):
            found = self.describe_next()
            raise self.error(f"expected {what or repr(token)}, found {found}")

    def describe_next(self) -> str:
        """A short human description of what comes next, for error messages."""
        self.skip_ws()
        if self.pos >= len(self.text):
            return "end of line"
        return repr(self.text[self.pos])

    def number(self) -> float | None:
        """Consume an unsigned decimal number literal, or return None if none comes next."""
        self.skip_ws()
        m = _NUMBER.match(self.text, self.pos)
        if not m:
            return None
        self.pos = m.end()
        return float(m.group())

    def name(self) -> str | None:
        """Consume an identifier, or return None if none comes next."""
        self.skip_ws()
        m = _NAME.match(self.text, self.pos)
        if not m:
            return None
        self.pos = m.end()
        return m.group()
