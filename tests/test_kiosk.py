"""Kiosk mode: touch only, staff PIN, attract loop, visitor reset, fault recovery, watchdog, strings."""

import sys
import time
from pathlib import Path

import pygame
import pytest

from arbor.engine.base.errors import LSysError
from arbor.game import strings
from arbor.game.input.events import DOWN, KEY_DOWN, MOVE, QUIT, UP, InputEvent
from arbor.game.screens.game import Game, GameConfig
from arbor.game.screens.kiosk import Kiosk, KioskConfig, load_kiosk_config
from arbor.game.watchdog import STAFF_EXIT, watch
from tests.conftest import FakeClock

SIZE = (1280, 720)


@pytest.fixture
def kiosk(gl_ctx, tmp_path):
    clock = FakeClock(50.0)
    config = KioskConfig(attract_after=10.0, reset_after=30.0, admin_hold=2.0, speed=10.0)
    folder = tmp_path / "kiosk"  # as run_kiosk does: the kiosk's own folder, never the home saves
    k = Kiosk(lambda: Game(gl_ctx, SIZE, GameConfig(saves=folder, seed=2, resume=True), clock=clock), config,
              folder, clock=clock)
    k.fake = clock
    k.fbo = gl_ctx.framebuffer(color_attachments=[gl_ctx.renderbuffer(SIZE)],
                               depth_attachment=gl_ctx.depth_renderbuffer(SIZE))
    return k


def tap(k, x, y, pid=5):
    assert k.frame([InputEvent(DOWN, k.fake.t, "touch:1", pid, x, y)], 0.0, k.fbo)
    k.fake.t += 0.1
    return k.frame([InputEvent(UP, k.fake.t, "touch:1", pid, x, y)], 0.0, k.fbo)


def test_settings_file(tmp_path):
    config = load_kiosk_config("assets/kiosk.toml")
    assert config.pin.isdigit() and config.reset_after > config.attract_after
    bad = tmp_path / "k.toml"
    bad.write_text('pin = "12"\n')
    with pytest.raises(LSysError, match="PIN"):
        load_kiosk_config(bad)
    bad.write_text("wallpaper = 1\n")
    with pytest.raises(LSysError, match="unknown"):
        load_kiosk_config(bad)


def test_keys_and_window_close_do_not_quit(kiosk):
    for e in (InputEvent(QUIT, 0.0, "window"), InputEvent(KEY_DOWN, 0.0, "keyboard", key=pygame.K_ESCAPE)):
        assert kiosk.frame([e], 0.0, kiosk.fbo)


def test_staff_pin_quits_only_when_right(kiosk):
    assert kiosk.frame([InputEvent(DOWN, kiosk.fake.t, "touch:1", 1, 20, 20)], 0.0, kiosk.fbo)
    kiosk.fake.t += 2.5
    kiosk.frame([], 0.0, kiosk.fbo)
    pad = kiosk.pin_pad
    assert pad is not None
    for digit in "1111":
        tap(kiosk, *pad.keys[digit].center)
    tap(kiosk, *pad.keys["ok"].center)
    assert pad.wrong and not kiosk.quit_requested
    for digit in kiosk.config.pin:
        tap(kiosk, *pad.keys[digit].center)
    ok = InputEvent(DOWN, kiosk.fake.t, "touch:1", 5, *pad.keys["ok"].center)
    assert not kiosk.frame([ok], 0.0, kiosk.fbo) and kiosk.quit_requested


def test_wrong_pins_lock_the_pad_longer_each_time(kiosk):
    kiosk.frame([InputEvent(DOWN, kiosk.fake.t, "touch:1", 1, 20, 20)], 0.0, kiosk.fbo)
    kiosk.fake.t += 2.5
    kiosk.frame([], 0.0, kiosk.fbo)
    pad = kiosk.pin_pad

    def enter(code):
        for digit in code:
            tap(kiosk, *pad.keys[digit].center)
        return kiosk.frame([InputEvent(DOWN, kiosk.fake.t, "touch:1", 5, *pad.keys["ok"].center)], 0.0, kiosk.fbo)

    for _ in range(3):
        assert enter("0000")
    assert kiosk.pin_lock.locked_for(kiosk.fake.t) == 30.0
    assert enter(kiosk.config.pin) and not kiosk.quit_requested  # the right PIN is refused while locked
    kiosk.fake.t += 31.0
    assert enter("0000") and kiosk.pin_lock.locked_for(kiosk.fake.t) == 60.0  # then the delay doubles
    kiosk.fake.t += 61.0
    assert not enter(kiosk.config.pin) and kiosk.quit_requested


def test_attract_loop_after_idle_and_visitor_touch_ends_it(kiosk):
    yaw = kiosk.game.control.yaw
    kiosk.fake.t += 11.0
    kiosk.frame([], 1 / 60, kiosk.fbo)
    assert kiosk.attract is not None
    for _ in range(40):
        kiosk.fake.t += 1 / 60
        kiosk.frame([], 1 / 60, kiosk.fbo)
    assert kiosk.game.control.yaw != yaw  # the recorded drags turn the tree
    tap(kiosk, 640, 400)
    assert kiosk.attract is None


