"""The real game, headless: SDL dummy video for events, EGL for pixels, synthetic touch/mouse/keys."""

import math

import numpy as np
import pygame
import pytest

from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.log import replay
from arbor.game.input.gestures import MAX_TILT
from arbor.game.screens.game import Game, GameConfig
from tests.conftest import FakeClock

SIZE = (1280, 720)


@pytest.fixture(scope="module")
def ctx(gl_ctx):
    return gl_ctx


@pytest.fixture
def game(ctx, tmp_path):
    clock = FakeClock()
    g = Game(ctx, SIZE, GameConfig(saves=tmp_path, seed=4), clock=clock, wall_clock=lambda: 1.7e9 + clock.t)
    g.fake_clock = clock
    pygame.event.clear()
    return g


def post(kind, **attrs):
    pygame.event.post(pygame.event.Event(kind, **attrs))


def pump(game):
    for e in pygame.event.get():
        game.handle_event(e)


def finger(kind, fid, x, y):
    post(kind, touch_id=1, finger_id=fid, x=x / SIZE[0], y=y / SIZE[1], dx=0.0, dy=0.0, pressure=1.0)


def drag(game, fid, path, dt=0.05):
    finger(pygame.FINGERDOWN, fid, *path[0])
    pump(game)
    for p in path[1:]:
        game.fake_clock.t += dt
        finger(pygame.FINGERMOTION, fid, *p)
        pump(game)
    game.fake_clock.t += dt
    finger(pygame.FINGERUP, fid, *path[-1])
    pump(game)


def tap(game, x, y):
    finger(pygame.FINGERDOWN, 9, x, y)
    pump(game)
    game.fake_clock.t += 0.1
    finger(pygame.FINGERUP, 9, x, y)
    pump(game)


def test_one_finger_drag_turns_the_tree_all_the_way_round(game):
    yaw0 = game.control.yaw
    drag(game, 0, [(200 + 30 * i, 400) for i in range(16)])  # 450 px to the right
    assert game.control.yaw == pytest.approx((yaw0 - 180) % 360)
    drag(game, 0, [(200 + 30 * i, 400) for i in range(16)])
    assert game.control.yaw == pytest.approx(yaw0 % 360)
    assert not game.menu.visible


def test_two_fingers_one_still_tilts_up_to_acos_0_8(game):
    finger(pygame.FINGERDOWN, 0, 300, 300)
    finger(pygame.FINGERDOWN, 1, 900, 200)
    pump(game)
    for i in range(1, 20):
        game.fake_clock.t += 0.03
        finger(pygame.FINGERMOTION, 1, 900, 200 + 20 * i)
        pump(game)
    assert game.control.tilt == pytest.approx(MAX_TILT)
    assert pytest.approx(math.degrees(math.acos(0.8))) == MAX_TILT
    finger(pygame.FINGERUP, 1, 900, 580)
    finger(pygame.FINGERUP, 0, 300, 300)
    pump(game)
    assert not game.menu.visible  # a two-finger gesture is never a tap


def test_pinch_zooms_faster_when_farther(game):
    def pinch(spread):
        finger(pygame.FINGERDOWN, 0, 600, 360)
        finger(pygame.FINGERDOWN, 1, 700, 360)
        pump(game)
        before = game.control.distance
        game.fake_clock.t += 0.05
        finger(pygame.FINGERMOTION, 0, 600 - spread, 360)
        finger(pygame.FINGERMOTION, 1, 700 + spread, 360)
        pump(game)
        finger(pygame.FINGERUP, 0, 600 - spread, 360)
        finger(pygame.FINGERUP, 1, 700 + spread, 360)
        pump(game)
        return before, game.control.distance

    near_before, near_after = pinch(50)
    assert near_after < near_before
    game.control.distance = 4.0
    far_before, far_after = pinch(50)
    assert (far_before - far_after) > 2 * (near_before - near_after)


def test_tap_shows_menu_at_tap_point_and_blocks_camera(game):
    tap(game, 400, 100)
    assert game.menu.visible and game.menu.rect.topleft == (400, 100)
    assert all(w.rect.height >= 48 for w in game.menu.shown())
    yaw = game.control.yaw
    drag(game, 0, [(900, 650), (1000, 650), (1100, 650)])
    assert game.control.yaw == yaw  # camera gestures are off while the menu is shown
    tap(game, 1100, 650)
    assert not game.menu.visible


def test_menu_water_button_waters_while_held(game):
    tap(game, 300, 200)
    button = game.menu.reveal("water").rect.center
    finger(pygame.FINGERDOWN, 3, *button)
    pump(game)
    assert game.world.sim.state.watering
    water = game.world.sim.state.water_meter
    game.update(1.0)
    assert game.world.sim.state.water_meter > water
    finger(pygame.FINGERUP, 3, *button)
    pump(game)
    assert not game.world.sim.state.watering
    assert game.menu.visible


