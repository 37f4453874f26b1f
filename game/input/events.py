"""One input layer: every source (mouse, SDL touch, keyboard, TUIO, HID 3D trackers, recordings)
becomes the same :class:`InputEvent`, which the camera, the menu and the modeler consume.

Nothing else in the app reads pygame events or devices directly. Sessions can be recorded to a
JSON-lines file and replayed with their timestamps (tests, kiosk attract mode, bug reports).
"""

from __future__ import annotations

import json
import math
from collections.abc import Iterable
from dataclasses import asdict, dataclass, fields
from pathlib import Path

import pygame

from arbor.engine.base.errors import LSysError
from arbor.engine.base.reader import read_user_text

DOWN, MOVE, UP = "down", "move", "up"
KEY_DOWN, KEY_UP, WHEEL, ROTATE, QUIT, FOCUS_LOST, DEVICE = (
    "key_down", "key_up", "wheel", "rotate", "quit", "focus_lost", "device")
MOUSE_ID = -1
KINDS = (DOWN, MOVE, UP, KEY_DOWN, KEY_UP, WHEEL, ROTATE, QUIT, FOCUS_LOST, DEVICE)
EVENT_LIMIT = 1e9  # any number in a recorded event (times, pixels, ids, keys) within +- this ...
FIELD_LIMITS = {"x": 1e6, "y": 1e6, "z": 1e6, "pressure": 10.0, "amount": 100.0, "rx": 100.0, "ry": 100.0,
                "rz": 100.0}  # ... and these within +- their own (a wheel turns, rates: what devices send)
MAX_RECORDING = 64 * 1024 * 1024  # bytes of a recording file


@dataclass(frozen=True)
class InputEvent:
    """A device-independent input event.

    Pointers (kind down/move/up) carry a 2D position in window pixels, or a 3D position in scene
    units when ``dims`` is 3; ``pointer`` identifies a finger/cursor within ``device``. ``button`` is
    the mouse/tracker button (1 = primary, 3 = secondary). ``rotate`` carries 3D-tracker rotation
    rates (rx, ry, rz); ``device`` events announce devices and problems in ``text``.
    """

    kind: str
    t: float
    device: str = "mouse"
    pointer: int = 0
    x: float = 0.0
    y: float = 0.0
    z: float = 0.0
    dims: int = 2
    pressure: float = 1.0
    button: int = 1
    key: int = 0
    amount: float = 0.0
    rx: float = 0.0
    ry: float = 0.0
    rz: float = 0.0
    text: str = ""

    def to_json(self) -> str:
        """One line of a recording (only non-default fields)."""
        defaults = InputEvent("", 0.0)
        data = {k: v for k, v in asdict(self).items() if k in ("kind", "t") or v != getattr(defaults, k)}
        return json.dumps(data, separators=(",", ":"))

    @classmethod
    def from_json(cls, line: str) -> InputEvent:
        """Inverse of :meth:`to_json`; raises ValueError (one line) for anything that is not an event: not
        a JSON object, an unknown kind or field, a value of the wrong type, a number that is not finite
        or beyond EVENT_LIMIT (a recording is edited and shared, and replayed into the game)."""
        try:
            data = json.loads(line)
        except RecursionError:
            raise ValueError("not an input event (nested too deeply)") from None
        if not isinstance(data, dict) or "kind" not in data or "t" not in data:
            raise ValueError("not an input event (an object with at least 'kind' and 't')")
        defaults = {f.name: f.default for f in fields(cls)}
        for key, value in data.items():
            if key not in defaults:
                raise ValueError(f"unknown field {key[:40]!r}")
            want = type(defaults[key]) if key not in ("kind", "t") else (str if key == "kind" else float)
            if want is float and isinstance(value, int) and not isinstance(value, bool):
                data[key] = value = float(value)
            if isinstance(value, bool) or not isinstance(value, want):
                raise ValueError(f"'{key}' must be {'text' if want is str else 'a number'}")
            limit = FIELD_LIMITS.get(key, EVENT_LIMIT)
            if want is not str and not (math.isfinite(value) and abs(value) <= limit):
                raise ValueError(f"'{key}' must be a finite number from {-limit:g} to {limit:g}")
            if want is str and len(value) > 1000:
                raise ValueError(f"'{key}' is too long (at most 1,000 characters)")
        if data.get("dims", 2) not in (2, 3):
            raise ValueError("'dims' must be 2 or 3")
        if data["kind"] not in KINDS:
            raise ValueError(f"unknown kind {data['kind'][:40]!r} (one of {', '.join(KINDS)})")
        return cls(**data)


