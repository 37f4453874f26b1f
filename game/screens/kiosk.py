"""Kiosk mode: an unattended touchscreen that never quits, crashes for good, or loses a tree.

* touch only: keys and window-close do nothing; staff hold the top-left corner for a few seconds to
  get a PIN pad, and the right PIN (assets/kiosk.toml) quits;
* half a minute without a touch and the garden is cared for (the autopilot: the can pours and the sun is
  raised whenever a tree comes near a need), so a visitor always finds a living tree, in daylight;
* after a while without touches an attract loop replays recorded gestures on a copy of the settings
  (game/screens/attract.py: every slider it moves goes back); the first real touch ends it;
* after a longer while the visitor's tree is saved (saves/kiosk/visitor-*.arbor) and a fresh sapling
  is planted for the next visitor;
* the app loop hands every frame to :meth:`Kiosk.frame`, which logs any exception and carries on with
  a freshly loaded garden instead of exiting (a watchdog restarts the process if it dies anyway).
"""

from __future__ import annotations

import logging
import time
import traceback
from dataclasses import dataclass
from pathlib import Path

import pygame

from arbor.engine.base.config import fill_dataclass, toml_position
from arbor.engine.base.errors import SettingsError
from arbor.engine.base.reader import read_user_toml
from arbor.engine.life.keep.save import SavedGarden
from arbor.game.input.events import DOWN, KEY_DOWN, KEY_UP, MOVE, QUIT, UP, InputEvent, load_recording
from arbor.game.paths import ASSETS
from arbor.game.screens.attract import AttractShow
from arbor.game.screens.config import check_volume
from arbor.game.screens.saves import VisitorSaves
from arbor.game.screens.stack import Canvas, Screen
from arbor.game.screens.title import TitleScreen, box_corners
from arbor.game.strings import set_language, set_touch, text
from arbor.game.watchdog import reading

CORNER = 90  # px: the staff corner
PAD_BUTTON = 96

log = logging.getLogger("arbor.kiosk")


@dataclass
class KioskConfig:
    """Settings from assets/kiosk.toml."""

    pin: str = "2468"
    admin_hold: float = 3.0
    care_after: float = 30.0  # seconds without a touch before the autopilot cares for the garden
    attract_after: float = 90.0
    reset_after: float = 300.0
    attract: str = "attract/demo.jsonl"
    language: str = "en"
    speed: float = 10.0
    pace: str = "demo"  # visitors stay minutes: the tamagotchi thesis's fast pace
    volume: float = 0.5  # the sound's volume 0..1 (0: silent), set again for every visitor


KIOSK_LIMIT = 65_536  # bytes: a kiosk.toml is a dozen lines


def load_kiosk_config(path: str | Path) -> KioskConfig:
    """Read kiosk settings (through the one reader for users' files); a file that is not a small plain
    TOML file, unknown keys or wrong types are SettingsErrors naming the file, key, line and column."""
    config = KioskConfig()
    text, data = read_user_toml(path, SettingsError, KIOSK_LIMIT)
    fill_dataclass(config, data, str(path), "kiosk setting", SettingsError, text)
    if not config.pin.isdigit() or not 4 <= len(config.pin) <= 8:
        raise SettingsError("the kiosk PIN must be 4 to 8 digits", str(path), *toml_position(text, "", "pin"))
    check_volume(config.volume, str(path), text)
    return config


def kiosk_config_or_defaults(path: str | Path) -> tuple[KioskConfig, str]:
    """The kiosk's settings from ``path``, or the defaults and one line saying why (logged, and said on
    stderr) when the file cannot be used: a bad kiosk.toml must not stop the kiosk, nor make a watchdog
    count crashes and set the visitors' garden aside."""
    try:
        with reading(path):  # (a watchdog sets aside the file a crash loop died reading)
            return load_kiosk_config(path), ""
    except SettingsError as err:
        line = f"{err} (the kiosk runs on its default settings: fix the file and restart)"
        log.error("%s", line)
        return KioskConfig(), line


