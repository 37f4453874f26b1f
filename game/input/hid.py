"""3D trackers over hidapi: 3Dconnexion SpaceMouse devices and data-described absolute trackers.

A SpaceMouse is a rate device: its translation moves a 3D cursor (which draws strokes while button 1
is held) and its rotation orbits the camera. Old firmware sends translation (report 1, 3 x int16) and
rotation (report 2) separately; newer devices send all six axes in report 1 (6 x int16). Buttons come
in report 3 as a bitmask. Absolute trackers are described in assets/input/devices.toml.

Devices may appear and disappear at any time (hot-plug is polled); unplugging while a button is held
ends the stroke with an "up" event. Missing hidapi, missing permissions and malformed reports become
messages (DEVICE events), never exceptions.
"""

from __future__ import annotations

import contextlib
import difflib
import math
import re
import struct
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from arbor.engine.base.config import read_toml, toml_position
from arbor.engine.base.errors import SettingsError
from arbor.game.input.events import DEVICE, DOWN, MOVE, ROTATE, UP, InputEvent

THREEDCONNEXION = 0x256F
LOGITECH = 0x046D
LOGITECH_3D_MICE = {0xC603, 0xC605, 0xC606, 0xC621, 0xC623, 0xC625, 0xC626, 0xC627, 0xC628, 0xC629, 0xC62B,
                    0xC640}
AXIS_FULL = 350.0  # a SpaceMouse axis pushed all the way
TYPES = {"int8": "<b", "uint8": "<B", "int16": "<h", "uint16": "<H", "int32": "<i", "uint32": "<I",
         "float32": "<f"}


def is_spacemouse(vendor_id: int, product_id: int) -> bool:
    """3Dconnexion devices (any product of their own vendor id, known ones under Logitech's)."""
    return vendor_id == THREEDCONNEXION or (vendor_id == LOGITECH and product_id in LOGITECH_3D_MICE)


@dataclass
class SpaceMouseState:
    """Latest axes (-1..1) and buttons of one SpaceMouse."""

    translation: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rotation: tuple[float, float, float] = (0.0, 0.0, 0.0)
    buttons: int = 0


def parse_spacemouse(report: bytes, state: SpaceMouseState) -> bool:
    """Update ``state`` from one HID report; False if the report is malformed or unknown."""
    if len(report) < 2:
        return False
    rid = report[0]
    if rid == 1 and len(report) >= 13:  # new layout: six axes in one report
        axes = struct.unpack_from("<6h", report, 1)
        state.translation = tuple(a / AXIS_FULL for a in axes[:3])
        state.rotation = tuple(a / AXIS_FULL for a in axes[3:])
        return True
    if rid in (1, 2) and len(report) >= 7:  # old layout: translation, then rotation
        axes = tuple(a / AXIS_FULL for a in struct.unpack_from("<3h", report, 1))
        if rid == 1:
            state.translation = axes
        else:
            state.rotation = axes
        return True
    if rid == 3:
        state.buttons = int.from_bytes(report[1:5], "little")
        return True
    return False


@dataclass(frozen=True)
class Field:
    """Where one value sits in a report."""

    offset: int
    fmt: str
    scale: float = 1.0

    def read(self, report: bytes) -> float:
        """The scaled value (struct.error if the report is too short)."""
        return struct.unpack_from(self.fmt, report, self.offset)[0] * self.scale


@dataclass(frozen=True)
class Profile:
    """An absolute 3D tracker described by data (see assets/input/devices.toml)."""

    name: str
    vendor_id: int
    product_id: int
    report_id: int
    x: Field
    y: Field
    z: Field
    buttons: Field | None = None


class DevicesError(SettingsError, ValueError):
    """A problem in devices.toml: ``str()`` is one line, ``file:line:col: device #N: what is wrong``."""


DEVICE_KEYS = ("name", "vendor_id", "product_id", "report_id", "x", "y", "z", "buttons")
FIELD_KEYS = ("offset", "type", "scale")
REPORT_BYTES = 64  # a HID input report at most (full-speed USB)