class PygameTranslator:
    """pygame events -> InputEvents (mouse, multi-touch fingers, keys, wheel, quit, focus)."""

    def __init__(self, size: tuple[int, int]) -> None:
        self.size = size

    def translate(self, e: pygame.event.Event, t: float) -> list[InputEvent]:
        """The InputEvents for one pygame event (often none)."""
        w, h = self.size
        if e.type == pygame.QUIT:
            return [InputEvent(QUIT, t, "window")]
        if e.type in (pygame.FINGERDOWN, pygame.FINGERMOTION, pygame.FINGERUP):
            kind = {pygame.FINGERDOWN: DOWN, pygame.FINGERMOTION: MOVE, pygame.FINGERUP: UP}[e.type]
            # SDL gives finger positions normalised to 0..1 of the window
            return [InputEvent(kind, t, f"touch:{e.touch_id}", int(e.finger_id), e.x * w, e.y * h,
                               pressure=float(getattr(e, "pressure", 1.0)))]
        if getattr(e, "touch", False):
            return []  # SDL's mouse emulation of touches: the finger events already cover them
        if e.type in (pygame.MOUSEBUTTONDOWN, pygame.MOUSEBUTTONUP) and e.button in (1, 2, 3):
            kind = DOWN if e.type == pygame.MOUSEBUTTONDOWN else UP
            return [InputEvent(kind, t, "mouse", MOUSE_ID, *e.pos, button=e.button)]
        if e.type == pygame.MOUSEMOTION and any(e.buttons):
            button = 1 if e.buttons[0] else (3 if e.buttons[2] else 2)
            return [InputEvent(MOVE, t, "mouse", MOUSE_ID, *e.pos, button=button)]
        if e.type == pygame.MOUSEWHEEL:
            return [InputEvent(WHEEL, t, "mouse", amount=float(e.y))]
        if e.type in (pygame.KEYDOWN, pygame.KEYUP):
            return [InputEvent(KEY_DOWN if e.type == pygame.KEYDOWN else KEY_UP, t, "keyboard", key=e.key)]
        if e.type == pygame.WINDOWFOCUSLOST:
            return [InputEvent(FOCUS_LOST, t, "window")]
        return []


class Recorder:
    """Appends every event to a JSON-lines file, flushing each line (a crash keeps what came before)."""

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path)
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self.file = open(self.path, "w", encoding="utf-8")  # noqa: SIM115 - kept open while recording
        self.file.write('{"arbor_input_recording":1}\n')

    def write(self, events: Iterable[InputEvent]) -> None:
        """Record events."""
        for e in events:
            self.file.write(e.to_json() + "\n")
        self.file.flush()

    def close(self) -> None:
        """Finish the recording."""
        self.file.close()


class RecordingError(LSysError, ValueError):
    """A recording that cannot be replayed: ``file:line:column: why`` (a ValueError too, as callers expect)."""


MAX_LINE_NESTING = 8  # arrays or objects nested in one event's JSON (an event nests 2)


def load_recording(path: str | Path) -> list[InputEvent]:
    """Read a recording through the one reader for users' files (a regular file itself, at most
    MAX_RECORDING bytes of UTF-8); a bad line is a :class:`RecordingError` naming the file and line, in
    one line (JSON nested deeper than an event is refused before it is parsed)."""
    content = read_user_text(path, MAX_RECORDING, RecordingError)
    events = []
    for number, line in enumerate(content.splitlines(), start=1):
        if (number == 1 and "arbor_input_recording" in line) or not line.strip():
            continue
        if line.count("[") + line.count("{") > MAX_LINE_NESTING:
            raise RecordingError(f"not an input event: more than {MAX_LINE_NESTING} brackets", str(path), number)
        try:
            events.append(InputEvent.from_json(line))
        except (ValueError, TypeError, RecursionError) as exc:
            raise RecordingError(str(exc), str(path), number) from None
    return events


class Player:
    """Replays a recording against a clock: events come out when their (relative) time has come."""

    def __init__(self, events: list[InputEvent], start: float, loop: bool = False) -> None:
        self.events = sorted(events, key=lambda e: e.t)
        self.origin = self.events[0].t if self.events else 0.0
        self.start = start
        self.loop = loop
        self.index = 0

    @property
    def done(self) -> bool:
        """True when every event has been played (never, when looping)."""
        return not self.loop and self.index >= len(self.events)

    def poll(self, now: float) -> list[InputEvent]:
        """Events due by ``now``, re-timed to the playback clock."""
        out = []
        while self.index < len(self.events) and self.events[self.index].t - self.origin <= now - self.start:
            e = self.events[self.index]
            out.append(_retime(e, self.start + e.t - self.origin))
            self.index += 1
        if self.loop and self.index >= len(self.events) and self.events:
            self.start, self.index = now, 0
        return out


def _retime(e: InputEvent, t: float) -> InputEvent:
    data = asdict(e)
    data["t"] = t
    return InputEvent(**data)


class InputHub:
    """Collects events from pygame and every other source; optionally records them."""

    def __init__(self, size: tuple[int, int], sources: list | None = None, recorder: Recorder | None = None) -> None:
        self.translator = PygameTranslator(size)
        self.sources = list(sources or [])
        self.recorder = recorder

    def poll(self, pygame_events: Iterable[pygame.event.Event], now: float) -> list[InputEvent]:
        """All events of this frame, in order: pygame first, then each source's."""
        events = [ie for e in pygame_events for ie in self.translator.translate(e, now)]
        for source in self.sources:
            events.extend(source.poll(now))
        if self.recorder is not None and events:
            self.recorder.write(events)
        return events

    def close(self) -> None:
        """Stop every source and the recorder."""
        for source in self.sources:
            close = getattr(source, "close", None)
            if close:
                close()
        if self.recorder is not None:
            self.recorder.close()