class PinLock:
    """Wrong PINs lock the pad for a while, longer after every further miss (so a PIN cannot be found
    by trying them all): FREE_TRIES misses are free, then 30 s, 60 s, 120 s, ... at most an hour."""

    FREE_TRIES = 3

    def __init__(self) -> None:
        self.misses = 0
        self.until = float("-inf")

    def locked_for(self, now: float) -> float:
        """Seconds left before the pad takes a PIN again (0 when it does)."""
        return max(self.until - now, 0.0)

    def missed(self, now: float) -> None:
        """A wrong PIN was entered at ``now``."""
        self.misses += 1
        if self.misses >= self.FREE_TRIES:
            self.until = now + min(30.0 * 2 ** (self.misses - self.FREE_TRIES), 3600.0)

    def reset(self) -> None:
        """The right PIN: forget the misses."""
        self.misses, self.until = 0, float("-inf")


class PinPad(Screen):
    """A big on-screen keypad; returns True from :meth:`tap` when the right PIN was entered. On the game's
    screen stack it takes every press and calls ``on_right`` for the right PIN; Cancel takes it down."""

    layer = 3  # (over everything: the staff's PIN takes every press)

    def __init__(self, size: tuple[int, int], pin: str, lock: PinLock | None = None, clock=time.monotonic,
                 font: pygame.font.Font | None = None, on_right=None) -> None:
        self.pin, self.entered, self.wrong = pin, "", False
        self.lock, self.clock, self.font, self.on_right = lock or PinLock(), clock, font, on_right
        keys = ["1", "2", "3", "4", "5", "6", "7", "8", "9", "cancel", "0", "ok"]
        left = size[0] // 2 - (3 * PAD_BUTTON + 20) // 2
        top = size[1] // 2 - (4 * PAD_BUTTON + 30) // 2 + 30
        self.keys = {k: pygame.Rect(left + (i % 3) * (PAD_BUTTON + 10), top + (i // 3) * (PAD_BUTTON + 10),
                                    PAD_BUTTON, PAD_BUTTON) for i, k in enumerate(keys)}
        self.closed = False

    def tap(self, x: float, y: float) -> bool:
        """Handle a tap; True means: the PIN is right, quit. While locked, only Cancel works."""
        key = next((k for k, r in self.keys.items() if r.collidepoint(x, y)), None)
        if key is None:
            return False
        now = self.clock()
        if key == "cancel":
            self.closed = True
        elif self.lock.locked_for(now) > 0:
            self.entered = ""
        elif key == "ok":
            if self.entered == self.pin:
                self.lock.reset()
                return True
            self.lock.missed(now)
            self.entered, self.wrong = "", True
        elif len(self.entered) < 8:
            self.entered += key
            self.wrong = False
        return False

    def handle(self, e: InputEvent) -> InputEvent | None:
        """Every press, move and release is the pad's (a right PIN calls ``on_right``); the rest goes down."""
        if e.kind not in (DOWN, MOVE, UP):
            return e
        if e.kind == DOWN and self.tap(e.x, e.y) and self.on_right is not None:
            self.on_right()
        if self.closed:
            self.close()
        return None

    def key(self) -> tuple:
        """The digits entered, a wrong PIN, the seconds still locked."""
        return len(self.entered), self.wrong, int(self.lock.locked_for(self.clock()))

    def draw(self, canvas: Canvas) -> None:
        """The keypad over a dimmed screen."""
        surface, font = canvas.surface, self.font
        dim = pygame.Surface(surface.get_size(), pygame.SRCALPHA)
        dim.fill((0, 0, 0, 170))
        surface.blit(dim, (0, 0))
        wait = self.lock.locked_for(self.clock())
        if wait > 0:
            title = text("kiosk.locked", seconds=wait)
        else:
            title = text("kiosk.wrong_pin") if self.wrong else text("kiosk.admin") + "  " + "*" * len(self.entered)
        label = font.render(title, True, (255, 255, 255))
        first = self.keys["1"]
        surface.blit(label, (first.left, first.top - 50))
        for key, rect in self.keys.items():
            pygame.draw.rect(surface, (60, 80, 60, 255), rect, border_radius=12)
            name = text(f"kiosk.{key}") if key in ("ok", "cancel") else key
            glyph = font.render(name, True, (255, 255, 255))
            surface.blit(glyph, glyph.get_rect(center=rect.center))


class Kiosk:
    """Wraps a game (built by ``make_game``) for an unattended touchscreen; see module docstring."""

    def __init__(self, make_game, config: KioskConfig, saves: Path, clock=time.monotonic) -> None:
        language = set_language(config.language)  # ('' or why the translation could not be used)
        if language:
            log.error("%s", language)
        self.make_game, self.config, self.saves, self.clock = make_game, config, saves, clock
        self.game = make_game()
        self.game.state.valve_always = True  # (a child holds the can on and on: it stops at the top)
        set_touch(True)  # (no key names on a touch screen: "tap Go on", not "press G")
        if language:
            self.game.say(language, 12)
        self.game.set_speed(config.speed)
        self._kiosk_volume()
        self.last_touch = clock()
        self.corner_down: float | None = None
        self.attract: AttractShow | None = None
        self.attract_runs = 0  # attract runs played to their end (of every show)
        self.quit_requested = False
        self.recoveries = 0
        self.visitor_saved = False
        self.visitors = VisitorSaves(saves)
        self.pin_lock = PinLock()  # kept across pad openings: closing the pad does not reset the delay
        self.title: TitleScreen | None = None  # drawn over the attract loop
        self.screen = KioskScreen(self)
        self.game.screens.push(self.screen)

    @property
    def pin_pad(self) -> PinPad | None:
        """The staff's PIN pad, while it is up on the game's screen stack."""
        return next((s for s in self.game.screens if isinstance(s, PinPad)), None)

    # ----- input ---------------------------------------------------------------------------------
    def handle_input(self, e: InputEvent) -> bool:
        """Visitor input, through the game's screens (the kiosk's own on top: keys and quit do nothing);
        returns False only after the staff PIN."""
        if e.kind in (DOWN, MOVE, UP):
            self._touched(e)
        self.game.handle_input(e)
        return not self.quit_requested

    def staff_quit(self) -> None:
        """The right PIN on the pad: the kiosk ends."""
        self.quit_requested = True

    def _touched(self, e: InputEvent) -> None:
        self.last_touch = self.clock()
        self.visitor_saved = False
        if self.attract is not None:  # a visitor: stop the show and give them a clean view
            self.attract = None
            AttractShow.tidy(self.game)
            self.game.coach.first_run()  # (the show turned the view: the visitor still gets every hint)
        if self.game.state.autopilot:  # the visitor takes over the care, in daylight
            self.game.state.autopilot = False
            self.game.state.daylight()

    def guarded(self, poll):
        """``poll`` (the input layer) inside the kiosk's guard: a device or packet that makes it raise is
        logged and its events dropped, never fatal."""
        def safe(events, now: float) -> list[InputEvent]:
            try:
                return poll(events, now)
            except Exception:
                log.error("input failed, events dropped:\n%s", traceback.format_exc())
                return []

        return safe

    # ----- frame ---------------------------------------------------------------------------------
    def frame(self, events: list[InputEvent], real_seconds: float, fbo) -> bool:
        """One frame (events, update, draw), never raising; returns False when staff quit."""
        try:
            for e in events:
                if not self.handle_input(e):
                    return False
            self.update(real_seconds)
            self.game.draw(fbo)
        except Exception:
            self.recover()
        return True

    def recover(self) -> None:
        """Log the exception and continue with a freshly loaded garden (the autosave, else a sapling)."""
        self.recoveries += 1
        log.error("frame failed, restarting the garden:\n%s", traceback.format_exc())
        try:
            self.game.save()
        except Exception:
            log.error("could not save while recovering:\n%s", traceback.format_exc())
        self.game = self.make_game()
        self.game.state.valve_always = True
        set_touch(True)
        self.game.set_speed(self.config.speed)
        self._kiosk_volume()
        self.game.screens.push(self.screen)
        self.game.say(text("messages.recovered"), 6)

    def update(self, real_seconds: float) -> None:
        """Idle handling (attract, visitor reset), the staff corner, then the game's own update."""
        now = self.clock()
        idle = now - self.last_touch
        if self.corner_down is not None and now - self.corner_down >= self.config.admin_hold:
            self.corner_down = None
            self.game.screens.push(PinPad(self.game.size, self.config.pin, self.pin_lock, self.clock,
                                          self.game.font, self.staff_quit))
        if idle >= self.config.care_after and not self.game.state.autopilot:
            self.start_autopilot()
        if idle >= self.config.reset_after and not self.visitor_saved:
            self.reset_visitor()
        if idle >= self.config.attract_after and self.attract is None and self.pin_pad is None:
            self.start_attract(now)
        if self.attract is not None:
            runs = self.attract.runs
            self.attract.play(self.game, now)
            self.attract_runs += self.attract.runs - runs
        self.game.update(real_seconds)

    def start_autopilot(self) -> None:
        """Nobody is there: the garden is cared for every step from now on (the guardian's tending,
        engine/life/world/guardian.py), at the kiosk's own speed (a stop the guardian made is gone on)."""
        state = self.game.state
        state.autopilot = True
        if state.halted is not None:
            state.go_on()
        self.game.set_speed(self.config.speed)

    def start_attract(self, now: float) -> None:
        """Begin the attract loop (if its recording can be read; a bad file is logged, not fatal)."""
        try:
            self.attract = AttractShow(load_recording(ASSETS / self.config.attract), now)
        except (OSError, ValueError) as exc:
            log.error("attract recording unusable: %s", exc)
            self.attract = AttractShow([], now)

    def reset_visitor(self) -> None:
        """Save the visitor's tree and plant a fresh sapling for the next one (a disk that refuses the save
        keeps the tree in memory, said on the screen and in the log: game/screens/saves.VisitorSaves)."""
        error = self.visitors.keep(SavedGarden([self.game.world]))  # (in the kiosk's own folder)
        self.game.care.replant(confirmed=True)  # (the visitor's tree is saved first; nobody to ask)
        self._kiosk_volume()  # (whatever the last visitor set)
        self.game.coach.first_run()
        if error is None:
            self.game.say(text("messages.visitor_reset"), 5)
        else:
            log.error("could not save the visitor's tree (%s): %d kept in memory", error, len(self.visitors.waiting))
            self.game.say(text("messages.visitor_unsaved", error=error, count=len(self.visitors.waiting)), 8)
        self.visitor_saved = True

    def _kiosk_volume(self) -> None:
        """The sound at kiosk.toml's volume, unmuted, and the Settings slider showing it."""
        self.game.sound.use(self.config.volume)
        self.game.care.sync_sliders()

    def draw_attract(self, canvas: Canvas | pygame.Surface) -> None:
        """While the attract loop plays, the title over the garden playing behind it (clear of the crown
        when ``canvas`` is the game's: its camera says where the tree is)."""
        if self.attract is not None:
            surface = canvas.surface if isinstance(canvas, Canvas) else canvas
            if self.title is None or self.title.size != surface.get_size():
                self.title = TitleScreen(surface.get_size(), prompt=text("kiosk.attract"))
                self.title.subject = lambda: box_corners(self.game.renderer.lo, self.game.renderer.hi)
            if isinstance(canvas, Canvas):
                self.title.draw(canvas)
            else:
                self.title.paint(surface)


class KioskScreen(Screen):
    """The kiosk's screen, over the game's: keys and window-close do nothing (only the staff PIN quits), a
    press held in the top-left corner is watched (it brings up the PIN pad, pushed over this), and the
    attract loop's title is drawn."""

    layer = 2  # (the kiosk's own layer stays over a menu or the modeler a visitor opens)

    def __init__(self, kiosk: Kiosk) -> None:
        self.kiosk = kiosk

    def handle(self, e: InputEvent) -> InputEvent | None:
        """Keys and quit stop here; presses go on down, the corner's watched."""
        if e.kind in (QUIT, KEY_DOWN, KEY_UP):
            return None
        if e.kind == DOWN and e.x < CORNER and e.y < CORNER:
            self.kiosk.corner_down = self.kiosk.clock()
        elif e.kind == UP:
            self.kiosk.corner_down = None
        return e

    def draw(self, canvas: Canvas) -> None:
        """The attract loop's title (see :meth:`Kiosk.draw_attract`)."""
        self.kiosk.draw_attract(canvas)

    def key(self) -> tuple:
        """Whether the attract loop plays."""
        return (self.kiosk.attract is not None,)