def test_menu_sliders_and_sapling(game):
    tap(game, 300, 200)
    slider = game.menu.reveal("orbit_height").rect
    drag(game, 4, [(slider.left + 20, slider.centery), (slider.right - 5, slider.centery)])
    assert game.world.sim.state.orbit_height == pytest.approx(game.rules.sun.orbit_height_max, abs=0.05)
    speed = game.menu.reveal("sun_speed").rect
    drag(game, 4, [(speed.centerx, speed.centery), (speed.left + 10, speed.centery)])
    assert game.world.sim.state.sun_speed < 0.01
    game.world.sim.state.wilt = 0.7
    sapling = game.menu.reveal("replant").rect.center
    tap(game, *sapling)  # issue 28: the first press only asks ...
    assert game.world.sim.state.wilt == 0.7 and "again" in game.hud_info().message
    tap(game, *game.menu.reveal("replant").rect.center)  # ... the second replants
    assert game.world.sim.state.wilt == 0.0
    assert 0.25 <= game.world.sim.state.sun_meter <= 1.0


def test_mouse_and_keyboard_equivalents(game):
    yaw = game.control.yaw
    post(pygame.MOUSEBUTTONDOWN, button=1, pos=(500, 400), touch=False)
    post(pygame.MOUSEMOTION, buttons=(1, 0, 0), pos=(600, 400), rel=(100, 0), touch=False)
    post(pygame.MOUSEBUTTONUP, button=1, pos=(600, 400), touch=False)
    pump(game)
    assert game.control.yaw == pytest.approx((yaw - 40) % 360)
    post(pygame.MOUSEBUTTONDOWN, button=3, pos=(600, 100), touch=False)
    post(pygame.MOUSEMOTION, buttons=(0, 0, 1), pos=(600, 500), rel=(0, 400), touch=False)
    post(pygame.MOUSEBUTTONUP, button=3, pos=(600, 500), touch=False)
    pump(game)
    assert game.control.tilt == pytest.approx(MAX_TILT)
    d = game.control.distance
    post(pygame.MOUSEWHEEL, x=0, y=2, flipped=False, touch=False)
    pump(game)
    assert game.control.distance == pytest.approx(d * 0.81)
    post(pygame.MOUSEBUTTONDOWN, button=1, pos=(500, 300), touch=False)
    pump(game)
    game.fake_clock.t += 0.1
    post(pygame.MOUSEBUTTONUP, button=1, pos=(500, 300), touch=False)
    pump(game)
    assert game.menu.visible  # a click is a tap
    for key in (pygame.K_m, pygame.K_3):
        post(pygame.KEYDOWN, key=key, mod=0, unicode="", scancode=0)
    post(pygame.KEYDOWN, key=pygame.K_w, mod=0, unicode="w", scancode=0)
    pump(game)
    assert not game.menu.visible and game.loop.speed == 100 and game.world.sim.state.watering
    post(pygame.KEYUP, key=pygame.K_w, mod=0, unicode="w", scancode=0)
    pump(game)
    assert not game.world.sim.state.watering


def test_meters_and_growth_under_the_rules(game):
    game.state.autopilot = True  # (tended, so the fast-forward guardian (issue 28) has no need to stop)
    game.set_speed(100.0)
    s = game.world.sim.state
    s.orbit_height, s.sun_meter, s.water_meter = 1.0, 0.9, 0.9
    t0, modules0 = s.length_time, len(game.world.tree.lstring)
    for _ in range(60):  # one real second at 60 fps = 100 s of game time
        game.act(Action.WATER, float(game.world.sim.state.water_meter < 0.6))
        game.update(1 / 60)
    s = game.world.sim.state
    assert s.time == pytest.approx(100.0, abs=0.2)
    assert s.sun_cycle.earned >= 1 and s.length_time > t0
    assert len(game.world.tree.lstring) > modules0 and game.world.status() == "growing"


def test_slow_frame_does_not_spiral(game):
    game.state.autopilot = True  # (tended, so the fast-forward guardian (issue 28) has no need to stop)
    game.set_speed(100.0)
    steps = game.loop.steps
    game.update(5.0)  # a 5 s hitch
    assert game.loop.steps - steps == 250  # clamped to 0.25 s of real time


def test_input_log_replays_identically(game):
    game.set_speed(10.0)
    for i in range(120):
        if i == 10:
            game.act(Action.WATER, 1.0)
        if i == 40:
            game.act(Action.WATER, 0.0)
        if i == 70:
            game.act(Action.ORBIT_HEIGHT, 0.9)
        game.update(1 / 30)
    again = replay(game.world.log)
    assert again.sim.state == game.world.sim.state
    assert again.tree.lstring.to_text() == game.world.tree.lstring.to_text()


