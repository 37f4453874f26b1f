"""User-facing text, loaded from assets/strings/<language>.toml (editable without code)."""

from __future__ import annotations

import tomllib
from pathlib import Path

from arbor.game.paths import ASSETS

STRINGS_DIR = ASSETS / "strings"
_table: dict[str, dict[str, str]] = {}
_language = ""


def set_language(language: str = "en", folder: Path = STRINGS_DIR) -> None:
    """Load a strings file; keys missing from it fall back to English."""
    global _table, _language
    base = tomllib.loads((folder / "en.toml").read_text(encoding="utf-8"))
    if language != "en":
        override = tomllib.loads((folder / f"{language}.toml").read_text(encoding="utf-8"))
        for section, values in override.items():
            base.setdefault(section, {}).update(values)
    _table, _language = base, language


def text(key: str, **values) -> str:
    """The text for 'section.name', with {placeholders} filled in."""
    if not _table:
        set_language(_language or "en")
    section, _, name = key.partition(".")
    template = _table.get(section, {}).get(name, key)
    try:
        return template.format(**values)
    except (KeyError, IndexError, ValueError):
        return template


def duration(seconds: float) -> str:
    """A span of time the way a player reads it: seconds, minutes, hours or days."""
    if seconds < 90:
        return text("hud.seconds", seconds=seconds)
    if seconds < 5400:
        return text("hud.minutes", minutes=seconds / 60)
    if seconds < 172800:
        return text("hud.hours", hours=seconds / 3600)
    return text("hud.days", days=seconds / 86400)
