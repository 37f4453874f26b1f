"""Issue 28: the kiosk with nobody there cares for its garden, and the attract loop moves no setting for good."""

import pytest

from arbor.game.input.events import DOWN, MOVE, UP, InputEvent, Recorder
from arbor.game.render.ui import Menu
from arbor.game.screens.game import Game, GameConfig
from arbor.game.screens.kiosk import Kiosk, load_kiosk_config
from arbor.game.screens.state import LOW_SUN
from arbor.game.strings import set_language
from tests.conftest import FakeClock

SIZE = (1280, 720)
FRAME = 0.25  # real seconds a frame (the game loop's clamp: 25 steps at 10x)


def slider_drags(path, size=SIZE):
    """An attract recording that does what a careless one could: it opens the menu, drags the sun height
    slider to its lowest, presses the speed button and leaves the menu open."""
    set_language("en")
    menu = Menu(size)
    menu.show_at(600, 200)
    sun, speed = menu.widget("orbit_height").rect, menu.widget("speed").rect
    events = [InputEvent(DOWN, 0.0, "attract", 1, 600, 200), InputEvent(UP, 0.1, "attract", 1, 600, 200),
              InputEvent(DOWN, 1.0, "attract", 2, *sun.center)]
    events += [InputEvent(MOVE, 1.0 + i / 10, "attract", 2, sun.centerx - i * sun.width / 10, sun.centery)
               for i in range(1, 11)]
    events += [InputEvent(UP, 2.2, "attract", 2, sun.left, sun.centery),
               InputEvent(DOWN, 3.0, "attract", 3, *speed.center), InputEvent(UP, 3.1, "attract", 3, *speed.center),
               InputEvent(MOVE, 6.0, "attract", 4, 5, 5)]  # (the run lasts 6 s)
    recorder = Recorder(path)
    recorder.write(events)
    recorder.close()
    return path


@pytest.fixture
def left_alone(gl_ctx, tmp_path):
    """The kiosk with kiosk.toml's timings and speed over a garden of two trees, playing a careless attract
    recording, on a fake clock."""
    config = load_kiosk_config("assets/kiosk.toml")
    config.attract = str(slider_drags(tmp_path / "careless.jsonl"))  # (absolute: read as it is)
    clock = FakeClock(100.0)
    folder = tmp_path / "kiosk"
    kiosk = Kiosk(lambda: Game(gl_ctx, SIZE, GameConfig(saves=folder, seed=4, resume=False, pace="demo"),
                               clock=clock), config, folder, clock=clock)
    kiosk.game.care.plant()
    kiosk.fake = clock
    kiosk.fbo = gl_ctx.framebuffer(color_attachments=[gl_ctx.renderbuffer(SIZE)])
    return kiosk


def idle(kiosk, seconds, on_frame=lambda: None):
    for i in range(int(seconds / FRAME)):
        kiosk.fake.t += FRAME
        if i % 40:
            kiosk.update(FRAME)
        else:
            assert kiosk.frame([], FRAME, kiosk.fbo)
        on_frame()


def test_the_kiosk_left_alone_keeps_every_tree_alive_and_its_settings(left_alone):
    kiosk = left_alone
    game, rules = kiosk.game, kiosk.game.rules
    want = (rules.sun.orbit_height, rules.sun.speed, kiosk.config.speed)
    seen = {"runs": 0, "poured": False, "after": [], "driest": 1.0}

    def look():
        worlds = kiosk.game.garden.worlds
        seen["poured"] = seen["poured"] or any(w.sim.state.watering for w in worlds)
        if kiosk.clock() - kiosk.last_touch > kiosk.config.care_after + 5:
            seen["driest"] = min(seen["driest"], *(w.sim.state.water_meter for w in worlds))
        show = kiosk.attract
        if show is not None and show.runs != seen["runs"]:
            seen["runs"] = show.runs
            seen["after"].append((show.after_run.orbit_height, show.after_run.sun_speed, show.after_run.speed,
                                  kiosk.game.menu.visible))

    idle(kiosk, 400.0, look)  # 4000 s of game time at 10x: care, attract runs, the visitor reset
    worlds = kiosk.game.garden.worlds
    assert len(worlds) == 2 and all(w.sim.state.alive for w in worlds)
    assert all(w.sim.state.wilt < 0.2 for w in worlds)
    assert seen["poured"]  # (the can poured: the care is seen)
    assert seen["driest"] > rules.growth.threshold  # (kept in the healthy band: no meter reached the need line)
    assert len(seen["after"]) >= 20 and set(seen["after"]) == {(*want, False)}  # (each run ends with it closed)
    assert len(list((kiosk.saves).glob("visitor-*.arbor"))) == 1
    assert game is kiosk.game and kiosk.recoveries == 0


def test_a_visitor_after_the_autopilot_takes_over_in_daylight(left_alone):
    kiosk = left_alone
    idle(kiosk, 40.0)
    assert kiosk.game.state.autopilot
    for world in kiosk.game.garden.worlds:
        world.sim.state.sun_angle = -1.4  # deep night
    assert kiosk.game.world.sim.sun_height() < 0
    kiosk.frame([InputEvent(DOWN, kiosk.fake.t, "touch:1", 5, 640, 400)], 0.0, kiosk.fbo)
    assert not kiosk.game.state.autopilot
    assert all(w.sim.sun_height() >= LOW_SUN for w in kiosk.game.garden.worlds)


def test_a_visitor_after_the_attract_loop_gets_every_hint(left_alone):
    kiosk = left_alone
    idle(kiosk, 120.0)  # the show has turned the view
    assert kiosk.attract is not None
    kiosk.frame([InputEvent(DOWN, kiosk.fake.t, "touch:1", 5, 640, 400)], 0.0, kiosk.fbo)
    assert kiosk.attract is None and kiosk.game.coach.hints == ["water", "sun", "turn"]