def test_save_resume_and_offline_growth(ctx, game, tmp_path):
    game.state.autopilot = True  # (tended, so the fast-forward guardian (issue 28) has no need to stop)
    game.set_speed(100.0)
    for _ in range(60):
        game.update(1 / 60)
    game.quit()
    text = game.world.tree.lstring.to_text()
    clock = game.fake_clock
    clock.t += 30.0  # away for 30 s of wall time
    again = Game(ctx, SIZE, GameConfig(saves=tmp_path, seed=99), clock=clock,
                 wall_clock=lambda: 1.7e9 + clock.t)
    assert again.world.sim.state.time == pytest.approx(game.world.sim.state.time + 30.0, abs=1.0)
    # the same tree, grown on (its first modules thicken meanwhile: a sapling starts comfortable since issue 28)
    assert again.world.seed == game.world.seed and again.world.tree.lstring.to_text().count("I(") >= text.count("I(")
    assert again.world.sim.state.girth_time > game.world.sim.state.girth_time


def test_corrupt_autosave_is_kept_and_a_new_tree_planted(ctx, tmp_path):
    (tmp_path / "autosave.arbor").write_text("format = 1\nthis is not toml [[[")
    clock = FakeClock()
    g = Game(ctx, SIZE, GameConfig(saves=tmp_path, seed=2), clock=clock, wall_clock=lambda: 1.7e9)
    assert "Could not load autosave.arbor" in g.hud_info().message
    assert (tmp_path / "autosave.arbor.broken").read_text().startswith("format = 1\nthis is not")
    assert len(g.world.tree.lstring) > 2


def test_game_screen_with_hud(ctx, game):
    size = SIZE
    fbo = ctx.framebuffer(color_attachments=[ctx.renderbuffer(size)], depth_attachment=ctx.depth_renderbuffer(size))
    game.world.sim.state.watering = True
    game.draw(fbo)
    img = np.frombuffer(fbo.read(components=3), np.uint8).reshape(size[1], size[0], 3)[::-1]
    sun_bar, water_bar = img[40, 120], img[88, 120]
    assert sun_bar[0] > 200 and sun_bar[1] > 160 and sun_bar[2] < 100  # yellow sun meter
    assert water_bar[2] > 200 and water_bar[0] < 100  # blue water meter
    green = (img[..., 1].astype(int) > img[..., 0] + 10) & (img[..., 1].astype(int) > img[..., 2] + 10)
    assert green[300:, :].mean() > 0.3  # grass


def test_a_garden_of_several_trees(ctx, tmp_path):
    clock = FakeClock()
    game = Game(ctx, SIZE, GameConfig(saves=tmp_path, seed=4), clock=clock, wall_clock=lambda: 1.7e9 + clock.t)
    fbo = ctx.framebuffer(color_attachments=[ctx.renderbuffer(SIZE)], depth_attachment=ctx.depth_renderbuffer(SIZE))
    game.draw(fbo)
    alone = game.triangles
    first = game.world
    game.act(Action.PLANT, 1.0)
    game.act(Action.PLANT, 1.0)
    assert len(game.others) == 2 and game.world is not first
    positions = {game.world.position, *(o.position for o in game.others)}
    assert len(positions) == 3  # three places in the garden
    game.draw(fbo)
    trees = [p for p in game.renderer.placed if p.version >= 0]  # (and the scenery: stones, shrubs, a path)
    assert len(trees) == 3 and game.triangles > 1.3 * alone  # all three drawn (far ones coarser)
    game.act(Action.ORBIT_HEIGHT, 0.9)
    assert {round(o.sim.state.orbit_height, 6) for o in [game.world, *game.others]} == {
        round(game.world.sim.state.orbit_height, 6)}  # one sun for the whole garden
    game.act(Action.NEXT, 1.0)
    assert game.world is first  # "next" goes round the garden, oldest first
    game.state.autopilot = True  # (tended, so the fast-forward guardian (issue 28) has no need to stop)
    game.set_speed(100.0)
    for _ in range(30):
        game.update(1 / 60)
    assert all(o.sim.state.time > 40 for o in game.others)  # every tree lives on
    game.quit()
    again = Game(ctx, SIZE, GameConfig(saves=tmp_path, seed=4), clock=clock, wall_clock=lambda: 1.7e9 + clock.t)
    assert len(again.others) == 2
    assert {again.world.position, *(o.position for o in again.others)} == positions
    for _ in range(6):
        game.act(Action.PLANT, 1.0)
    assert len(game.others) + 1 == 6  # the garden has a limit
