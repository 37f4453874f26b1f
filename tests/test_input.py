"""The input layer: fake HID trackers, TUIO over loopback, recordings replayed through the real game."""

import socket
import struct
import time

import pygame
import pytest
from pythonosc.osc_bundle_builder import IMMEDIATELY, OscBundleBuilder
from pythonosc.osc_message_builder import OscMessageBuilder

from arbor.game.input.events import (
    DEVICE,
    DOWN,
    MOVE,
    ROTATE,
    UP,
    InputEvent,
    InputHub,
    Player,
    Recorder,
    load_recording,
)
from arbor.game.input.hid import HidManager, SpaceMouseState, load_profiles, parse_spacemouse
from arbor.game.input.tuio import TuioListener
from arbor.game.screens.game import Game, GameConfig

SIZE = (1280, 720)


# ---------- fake hidapi --------------------------------------------------------------------------
class FakeDevice:
    def __init__(self, reports):
        self.reports = list(reports)
        self.closed = False
        self.fail = False

    def read(self):
        if self.fail:
            raise OSError("device disconnected")
        return self.reports.pop(0) if self.reports else b""

    def close(self):
        self.closed = True


class FakeBackend:
    def __init__(self):
        self.devices = {}  # path -> (info, FakeDevice)
        self.denied = set()

    def plug(self, path, vid, pid, reports, name="Fake"):
        self.devices[path] = ({"path": path, "vendor_id": vid, "product_id": pid, "product_string": name},
                              FakeDevice(reports))
        return self.devices[path][1]

    def unplug(self, path):
        self.devices.pop(path)

    def enumerate(self):
        return [info for info, _ in self.devices.values()]

    def open(self, info):
        if info["path"] in self.denied:
            raise OSError("open failed: permission denied")
        return self.devices[info["path"]][1]


def axes(rid, *values):
    return bytes([rid]) + struct.pack(f"<{len(values)}h", *values)


def test_spacemouse_old_and_new_layouts():
    old = SpaceMouseState()
    assert parse_spacemouse(axes(1, 350, -175, 0), old) and old.translation == (1.0, -0.5, 0.0)
    assert parse_spacemouse(axes(2, 0, 70, -350), old) and old.rotation == (0.0, 0.2, -1.0)
    new = SpaceMouseState()
    assert parse_spacemouse(axes(1, 35, 0, -35, 350, 0, 175), new)
    assert new.translation == (0.1, 0.0, -0.1) and new.rotation == (1.0, 0.0, 0.5)
    assert parse_spacemouse(bytes([3, 0b10, 0]), new) and new.buttons == 2
    for bad in (b"", b"\x01", b"\x01\x02\x03", b"\x07" + bytes(12), b"\x02\x00"):
        assert not parse_spacemouse(bad, SpaceMouseState())


def test_spacemouse_cursor_strokes_and_orbit():
    backend = FakeBackend()
    dev = backend.plug(b"/dev/a", 0x256F, 0xC635, [], "SpaceMouse Compact")
    hid = HidManager(backend)
    events = hid.poll(0.0)
    assert [e.kind for e in events] == [DEVICE] and "connected" in events[0].text
    dev.reports += [axes(1, 350, 0, -350, 0, 0, 0), bytes([3, 1])]
    hid.poll(0.05)
    events = hid.poll(0.10)  # 0.1 s at full deflection, 2 units/s: x right, up (device z is down)
    moves = [e for e in events if e.kind == MOVE]
    assert moves and moves[-1].dims == 3 and moves[-1].x == pytest.approx(0.2) and moves[-1].y == pytest.approx(0.2)
    dev.reports += [axes(1, 0, 0, 0, 175, 0, 350)]
    events = hid.poll(0.15)
    rot = [e for e in events if e.kind == ROTATE]
    assert rot and rot[0].ry == pytest.approx(90 * 0.05) and rot[0].rx == pytest.approx(45 * 0.05)


def test_unplug_mid_stroke_ends_the_stroke():
    backend = FakeBackend()
    dev = backend.plug(b"/dev/a", 0x256F, 0xC62E, [bytes([3, 1])], "SpaceMouse Wireless")
    hid = HidManager(backend, scan_interval=0.5)
    events = hid.poll(0.0)
    assert [e.kind for e in events] == [DEVICE, DOWN]
    dev.fail = True  # the read fails before the next scan notices
    events = hid.poll(0.1)
    assert [e.kind for e in events] == [UP, DEVICE] and "unplugged" in events[1].text
    assert hid.device_names() == [] and dev.closed
    backend.unplug(b"/dev/a")
    assert hid.poll(1.0) == []
    backend.plug(b"/dev/a", 0x256F, 0xC62E, [], "SpaceMouse Wireless")
    assert "connected" in hid.poll(2.0)[0].text  # and back again


