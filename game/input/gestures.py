"""Touch and mouse gestures for the camera and the menu (the tamagotchi thesis, sections 2.4.1-2.4.2).

* one finger dragged horizontally turns the tree about the vertical axis (a full 360 deg);
* two fingers, one still and one moving vertically, tilt it, at most acos(0.8) ~ 36.9 deg;
* two fingers sliding sideways together also turn it (one finger draws in the modeler);
* a pinch zooms, faster when the camera is farther away (the change is proportional to distance),
  unless ``pinch_target`` takes it (a pinch over a modeler region resizes the region);
* a quick tap shows the menu at the tap point; another tap hides it. While the menu is shown the
  camera gestures are off (touches go to the menu).

Pure logic: feed it pointer events with positions in pixels and times in seconds.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

MAX_TILT = math.degrees(math.acos(0.8))  # 36.87 deg
TAP_TIME = 0.3  # s
TAP_SLOP = 12.0  # px a tap may wander
YAW_PER_PX = 0.4  # deg per pixel of horizontal drag
TILT_PER_PX = 0.25  # deg per pixel of vertical drag
STILL_PX = 6.0  # a finger that moved less than this during a two-finger gesture counts as still


@dataclass
class CameraControl:
    """What the gestures change: yaw (deg), tilt (deg, 0..MAX_TILT) and zoom distance."""

    yaw: float = 255.0  # facing a little north of east: the rising sun is in view, the day's sun lights the side
    tilt: float = 0.0
    distance: float = 10.0
    min_distance: float = 0.5
    max_distance: float = 500.0

    def turn(self, degrees: float) -> None:
        """Turn about the vertical axis (wraps, so a full circle is possible)."""
        self.yaw = (self.yaw + degrees) % 360.0

    def tilt_by(self, degrees: float) -> None:
        """Tilt, clamped to [0, acos(0.8)]."""
        self.tilt = min(max(self.tilt + degrees, 0.0), MAX_TILT)

    def zoom(self, factor: float) -> None:
        """Multiply the distance (so zoom speed grows with distance), within limits."""
        self.distance = min(max(self.distance * factor, self.min_distance), self.max_distance)


@dataclass
class _Pointer:
    x: float
    y: float
    x0: float
    y0: float
    t0: float
    moved: float = 0.0


@dataclass
class Gestures:
    """Turns pointer down/move/up events into camera changes and taps."""

    camera: CameraControl
    menu_open: bool = False
    pointers: dict[int, _Pointer] = field(default_factory=dict)
    taps: list[tuple[float, float]] = field(default_factory=list)  # taps not yet consumed
    _multi: bool = False  # a second finger joined during this gesture (so it is not a tap)
    pinch_target: Callable[[float, float, float], bool] | None = None  # (scale, x, y) -> took the pinch

    def down(self, pid: int, x: float, y: float, t: float) -> None:
        """A finger or the mouse button went down."""
        self.pointers[pid] = _Pointer(x, y, x, y, t)
        self._multi = self._multi or len(self.pointers) > 1

    def move(self, pid: int, x: float, y: float, t: float) -> None:
        """A pointer moved; drives rotate/tilt/pinch unless the menu is open."""
        p = self.pointers.get(pid)
        if p is None:
            return
        dx, dy = x - p.x, y - p.y
        before = dict((k, (q.x, q.y)) for k, q in self.pointers.items())
        p.x, p.y = x, y
        p.moved += math.hypot(dx, dy)
        if self.menu_open:
            return
        if len(self.pointers) == 1:
            self.camera.turn(-dx * YAW_PER_PX)
        elif len(self.pointers) == 2:
            self._two_fingers(pid, dx, dy, before)

    def _two_fingers(self, pid: int, dx: float, dy: float, before: dict) -> None:
        (a, pa), (b, pb) = self.pointers.items()
        other = pb if a == pid else pa
        other_still = math.hypot(other.x - other.x0, other.y - other.y0) < STILL_PX
        if other_still and abs(dy) > abs(dx):
            self.camera.tilt_by(dy * TILT_PER_PX)
            return
        (ax, ay), (bx, by) = before[a], before[b]
        old = math.hypot(ax - bx, ay - by)
        new = math.hypot(pa.x - pb.x, pa.y - pb.y)
        me = self.pointers[pid]
        same_way = (me.x - me.x0) * (other.x - other.x0) > 0 and abs(dx) > abs(dy)
        if not other_still and same_way:
            self.camera.turn(-dx * YAW_PER_PX / 2)  # both fingers sliding sideways together: turn
        elif old > 1 and new > 1:
            mid_x, mid_y = (pa.x + pb.x) / 2, (pa.y + pb.y) / 2
            if self.pinch_target is None or not self.pinch_target(new / old, mid_x, mid_y):
                self.camera.zoom(old / new)

    def up(self, pid: int, x: float, y: float, t: float) -> tuple[float, float] | None:
        """A pointer went up; returns the tap position if this was a quick tap."""
        p = self.pointers.pop(pid, None)
        if p is None:
            return None
        tap = (not self._multi and t - p.t0 <= TAP_TIME and p.moved <= TAP_SLOP)
        if not self.pointers:
            self._multi = False
        if tap:
            self.taps.append((x, y))
            return (x, y)
        return None

    def cancel_all(self) -> None:
        """Forget every pointer (device unplugged, window lost focus)."""
        self.pointers.clear()
        self._multi = False
