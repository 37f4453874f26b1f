"""Where a game finds its data and keeps its saves (read by the game and its save keeper), and the
player's own settings kept beside the saves (:class:`Preferences`, ``settings.toml``: the sound's volume
and mute and the Away setting, set on the Settings page through :class:`PlayerSettings`)."""

from __future__ import annotations

import logging
import os
import re
from dataclasses import dataclass, field
from pathlib import Path

from arbor.engine.base.config import fill_dataclass, toml_position
from arbor.engine.base.errors import SettingsError
from arbor.engine.base.files import atomic_write, set_aside
from arbor.engine.base.reader import read_user_toml
from arbor.engine.life.world.actions import Action
from arbor.game.paths import ASSETS, default_saves
from arbor.game.strings import text
from arbor.game.watchdog import reading

PREFERENCES = "settings.toml"  # in the saves folder
PREFERENCES_LIMIT = 16_384  # bytes: a longer file is not ours
SAVE_AFTER = 0.5  # seconds a changed setting waits before it is written (a dragged slider writes once)

log = logging.getLogger("arbor.settings")


@dataclass
class GameConfig:
    """Where the game finds its data and keeps its saves."""

    lsystem: Path = ASSETS / "lsystems" / "game_tree.lsys"
    rules: Path = ASSETS / "rules.toml"
    saves: Path = field(default_factory=default_saves)
    autosave_seconds: float = 60.0  # real seconds between autosaves
    resume: bool = True
    seed: int | None = None
    pace: str | None = field(default_factory=lambda: os.environ.get("ARBOR_PACE") or None)  # None: rules.toml's
    title: bool = False  # the title screen over the garden until a key or touch (the window's game shows it)
    sprout: bool = False  # a new sapling is drawn rising from its seed (the window's and the kiosk's games)


@dataclass
class Preferences:
    """The player's settings that are not the garden's: how loud the sound plays (0..1), whether it is
    muted, and Away (the garden is watered while the player is gone: engine/life/keep/away.py). Kept in
    the saves folder's settings.toml, so they outlive a replant or a restored save."""

    volume: float = 0.7
    muted: bool = False
    away: bool = False
    gardener: bool = False  # at 10x and 100x the gardener tends the garden (engine/life/world/guardian.py)
    unlocked: str = ""  # the species of the collection the player has opened by milestones (keys, comma-separated)
    remind: bool = True  # a thirsty tree while the game's window is elsewhere flashes it (game/screens/bell.py)


def check_volume(volume: float, file: str, text: str, key: str = "volume") -> None:
    """A volume outside 0..1 is a SettingsError at its key's line (settings.toml and kiosk.toml)."""
    if not 0.0 <= volume <= 1.0:
        raise SettingsError(f"{key} must be from 0 to 1 (0 silent, 1 loudest), not {volume:g}", file,
                            *toml_position(text, "", key))


def read_preferences(path: Path) -> Preferences:
    """The preferences in ``path`` (defaults when there is no file); a file that is not a small plain
    TOML file of known keys in range is a SettingsError naming it (and the key's line)."""
    prefs = Preferences()
    if not path.exists() and not path.is_symlink():
        return prefs
    text, values = read_user_toml(path, SettingsError, PREFERENCES_LIMIT)
    fill_dataclass(prefs, values, str(path), "setting", SettingsError, text)
    check_volume(prefs.volume, str(path), text)
    return prefs


def bad_settings_line(err: SettingsError, path: Path) -> str:
    """One line for a settings file that could not be read: it is set aside (``settings.toml.broken``,
    so the player's file is kept and not read again at the next start) and the defaults are used."""
    try:
        kept = f"set aside as {set_aside(path).name}"
    except OSError as exc:
        kept = f"left where it is ({exc.strerror or exc})"
    return f"{err} ({kept}; sound settings back to their defaults)"


def write_preferences(prefs: Preferences, path: Path) -> None:
    """Write ``prefs`` to ``path`` atomically (the old file or the new one, never half of it)."""
    text = ("# Arbor's own settings (Settings in the game's menu); the garden is in autosave.arbor.\n"
            f"volume = {round(prefs.volume, 3)!r}\nmuted = {str(prefs.muted).lower()}\n"
            f"away = {str(prefs.away).lower()}  # the garden is watered while you are away\n"
            f"gardener = {str(prefs.gardener).lower()}  # the gardener cares while you skip (10x, 100x)\n"
            f"unlocked = \"{re.sub(r'[^a-z0-9_,]', '', prefs.unlocked)}\"  # species your trees opened\n"
            f"remind = {str(prefs.remind).lower()}  # a thirsty tree flashes the window while you are elsewhere\n")
    atomic_write(path, text.encode("utf-8"))


