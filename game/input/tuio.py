"""TUIO 1.1 touch frames over UDP (OSC), for kiosk touch frames that speak TUIO instead of HID touch.

Off by default (``arbor --tuio``); listens on 127.0.0.1:3333 unless told otherwise. Only /tuio/2Dcur
(cursors) is read: 'set' messages move a cursor (normalised 0..1 coordinates), 'alive' lists the
cursors still down (the others went up), 'fseq' ends a frame. Malformed packets are counted and
skipped, never raised.
"""

from __future__ import annotations

import logging
import math
import socket
import struct
import time

from pythonosc.osc_message import OscMessage
from pythonosc.osc_packet import OscPacket, ParseError

from arbor.game.input.events import DEVICE, DOWN, MOVE, UP, InputEvent

DEFAULT_PORT = 3333
MAX_MESSAGES = 64  # messages used from one bundle
MAX_CURSORS = 20  # fingers down at once; more is a hostile or broken sender
MAX_DATAGRAM = 16 * 1024  # bytes: a TUIO frame of MAX_CURSORS cursors is well under 2 KB
MAX_DEPTH = 4  # bundles inside bundles (TUIO senders use one)
BUNDLE = b"#bundle\0"
log = logging.getLogger("arbor.tuio")


LOG_EVERY = 60.0  # seconds: one log line per kind of bad input at most this often (a flood made 18.6 KB/s)


class LogLimit:
    """One log line per kind of bad input per LOG_EVERY seconds (the count since the last line said), so a
    flood of hostile datagrams cannot fill the disk with the kiosk's log."""

    def __init__(self, logger: logging.Logger, clock=time.monotonic) -> None:
        self.logger, self.clock = logger, clock
        self.last: dict[str, tuple[float, int]] = {}  # kind -> (when said, the total then)

    def warn(self, kind: str, total: int) -> bool:
        """Log ``kind`` (``total`` so far) unless it was logged less than LOG_EVERY seconds ago; True if logged."""
        now = self.clock()
        said = self.last.get(kind)
        if said is not None and now - said[0] < LOG_EVERY:
            return False
        since = total - (said[1] if said else 0)
        self.logger.warning("%s: %d since the last line, %d in all (said at most once a minute)", kind, since, total)
        self.last[kind] = (now, total)
        return True


class TuioParser:
    """TUIO 2Dcur session state: turns OSC messages into down/move/up pointer events."""

    def __init__(self, size: tuple[int, int], source: str = "tuio") -> None:
        self.size = size
        self.source = source
        self.down: dict[int, tuple[float, float]] = {}
        self.bad_packets = 0
        self.log_limit = LogLimit(log)

    def packet(self, data: bytes, now: float) -> list[InputEvent]:
        """Events for one UDP datagram (a bundle or a message)."""
        try:
            if len(data) > MAX_DATAGRAM or not _shallow(data, MAX_DEPTH):
                raise ParseError("too large or nested too deeply")  # before python-osc recurses into it
            packet = OscPacket(data)
        except (ParseError, ValueError, IndexError, TypeError, OverflowError, struct.error, RecursionError):
            self.bad_packets += 1
            self.log_limit.warn("dropped malformed TUIO packets", self.bad_packets)
            return [InputEvent(DEVICE, now, self.source, text="ignoring a malformed TUIO packet")] \
                if self.bad_packets == 1 else []
        out = []
        for timed in packet.messages[:MAX_MESSAGES]:
            out += self.message(timed.message, now)
        return out

    def message(self, msg: OscMessage, now: float) -> list[InputEvent]:
        """Events for one /tuio/2Dcur message; a message whose arguments have the wrong type or range
        is dropped (with one log line the first time), never raised."""
        if msg.address != "/tuio/2Dcur" or not msg.params:
            return []
        command, args = msg.params[0], msg.params[1:]
        w, h = self.size
        if command == "set" and len(args) >= 3:
            sid, x, y = args[0], args[1], args[2]
            if not (_session(sid) and _unit(x) and _unit(y)):
                return self._bad(now)
            if sid not in self.down and len(self.down) >= MAX_CURSORS:
                return self._bad(now)
            kind = MOVE if sid in self.down else DOWN
            self.down[sid] = (x * w, y * h)
            return [InputEvent(kind, now, self.source, sid, x * w, y * h)]
        if command == "alive":
            alive = {a for a in args if _session(a)}
            gone = [sid for sid in self.down if sid not in alive]
            return [InputEvent(UP, now, self.source, sid, *self.down.pop(sid)) for sid in gone]
        return []

    def _bad(self, now: float) -> list[InputEvent]:
        self.bad_packets += 1
        self.log_limit.warn("dropped TUIO messages with bad arguments", self.bad_packets)
        return [InputEvent(DEVICE, now, self.source, text="ignoring a malformed TUIO message")] \
            if self.bad_packets == 1 else []


def _shallow(data: bytes, depth: int) -> bool:
    """True when ``data`` nests bundles at most ``depth`` deep (each bundle: '#bundle\\0', an 8-byte time
    tag, then elements of a 4-byte big-endian size and that many bytes). Malformed sizes are left to
    the OSC parser to refuse; this only keeps it from recursing without end."""
    if not data.startswith(BUNDLE):
        return True
    if depth <= 0:
        return False
    at = len(BUNDLE) + 8
    while at + 4 <= len(data):
        (size,) = struct.unpack_from(">i", data, at)
        if size <= 0 or at + 4 + size > len(data):
            return True
        if not _shallow(data[at + 4:at + 4 + size], depth - 1):
            return False
        at += 4 + size
    return True


def _session(value) -> bool:
    """A TUIO session id: a non-negative 32-bit integer."""
    return isinstance(value, int) and not isinstance(value, bool) and 0 <= value < 2**32


def _unit(value) -> bool:
    """A normalised coordinate: a finite number in [0, 1]."""
    return isinstance(value, int | float) and not isinstance(value, bool) and math.isfinite(value) and 0 <= value <= 1


class TuioListener:
    """A non-blocking UDP socket feeding a :class:`TuioParser`; polled once per frame."""

    def __init__(self, size: tuple[int, int], host: str = "127.0.0.1", port: int = DEFAULT_PORT) -> None:
        self.parser = TuioParser(size, f"tuio:{host}:{port}")
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.setblocking(False)
        self.sock.bind((host, port))
        self.address = self.sock.getsockname()

    def poll(self, now: float) -> list[InputEvent]:
        """Every event from the datagrams that arrived since the last poll (at most 256)."""
        out = []
        for _ in range(256):
            try:
                data = self.sock.recv(65536)
            except BlockingIOError:
                break
            except OSError as exc:
                out.append(InputEvent(DEVICE, now, self.parser.source, text=f"TUIO stopped: {exc}"))
                break
            out += self.parser.packet(data, now)
        return out

    def close(self) -> None:
        """Stop listening."""
        self.sock.close()

