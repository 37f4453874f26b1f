"""Hostile TUIO (issue 33): bundles nested 10,000 deep and 64 KB of random bytes are dropped before the OSC
library recurses into them; the home game (`arbor --tuio`, under xvfb-run) keeps running through them."""

import random
import socket
import struct
import time

from pythonosc.osc_bundle_builder import IMMEDIATELY, OscBundleBuilder
from pythonosc.osc_message_builder import OscMessageBuilder

from arbor.game.input.tuio import MAX_DEPTH, TuioParser
from tests.test_signals import _start, _stop_and_time


def nested(depth: int) -> bytes:
    """A /tuio/2Dcur 'alive' message inside ``depth`` bundles."""
    msg = OscMessageBuilder("/tuio/2Dcur")
    msg.add_arg("alive")
    data = msg.build().dgram
    for _ in range(depth):
        data = b"#bundle\0" + b"\0" * 7 + b"\1" + struct.pack(">i", len(data)) + data
    return data


def test_deep_bundles_and_random_bytes_are_dropped_not_raised():
    parser = TuioParser((1280, 720))
    assert parser.packet(nested(MAX_DEPTH), 0.0) == []  # as deep as TUIO allows: read (an empty alive)
    assert parser.bad_packets == 0
    for data in (nested(10_000), nested(2_000)[:16_000], nested(MAX_DEPTH + 1),
                 random.Random(1).randbytes(64 * 1024)):
        parser.packet(data, 0.0)
    assert parser.bad_packets == 4


def test_a_valid_bundle_still_reads_after_the_attack():
    parser = TuioParser((1280, 720))
    parser.packet(nested(10_000), 0.0)
    bundle = OscBundleBuilder(IMMEDIATELY)
    for args in (["alive", 5], ["set", 5, 0.25, 0.5, 0.0, 0.0, 0.0], ["fseq", 1]):
        msg = OscMessageBuilder("/tuio/2Dcur")
        for a in args:
            msg.add_arg(a)
        bundle.add_content(msg.build())
    events = parser.packet(bundle.build().dgram, 1.0)
    assert [e.kind for e in events][-1] == "down" and events[-1].x == 320


def test_the_home_game_survives_a_deep_bundle_and_random_bytes(tmp_path):
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    proc, pid, err = _start(["--tuio", "--tuio-port", str(port)], tmp_path)
    deadline = time.monotonic() + 150
    while b"arbor-timing garden" not in err.read_bytes() and proc.poll() is None and time.monotonic() < deadline:
        time.sleep(0.2)  # (the garden's first frame: it listens)
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as out:
        for data in (nested(3_000), random.Random(2).randbytes(60_000), nested(10_000)[:65_000]):
            out.sendto(data, ("127.0.0.1", port))
    time.sleep(2.0)
    assert proc.poll() is None  # still running
    _, code, err = _stop_and_time(proc, pid, err)
    assert code == 0, err[-2000:]
    assert "RecursionError" not in err and "Traceback" not in err


def test_a_flood_of_bad_messages_logs_one_line_per_kind_per_minute(caplog):
    """Issue 45: every bad TUIO message logged a warning (18.6 KB/s of kiosk.log in a paced flood)."""
    from arbor.game.input.tuio import LOG_EVERY, TuioParser

    parser = TuioParser((800, 600))
    clock = [0.0]
    parser.log_limit.clock = lambda: clock[0]
    msg = OscMessageBuilder("/tuio/2Dcur")
    for a in ["set", 5, 7.5, 0.5, 0.0, 0.0, 0.0]:  # x out of 0..1: a message with bad arguments
        msg.add_arg(a)
    bad = msg.build().dgram
    for i in range(1000):
        clock[0] = i * 0.1  # 100 s of a flood, 10 a second
        parser.packet(bad, clock[0])
    lines = [r for r in caplog.records if r.name == "arbor.tuio"]
    assert len(lines) == 2 and LOG_EVERY == 60.0 and parser.bad_packets == 1000
    assert "600 since the last line, 601 in all" in lines[1].getMessage()