class PlayerSettings:
    """The Settings page's volume slider, mute button and Away button (the player's own settings):
    they set the game's :class:`Audio <arbor.game.audio.sounds.Audio>` at once and are written to
    settings.toml SAVE_AFTER seconds after the last change (a dragged slider writes the file once), and
    on :meth:`flush`."""

    def __init__(self, audio, folder: Path, clock) -> None:
        self.audio, self.path, self.clock = audio, Path(folder) / PREFERENCES, clock
        self.problem = ""  # one line about a settings file that could not be read ('' when it was fine)
        try:
            with reading(self.path):  # (a watchdog sets aside the file a crash loop died reading)
                self.prefs = read_preferences(self.path)
        except SettingsError as err:
            self.prefs, self.problem = Preferences(), bad_settings_line(err, self.path)
            log.error("%s", self.problem)
        self.changed_at: float | None = None  # when a change not yet written was made
        audio.set_volume(self.prefs.volume, self.prefs.muted)

    def use(self, volume: float) -> None:
        """Play at ``volume``, unmuted, for now (the kiosk's volume for each visitor): not written."""
        self.prefs.volume, self.prefs.muted = min(max(float(volume), 0.0), 1.0), False
        self.audio.set_volume(self.prefs.volume, self.prefs.muted)

    def set_volume(self, volume: float) -> None:
        """The slider: the volume 0..1 (moving it also unmutes: the player wants to hear it)."""
        self.prefs.volume, self.prefs.muted = min(max(float(volume), 0.0), 1.0), False
        self._changed()

    def toggle_mute(self) -> None:
        """The mute button: sound off, or back on at the volume it had."""
        self.prefs.muted = not self.prefs.muted
        self._changed()

    def toggle_away(self) -> bool:
        """The Away button: the garden is watered while the player is gone, or not. Returns it."""
        self.prefs.away = not self.prefs.away
        self._changed()
        return self.prefs.away

    def unlocked(self) -> set[str]:
        """The species the player has opened by milestones (kept in settings.toml)."""
        return {key for key in self.prefs.unlocked.split(",") if key}

    def unlock(self, keys: set[str]) -> None:
        """Keep ``keys`` among the opened species (written with the other settings)."""
        every = self.unlocked() | set(keys)
        if every != self.unlocked():
            self.prefs.unlocked = ",".join(sorted(every))
            self._changed()

    def toggle_gardener(self) -> bool:
        """The Gardener button: at 10x and 100x the gardener tends the garden, or the guardian stops time
        for every need. Returns it."""
        self.prefs.gardener = not self.prefs.gardener
        self._changed()
        return self.prefs.gardener

    def handlers(self, then) -> dict:
        """The Settings page's actions (for the game's one dispatch table): the slider's position is the
        volume, a press of Mute toggles; ``then()`` after each (the menu shows the change)."""
        def volume(value: float) -> None:
            self.set_volume(value)
            then()

        def mute(value: float) -> None:
            if value:  # (pressed, not let go)
                self.toggle_mute()
                then()
        return {Action.VOLUME: volume, Action.MUTE: mute}

    def show(self, menu) -> None:
        """Show the volume and mute on the Settings page of ``menu`` (a game/render/ui.Menu)."""
        menu.widget("volume").value = 0.0 if self.prefs.muted else self.prefs.volume
        menu.widget("mute").label = text("menu.unmute" if self.prefs.muted else "menu.mute")

    def _changed(self) -> None:
        self.audio.set_volume(self.prefs.volume, self.prefs.muted)
        self.changed_at = self.clock()

    def save_if_due(self) -> str:
        """Write a change SAVE_AFTER seconds old (called every frame); returns :meth:`flush`'s line."""
        if self.changed_at is not None and self.clock() - self.changed_at >= SAVE_AFTER:
            return self.flush()
        return ""

    def flush(self) -> str:
        """Write a change not yet written (also on quit). Returns '' or, when the folder cannot be
        written, one line saying so (the change then lasts for this run only)."""
        if self.changed_at is None:
            return ""
        self.changed_at = None
        try:
            write_preferences(self.prefs, self.path)
        except OSError as exc:
            return f"{self.path}: the sound settings could not be kept ({exc.strerror or exc})"
        return ""