def test_garbage_and_truncated_reports_are_messages_not_crashes():
    backend = FakeBackend()
    junk = [b"\xff" * 9, b"\x01\x02", b"", b"\x02", bytes(range(200))[:40], axes(1, 10, 10, 10)]
    dev = backend.plug(b"/dev/j", 0x256F, 0xC635, junk)
    hid = HidManager(backend)
    events = hid.poll(0.0) + hid.poll(0.1) + hid.poll(0.2)
    texts = [e.text for e in events if e.kind == DEVICE]
    assert any("malformed" in t for t in texts) and sum("malformed" in t for t in texts) == 1
    assert dev.reports == []


def test_permission_denied_and_missing_hidapi_are_messages():
    backend = FakeBackend()
    backend.plug(b"/dev/p", 0x256F, 0xC635, [])
    backend.denied.add(b"/dev/p")
    hid = HidManager(backend)
    first = hid.poll(0.0)
    assert len(first) == 1 and "permission" in first[0].text
    assert hid.poll(5.0) == []  # said once, not every scan

    class Broken:
        def enumerate(self):
            raise OSError("no hidapi")

    assert "cannot list" in HidManager(Broken()).poll(0.0)[0].text


def test_absolute_tracker_from_data_file(tmp_path):
    profiles = load_profiles("assets/input/devices.toml")
    p = profiles[0]
    backend = FakeBackend()
    report = bytes([1]) + struct.pack("<3hB", 500, 1500, -250, 1)
    backend.plug(b"/dev/t", p.vendor_id, p.product_id, [report, report[:4], bytes([9, 0, 0])])
    hid = HidManager(backend, profiles=profiles)
    events = hid.poll(0.0)
    down = next(e for e in events if e.kind == DOWN)
    move = next(e for e in events if e.kind == MOVE)
    assert (move.x, move.y, move.z) == pytest.approx((0.5, 1.5, -0.25)) and down.dims == 3
    assert any("malformed" in e.text for e in events if e.kind == DEVICE)  # the truncated one
    bad = tmp_path / "devices.toml"
    bad.write_text('[[device]]\nname = "x"\nvendor_id = 1\nproduct_id = 2\nreport_id = 1\n'
                   'x = { offset = 1, type = "int128" }\ny = { offset = 1, type = "int8" }\n'
                   'z = { offset = 1, type = "int8" }\n')
    with pytest.raises(ValueError, match="device #1"):
        load_profiles(bad)


# ---------- TUIO over loopback --------------------------------------------------------------------
def tuio_bundle(alive, sets, fseq):
    bundle = OscBundleBuilder(IMMEDIATELY)
    for args in (["alive", *alive], *[["set", sid, x, y, 0.0, 0.0, 0.0] for sid, x, y in sets], ["fseq", fseq]):
        msg = OscMessageBuilder("/tuio/2Dcur")
        for a in args:
            msg.add_arg(a)
        bundle.add_content(msg.build())
    return bundle.build().dgram


def test_tuio_cursors_over_loopback():
    listener = TuioListener(SIZE, "127.0.0.1", 0)
    sender = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    try:
        def send_and_poll(dgram):
            sender.sendto(dgram, listener.address)
            for _ in range(100):
                events = listener.poll(time.monotonic())
                if events:
                    return events
                time.sleep(0.005)
            return []

        down = send_and_poll(tuio_bundle([5], [(5, 0.25, 0.5)], 1))
        assert [(e.kind, e.pointer) for e in down] == [(DOWN, 5)]
        assert (down[0].x, down[0].y) == pytest.approx((320.0, 360.0))
        moved = send_and_poll(tuio_bundle([5, 6], [(5, 0.5, 0.5), (6, 0.1, 0.1)], 2))
        assert [e.kind for e in moved] == [MOVE, DOWN] and moved[0].x == pytest.approx(640.0)
        up = send_and_poll(tuio_bundle([6], [], 3))
        assert [(e.kind, e.pointer) for e in up] == [(UP, 5)]
        junk = send_and_poll(b"\x00garbage\xff")
        assert junk and junk[0].kind == DEVICE
    finally:
        sender.close()
        listener.close()


