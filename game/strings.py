"""User-facing text, loaded from assets/strings/<language>.toml (editable without code).

On a touch screen (the kiosk: :func:`set_touch`) a text that names keys has its touch form: ``section.name``
is read from the table ``[touch_section]`` when that has ``name`` (no "press G", no "(W)" on a kiosk)."""

from __future__ import annotations

import re
from pathlib import Path

from arbor.engine.base.errors import SettingsError
from arbor.engine.base.reader import read_user_toml
from arbor.game.paths import ASSETS

STRINGS_DIR = ASSETS / "strings"
_table: dict[str, dict[str, str]] = {}
_language = ""
_touch = False  # the texts for a touch screen (see module docstring)


LANGUAGE = re.compile(r"[a-z]{2,3}([_-][A-Za-z]{2,4})?")  # a language's file name: en, fr, pt_BR, zh-Hans
STRINGS_LIMIT = 256 * 1024  # bytes of a strings file (English is about 20 KB)


def set_language(language: str = "en", folder: Path = STRINGS_DIR) -> str:
    """Load a strings file (through the one reader for users' files: a translation is written by hand);
    keys missing from it fall back to English. Returns '' or one line saying why the language's file
    could not be used (then the text stays English): a bad translation must not stop a kiosk."""
    global _table, _language
    _, base = read_user_toml(folder / "en.toml", SettingsError, STRINGS_LIMIT)
    problem = ""
    if language != "en":
        try:
            if not LANGUAGE.fullmatch(language):
                raise SettingsError(f"{language!r} is not a language's name (en, fr, pt_BR, ...)", str(folder))
            _, override = read_user_toml(folder / f"{language}.toml", SettingsError, STRINGS_LIMIT)
            for section, values in override.items():
                if not isinstance(values, dict) or not all(isinstance(v, str) for v in values.values()):
                    raise SettingsError(f"[{section}] must be a table of texts in quotes", f"{folder / language}.toml")
                base.setdefault(section, {}).update(values)
        except SettingsError as err:
            problem, language = f"{err} (the text stays English)", "en"
            _, base = read_user_toml(folder / "en.toml", SettingsError, STRINGS_LIMIT)
    _table, _language = base, language
    return problem


def set_touch(touch: bool) -> None:
    """Use the touch forms of the texts (a kiosk: nobody has keys), or the keyboard's (the game)."""
    global _touch
    _touch = bool(touch)


def text(key: str, **values) -> str:
    """The text for 'section.name' (its touch form on a touch screen), with {placeholders} filled in."""
    if not _table:
        set_language(_language or "en")
    section, _, name = key.partition(".")
    touch = _table.get(f"touch_{section}", {}) if _touch else {}
    template = touch.get(name) or _table.get(section, {}).get(name, key)
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