def load_profiles(path: str | Path) -> list[Profile]:
    """Read device profiles strictly (the file is edited by hand): an unreadable file, bad TOML, an
    unknown key, a missing or mistyped value, an id or offset out of range is a :class:`DevicesError`
    naming the file, the line, the column and the entry."""
    text, data = read_toml(path, DevicesError)
    file = str(path)
    unknown = sorted(set(data) - {"device"})
    if unknown:
        raise DevicesError(f"unknown key {unknown[0]!r} (devices are [[device]] tables)", file,
                           *toml_position(text, "", unknown[0]))
    devices = data.get("device", [])
    if not isinstance(devices, list):
        raise DevicesError("'device' must be [[device]] tables", file, *toml_position(text, "", "device"))
    return [_profile(entry, i, _Entry(file, text, i)) for i, entry in enumerate(devices)]


@dataclass
class _Entry:
    """Where the ``index``-th [[device]] table is in the file (for one-line errors)."""

    file: str
    text: str
    index: int

    def error(self, message: str, key: str | None = None) -> DevicesError:
        """The error about this entry (at ``key``'s line when it can be found)."""
        headers = [m.start() for m in re.finditer(r"^\s*\[\[\s*device\s*\]\]", self.text, re.M)]
        line, col = 1, 1
        if self.index < len(headers):
            start = headers[self.index]
            end = headers[self.index + 1] if self.index + 1 < len(headers) else len(self.text)
            found = re.search(rf"^\s*{re.escape(key)}\s*=", self.text[start:end], re.M) if key else None
            at = start + (found.start() + len(found.group()) - len(found.group().lstrip()) if found else 0)
            line = self.text.count("\n", 0, at) + 1
            col = at - self.text.rfind("\n", 0, at)
        return DevicesError(f"device #{self.index + 1}: {message}", self.file, line, col)


def _profile(entry, i: int, where: _Entry) -> Profile:
    if not isinstance(entry, dict):
        raise where.error("must be a table of name, vendor_id, product_id, report_id, x, y, z (and buttons)")
    for key in entry:
        if key not in DEVICE_KEYS:
            near = difflib.get_close_matches(key, DEVICE_KEYS, 1)
            raise where.error(f"unknown key {key!r}" + (f" (did you mean {near[0]!r}?)" if near else ""), key)
    for key in DEVICE_KEYS[:-1]:
        if key not in entry:
            raise where.error(f"missing {key!r}")
    name = entry["name"]
    if not isinstance(name, str) or not 0 < len(name.strip()) <= 200:
        raise where.error("'name' must be text (1 to 200 characters)", "name")
    ids = [_whole(entry, key, high, where) for key, high in (("vendor_id", 0xFFFF), ("product_id", 0xFFFF),
                                                            ("report_id", 0xFF))]
    axes = [_field(entry[key], key, where) for key in ("x", "y", "z")]
    buttons = _field(entry["buttons"], "buttons", where) if "buttons" in entry else None
    return Profile(name, *ids, *axes, buttons)


def _whole(entry: dict, key: str, high: int, where: _Entry) -> int:
    v = entry[key]
    if isinstance(v, bool) or not isinstance(v, int) or not 0 <= v <= high:
        raise where.error(f"{key!r} must be a whole number from 0 to {high:#x}", key)
    return v


def _field(spec, key: str, where: _Entry) -> Field:
    """One value's place in the report: { offset = N, type = "int16", scale = 0.001 }."""
    if not isinstance(spec, dict) or "offset" not in spec or "type" not in spec:
        raise where.error(f"{key!r} must be a table like {{ offset = 1, type = \"int16\", scale = 0.001 }}", key)
    bad = sorted(set(spec) - set(FIELD_KEYS))
    if bad:
        raise where.error(f"{key!r}: unknown key {bad[0]!r} (known: offset, type, scale)", key)
    kind, offset, scale = spec["type"], spec["offset"], spec.get("scale", 1.0)
    if not isinstance(kind, str) or kind not in TYPES:
        raise where.error(f"{key!r}: unknown type {kind!r} (one of {', '.join(TYPES)})", key)
    size = struct.calcsize(TYPES[kind])
    if isinstance(offset, bool) or not isinstance(offset, int) or not 0 <= offset <= REPORT_BYTES - size:
        raise where.error(f"{key!r}: offset must be a whole number from 0 to {REPORT_BYTES - size} for {kind}", key)
    if isinstance(scale, bool) or not isinstance(scale, int | float) or not math.isfinite(scale) or abs(scale) > 1e6:
        raise where.error(f"{key!r}: scale must be a finite number (at most 1e6 either way)", key)
    return Field(offset, TYPES[kind], float(scale))