# ---------- recordings through the real game -----------------------------------------------------
@pytest.fixture(scope="module")
def ctx(gl_ctx):
    return gl_ctx


def session_events():
    t, out = 10.0, []
    out.append(InputEvent(DOWN, t, "touch:1", 0, 200, 400))
    for i in range(1, 10):
        out.append(InputEvent(MOVE, t + i * 0.05, "touch:1", 0, 200 + 25 * i, 400))
    out.append(InputEvent(UP, t + 0.5, "touch:1", 0, 425, 400))
    out.append(InputEvent(DOWN, t + 1.0, "mouse", -1, 600, 300))
    out.append(InputEvent(UP, t + 1.1, "mouse", -1, 600, 300))  # a tap: the menu opens
    return out


def test_recorded_session_replays_through_the_real_game(ctx, tmp_path):
    path = tmp_path / "session.jsonl"
    recorder = Recorder(path)
    clock = [100.0]
    live = Game(ctx, SIZE, GameConfig(saves=tmp_path / "a", seed=1, resume=False), clock=lambda: clock[0])
    for e in session_events():
        clock[0] = e.t
        recorder.write([e])
        live.handle_input(e)
    recorder.close()
    events = load_recording(path)
    assert events == session_events()  # timestamps and fields kept exactly

    clock2 = [500.0]
    hub = InputHub(SIZE, [Player(events, start=500.0)])
    again = Game(ctx, SIZE, GameConfig(saves=tmp_path / "b", seed=1, resume=False), clock=lambda: clock2[0])
    while clock2[0] < 502.0:  # the real frame loop: events, fixed steps, drawing
        for e in hub.poll([], clock2[0]):
            again.handle_input(e)
        again.update(1 / 60)
        clock2[0] += 1 / 60
    fbo = ctx.framebuffer(color_attachments=[ctx.renderbuffer(SIZE)], depth_attachment=ctx.depth_renderbuffer(SIZE))
    again.draw(fbo)
    assert again.control.yaw == pytest.approx(live.control.yaw)
    assert again.menu.visible and live.menu.visible
    assert sorted(again.state.devices) == ["mouse", "touch:1"]
    assert again.world.steps == pytest.approx(20, abs=1)  # two seconds of game time at 1x, 0.1 s steps


def test_bad_recording_names_its_line(tmp_path):
    path = tmp_path / "bad.jsonl"
    path.write_text('{"arbor_input_recording":1}\n{"kind":"down","t":1}\n{"kind":"down","t":2,"evil":1}\n')
    with pytest.raises(ValueError, match=r"bad\.jsonl:3"):
        load_recording(path)


def test_touch_coordinates_map_to_window_pixels(ctx, tmp_path):
    hub = InputHub(SIZE)
    e = pygame.event.Event(pygame.FINGERDOWN, touch_id=3, finger_id=7, x=0.25, y=0.75, dx=0, dy=0, pressure=0.4)
    (ev,) = hub.poll([e], 1.0)
    assert (ev.kind, ev.device, ev.pointer, ev.x, ev.y, ev.pressure) == (DOWN, "touch:3", 7, 320.0, 540.0, 0.4)
    emulated = pygame.event.Event(pygame.MOUSEBUTTONDOWN, button=1, pos=(1, 1), touch=True)
    assert hub.poll([emulated], 1.0) == []  # SDL's mouse emulation of a touch is not a second pointer


def test_tracker_cursor_is_drawn_where_it_is(ctx, tmp_path):
    game = Game(ctx, SIZE, GameConfig(saves=tmp_path, seed=1, resume=False), clock=lambda: 0.0)
    game.handle_input(InputEvent(MOVE, 0.0, "hid:SpaceMouse", 0, 0.5, 2.0, 0.0, dims=3))
    fbo = ctx.framebuffer(color_attachments=[ctx.renderbuffer(SIZE)], depth_attachment=ctx.depth_renderbuffer(SIZE))
    game.draw(fbo)
    x, y = game.hud.project(game.camera(), (0.5, 2.0, 0.0))
    overlay = pygame.image.frombytes(pygame.image.tobytes(game.hud.surface, "RGBA"), SIZE, "RGBA")
    ring = [overlay.get_at((int(x) + dx, int(y))) for dx in (-10, -9, 9, 10)]
    assert any(p.a > 150 and p.r > 200 and p.g > 180 for p in ring)