def test_idle_visitor_tree_is_saved_and_replanted(kiosk, tmp_path):
    kiosk.game.world.sim.state.wilt = 0.6
    kiosk.fake.t += 31.0
    kiosk.frame([], 1 / 60, kiosk.fbo)
    saved = list((tmp_path / "kiosk").glob("visitor-*.arbor"))
    assert len(saved) == 1 and kiosk.game.world.sim.state.wilt == 0.0
    kiosk.fake.t += 31.0
    kiosk.frame([], 1 / 60, kiosk.fbo)
    assert len(list((tmp_path / "kiosk").glob("visitor-*.arbor"))) == 1  # once per visitor


def test_a_failing_frame_is_logged_and_the_garden_restarts(kiosk, caplog, monkeypatch):
    text = kiosk.game.world.tree.lstring.to_text()
    kiosk.game.save()

    def boom(*_):
        raise RuntimeError("simulated fault")

    monkeypatch.setattr(kiosk.game, "update", boom)
    assert kiosk.frame([], 1 / 60, kiosk.fbo)
    assert kiosk.recoveries == 1 and "simulated fault" in caplog.text
    assert kiosk.game.world.tree.lstring.to_text() == text  # the tree came back from the autosave
    assert kiosk.frame([InputEvent(MOVE, 0.0, "touch:1", 0, 10, 10)], 1 / 60, kiosk.fbo)


def test_watchdog_restarts_until_staff_quit(tmp_path):
    counter = tmp_path / "runs"
    script = (f"import pathlib, sys; p = pathlib.Path({str(counter)!r}); n = int(p.read_text()) if p.exists() else 0; "
              f"p.write_text(str(n + 1)); sys.exit([0, 1, {STAFF_EXIT}][n])")
    pauses = []
    assert watch([sys.executable, "-c", script], sleep=pauses.append, poll=0.05) == STAFF_EXIT
    assert counter.read_text() == "3" and pauses == [1.0, 2.0]  # status 0 is restarted too: only staff stop it


def test_watchdog_kills_a_hung_app_and_moves_a_crashing_save_aside(tmp_path):
    folder = tmp_path / "kiosk"
    folder.mkdir()
    (folder / "autosave.arbor").write_text("poison")
    counter = tmp_path / "runs"
    script = (f"import os, pathlib, sys, time; p = pathlib.Path({str(counter)!r}); n = int(p.read_text()) "
              "if p.exists() else 0; p.write_text(str(n + 1))\n"
              f"save = pathlib.Path({str(folder)!r}) / 'autosave.arbor'\n"
              "if save.exists(): pathlib.Path(os.environ['ARBOR_HEARTBEAT'] + '.reading').write_text(str(save))\n"
              "if n == 0: time.sleep(60)\n"  # hangs, never beats
              f"sys.exit({STAFF_EXIT} if n >= 3 else 1)")  # (dies while reading the save, as reading() notes)
    started = time.monotonic()
    status = watch([sys.executable, "-c", script], sleep=lambda s: None, poll=0.05, hang=0.5, grace=0.5)
    assert status == STAFF_EXIT and time.monotonic() - started < 20  # the hang was killed in about a second
    assert not (folder / "autosave.arbor").exists() and (folder / "autosave.arbor.crashed").read_text() == "poison"


def test_strings_come_from_one_file(tmp_path, gl_ctx):
    folder = tmp_path / "strings"
    folder.mkdir()
    (folder / "en.toml").write_text(Path("assets/strings/en.toml").read_text())
    (folder / "fr.toml").write_text('[menu]\nreplant = "Nouvel arbre"\n')
    try:
        strings.set_language("fr", folder)
        game = Game(gl_ctx, SIZE, GameConfig(saves=tmp_path, seed=1, resume=False), clock=lambda: 0.0)
        assert game.menu.widget("replant").label == "Nouvel arbre"
        assert game.menu.widget("save").label == "Save"  # missing keys fall back to English
    finally:
        strings.set_language("en")


def test_kiosk_runs_fullscreen_in_a_real_window(tmp_path):
    import os
    import shutil
    import subprocess

    if shutil.which("xvfb-run") is None:
        pytest.skip("needs xvfb-run (CI installs it)")
    shot = tmp_path / "kiosk.png"
    env = dict(os.environ, SDL_VIDEODRIVER="x11", SDL_AUDIODRIVER="dummy", ARBOR_MAX_FRAMES="5",
               ARBOR_SCREENSHOT=str(shot), ARBOR_SAVES=str(tmp_path / "saves"))
    cmd = ["xvfb-run", "-a", "-s", "-screen 0 1024x768x24", sys.executable, "-m", "arbor.game.cli", "--kiosk"]
    proc = subprocess.run(cmd, env=env, capture_output=True, timeout=120)
    assert proc.returncode == 0, proc.stderr.decode()[-2000:]
    assert pygame.image.load(str(shot)).get_size() == (1024, 768)  # the whole screen
    assert (tmp_path / "saves" / "kiosk" / "kiosk.log").exists()