class HidBackend:
    """The real hidapi backend: enumerate devices and open them non-blocking."""

    def __init__(self) -> None:
        import hid  # raises ImportError when the hidapi library is missing

        self.hid = hid

    def enumerate(self) -> list[dict]:
        """hidapi's device list."""
        return self.hid.enumerate()

    def open(self, info: dict):
        """An opened device with ``read() -> bytes`` and ``close()``."""
        dev = self.hid.device()
        dev.open_path(info["path"])
        dev.set_nonblocking(1)
        return _HidapiDevice(dev)


class _HidapiDevice:
    def __init__(self, dev) -> None:
        self.dev = dev

    def read(self) -> bytes:
        return bytes(self.dev.read(64))

    def close(self) -> None:
        self.dev.close()


@dataclass
class _Open:
    name: str
    handle: object
    profile: Profile | None
    state: SpaceMouseState = field(default_factory=SpaceMouseState)
    cursor: list[float] = field(default_factory=lambda: [0.0, 0.0, 0.0])
    held: bool = False
    bad_reports: int = 0
    last: float | None = None


class HidManager:
    """Polls for hot-plugged trackers and turns their reports into InputEvents."""

    def __init__(self, backend: Callable[[], object] | object | None = None, profiles: list[Profile] | None = None,
                 scan_interval: float = 1.0, speed: float = 2.0, turn_rate: float = 90.0) -> None:
        self.profiles = profiles or []
        self.scan_interval = scan_interval
        self.speed, self.turn_rate = speed, turn_rate  # scene units / s and deg / s at full deflection
        self.open: dict[bytes, _Open] = {}
        self.failed: set[bytes] = set()
        self.last_scan: float | None = None
        self.pending: list[InputEvent] = []
        self.backend = backend
        if backend is None:
            try:
                self.backend = HidBackend()
            except (ImportError, OSError) as exc:
                self.pending.append(InputEvent(DEVICE, 0.0, "hid", text=f"3D trackers unavailable: {exc}"))

    def device_names(self) -> list[str]:
        """Names of the trackers connected now."""
        return [d.name for d in self.open.values()]

    def poll(self, now: float) -> list[InputEvent]:
        """Events since the last poll (hot-plug is checked every ``scan_interval`` seconds)."""
        out, self.pending = self.pending, []
        if self.backend is None:
            return out
        if self.last_scan is None or now - self.last_scan >= self.scan_interval:
            self.last_scan = now
            out += self._scan(now)
        for path, dev in list(self.open.items()):
            out += self._read(path, dev, now)
        return out

    def _match(self, info: dict) -> tuple[str, Profile | None] | None:
        vid, pid = int(info.get("vendor_id", 0)), int(info.get("product_id", 0))
        for profile in self.profiles:
            if (profile.vendor_id, profile.product_id) == (vid, pid):
                return profile.name, profile
        if is_spacemouse(vid, pid):
            return str(info.get("product_string") or "SpaceMouse"), None
        return None

    def _scan(self, now: float) -> list[InputEvent]:
        out = []
        try:
            infos = self.backend.enumerate()
        except OSError as exc:
            return [InputEvent(DEVICE, now, "hid", text=f"cannot list HID devices: {exc}")]
        present = set()
        for info in infos:
            match = self._match(info)
            path = info.get("path", b"")
            if match is None:
                continue
            present.add(path)
            if path in self.open or path in self.failed:
                continue
            name, profile = match
            try:
                handle = self.backend.open(info)
            except OSError as exc:
                self.failed.add(path)
                out.append(InputEvent(DEVICE, now, f"hid:{name}",
                                      text=f"cannot open {name} ({exc}); check device permissions (udev rules)"))
                continue
            self.open[path] = _Open(name, handle, profile)
            out.append(InputEvent(DEVICE, now, f"hid:{name}", amount=1.0, text=f"{name} connected"))
        for path in list(self.open):
            if path not in present:
                out += self._unplug(path, now)
        self.failed &= present
        return out

    def _unplug(self, path: bytes, now: float) -> list[InputEvent]:
        dev = self.open.pop(path)
        out = []
        if dev.held:  # end the stroke cleanly
            out.append(InputEvent(UP, now, f"hid:{dev.name}", 0, *dev.cursor, dims=3))
        with contextlib.suppress(OSError):
            dev.handle.close()
        out.append(InputEvent(DEVICE, now, f"hid:{dev.name}", amount=-1.0, text=f"{dev.name} unplugged"))
        return out

    def _read(self, path: bytes, dev: _Open, now: float) -> list[InputEvent]:
        out: list[InputEvent] = []
        for _ in range(64):  # drain what arrived, boundedly
            try:
                report = dev.handle.read()
            except (OSError, ValueError):
                return out + self._unplug(path, now)
            if not report:
                break
            ok = self._apply(dev, report, now, out)
            if not ok:
                dev.bad_reports += 1
                if dev.bad_reports == 1:
                    out.append(InputEvent(DEVICE, now, f"hid:{dev.name}",
                                          text=f"ignoring malformed reports from {dev.name}"))
        if dev.profile is None:
            out += self._integrate(dev, now)
        return out

    def _apply(self, dev: _Open, report: bytes, now: float, out: list[InputEvent]) -> bool:
        if dev.profile is None:
            before = dev.state.buttons
            if not parse_spacemouse(report, dev.state):
                return False
            self._buttons(dev, before, dev.state.buttons, now, out)
            return True
        p = dev.profile
        if report[0] != p.report_id:
            return True  # another report of the device: not ours to read
        try:
            pos = [p.x.read(report), p.y.read(report), p.z.read(report)]
            buttons = int(p.buttons.read(report)) if p.buttons else 0
        except struct.error:
            return False
        before = 1 if dev.held else 0
        moved = pos != dev.cursor
        dev.cursor = pos
        self._buttons(dev, before, buttons, now, out)
        if moved:
            out.append(InputEvent(MOVE, now, f"hid:{dev.name}", 0, *pos, dims=3))
        return True

    def _buttons(self, dev: _Open, before: int, after: int, now: float, out: list[InputEvent]) -> None:
        if (before ^ after) & 1:
            dev.held = bool(after & 1)
            out.append(InputEvent(DOWN if dev.held else UP, now, f"hid:{dev.name}", 0, *dev.cursor, dims=3))

    def _integrate(self, dev: _Open, now: float) -> list[InputEvent]:
        """SpaceMouse: translation moves the cursor, rotation turns the camera (rates x elapsed time)."""
        dt = 0.0 if dev.last is None else min(now - dev.last, 0.1)
        dev.last = now
        tx, ty, tz = dev.state.translation
        rx, ry, rz = dev.state.rotation
        out = []
        if dt > 0 and (tx or ty or tz):
            # device: +x right, +y towards the user, +z down -> scene: x right, y up, z towards the viewer
            step = self.speed * dt
            dev.cursor = [dev.cursor[0] + tx * step, dev.cursor[1] - tz * step, dev.cursor[2] + ty * step]
            out.append(InputEvent(MOVE, now, f"hid:{dev.name}", 0, *dev.cursor, dims=3))
        if dt > 0 and (rx or rz):
            turn = self.turn_rate * dt
            out.append(InputEvent(ROTATE, now, f"hid:{dev.name}", rx=rx * turn, ry=rz * turn, rz=ry * turn))
        return out

    def close(self) -> None:
        """Close every device."""
        for dev in self.open.values():
            with contextlib.suppress(OSError):
                dev.handle.close()
        self.open.clear()
