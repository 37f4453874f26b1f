"""Issue 28: fast-forward cannot kill (the guardian) and the HUD's status tells the truth."""

import pytest

from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.garden import Garden
from arbor.engine.life.world.guardian import Guardian
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import load_lsystem


@pytest.fixture(scope="module")
def system(lsys_dir):
    return load_lsystem(lsys_dir / "game_tree.lsys")


@pytest.fixture
def rules():
    return load_rules("assets/rules.toml", pace="demo")


def test_the_guardian_tells_a_thirst_before_the_need_line_and_tending_keeps_the_tree(system, rules):
    garden = Garden([World(system, rules, seed=3)])
    garden.plant(system, rules)
    guardian = Guardian(rules)
    told = None
    for _ in range(3000):  # 300 s of demo time, nobody waters
        garden.step(0.1)
        told = told or guardian.watch(garden)
        if told:
            break
    assert told is not None and told.what == "water"
    water = garden.worlds[told.index].sim.state.water_meter
    assert rules.growth.threshold < water < rules.growth.threshold + rules.health.guard_margin + 0.01
    guardian.tend(garden)  # "go on": the can pours until the meter is comfortable, then is let go
    assert garden.worlds[told.index].sim.state.watering
    peak = 0.0
    for _ in range(100):
        garden.step(0.1)
        guardian.care(garden)
        peak = max(peak, garden.worlds[told.index].sim.state.water_meter)
    assert not garden.worlds[told.index].sim.state.watering
    assert rules.health.comfort <= peak < rules.health.comfort + 0.02


def test_new_saplings_start_comfortable(system, rules):
    garden = Garden([World(system, rules, seed=3)])
    for _ in range(4):
        s = garden.plant(system, rules).sim.state
        assert 0.65 < s.water_meter < rules.water.drown_level and s.sun_meter > 0.65


def test_status_follows_one_ranking_of_the_real_state(system, rules):
    world = World(system, rules, seed=1)
    s = world.sim.state
    s.water_meter, s.drowning, s.wilt = 1.0, rules.water.drown_time + 1, 0.9  # drowned and wilting
    assert world.status() == "drowning"
    s.drowning, s.wilt, s.water_meter, s.sun_meter = 0.0, 0.0, 0.8, 0.3
    s.sun_angle = -1.2  # night: the sun is down
    assert world.sim.sunshine() == 0 and world.status() != "needs_light"
    s.sun_cycle.rate = s.water_cycle.rate = 1.0
    assert world.status() == "resting" and world.status(dark=False) == "growing"
    s.alive = False
    assert world.status() == "dead"
    s.alive, s.sun_turns = True, rules.seasons.year_days * (0.85 - rules.seasons.start)  # winter
    s.sun_angle, s.sun_meter = 0.6, 0.9
    assert world.status() == "winter"
    s.sun_turns = 0.0
    s.sun_cycle.rate = s.water_cycle.rate = 0.0
    s.sun_cycle.above = rules.growth.hold_time - 5.0
    assert world.status() == "starting" and world.sim.settle_left() == pytest.approx(rules.growth.hold_time)
    s.water_cycle.above = rules.growth.hold_time - 7.0
    assert world.sim.settle_left() == pytest.approx(7.0)  # the HUD's wait counts down


def test_r_asks_once_and_restore_brings_a_replaced_tree_back(gl_ctx, tmp_path):
    """R on a grown tree, confirm, autosaves, quit, restart, Settings -> Restore: the old tree is back."""
    from arbor.engine.life.keep.generations import generations
    from arbor.engine.life.world.actions import Action
    from arbor.game.screens.game import Game, GameConfig
    from tests.conftest import FakeClock

    clock = FakeClock()
    make = lambda: Game(gl_ctx, (640, 360), GameConfig(saves=tmp_path, seed=5), clock=clock,  # noqa: E731
                        wall_clock=lambda: 1.7e9 + clock.t)
    game = make()
    game.world.sim.state.length_time = 77.0  # the tree worth keeping (its clock is saved)
    game.save()
    game.act(Action.REPLANT, 1.0)
    assert game.world.sim.state.length_time == 77.0  # one key asked, destroyed nothing
    game.act(Action.REPLANT, 1.0)
    assert game.world.sim.state.length_time < 77.0
    for _ in range(4):  # four autosaves later (4 minutes) the tree is the 5th generation back
        clock.t += 61.0
        game.world.sim.state.time += 1.0
        game.save()
    assert len(generations(game.keeper.autosave_path)) == 4
    game.quit()
    assert len(generations(game.keeper.autosave_path)) == 5  # the tree is now the oldest kept
    game = make()
    assert game.world.sim.state.length_time < 77.0
    for _ in range(6):  # (the first press shows the kept autosaves, each next one brings one back)
        game.act(Action.RESTORE, 1.0)
        if game.world.sim.state.length_time >= 77.0:
            break
    assert game.world.sim.state.length_time >= 77.0, "restore did not bring the tree back"


def test_a_first_start_at_dusk_opens_in_daylight(gl_ctx, tmp_path):
    """A fresh saves folder at 20:15 local time, home pace: the sun is up and the sapling comfortable."""
    import time as _time

    from arbor.game.screens.game import Game, GameConfig
    from tests.conftest import FakeClock

    now = _time.mktime((2025, 6, 1, 20, 15, 0, 0, 0, -1))
    game = Game(gl_ctx, (640, 360), GameConfig(saves=tmp_path, seed=8, pace="home"), clock=FakeClock(),
                wall_clock=lambda: now)
    sim = game.world.sim
    assert sim.sun_height() > 0.8 and sim.state.water_meter > 0.65 and game.coach.hints


def test_a_replanted_tree_reads_its_light_at_once(system, rules):
    """The sapling planted in a grown tree's place (Replant, the kiosk's next visitor) is fed by its light
    from its first steps: its clock starts again at 0, so the light reading must not wait for the old
    tree's time (it starved through a whole year, then died in its first winter)."""
    from arbor.engine.life.world.actions import Action

    world = World(system, rules, seed=2)
    for _ in range(1500):  # 150 s: the last light reading is at about 150 s of the old tree's clock
        world.step(0.1)
    world.apply(Action.REPLANT, 1.0)
    assert world.carbon.leaf_area == 0.0
    for _ in range(int(rules.light.interval / 0.1) + 2):
        world.step(0.1)
    assert world.carbon.leaf_area > 0.0 and world.carbon.last_fixed_rate + world.carbon.last_upkeep_rate > 0


def test_a_new_game_s_seedling_unfolds_its_first_leaves_within_a_minute(gl_ctx, tmp_path):
    """At the default (home) pace a new game's sapling is first drawn as its seed, and within the first
    minute it stands with its leaves at their planted size (time to the first leaf drawn, measured)."""
    from arbor.game.screens.game import Game, GameConfig
    from benchmarks.first_minute import leaf_length
    from tests.conftest import FakeClock

    clock = FakeClock()
    game = Game(gl_ctx, (640, 360), GameConfig(saves=tmp_path, seed=5, resume=False, pace="home", sprout=True),
                clock=clock)
    fbo = gl_ctx.framebuffer(color_attachments=[gl_ctx.renderbuffer((640, 360))],
                             depth_attachment=gl_ctx.depth_renderbuffer((640, 360)))
    lengths = []
    for _second in range(61):
        game.draw(fbo)
        lengths.append(leaf_length(game))
        for _ in range(10):
            clock.t += 0.1
            game.update(0.1)
    assert lengths[0] < 0.05  # a seed at first
    first = next(t for t, length in enumerate(lengths) if length > 0.05)
    assert first < 60 and lengths[60] > 0.5 and lengths[60] == pytest.approx(max(lengths))


def test_hints_show_only_while_they_apply_and_go_once_done(gl_ctx, tmp_path):
    from arbor.engine.life.world.actions import Action
    from arbor.game.screens.game import Game, GameConfig
    from tests.conftest import FakeClock

    game = Game(gl_ctx, (640, 360), GameConfig(saves=tmp_path, seed=5, resume=False, pace="home"), clock=FakeClock())
    s, hint = game.world.sim.state, lambda: game.hud_info().hint
    s.water_meter, s.sun_meter = 0.85, 0.9  # (comfortable: no care to teach yet)
    assert "Drag" in hint()
    s.water_meter = 0.6
    assert "watering can" in hint()
    s.sun_meter = 0.5
    game.act(Action.WATER, 1.0)  # the player waters: that hint is gone for good
    game.act(Action.WATER, 0.0)
    assert "sun higher" in hint()
    s.sun_meter = 0.9
    assert "Drag" in hint()  # (the sun hint waits while the sun meter is comfortable)
    s.sun_meter = 0.5
    game.act(Action.ORBIT_HEIGHT, 0.7)
    game.control.yaw += 45.0
    assert hint() == ""
    game.coach.first_run()
    s.alive = False
    assert hint() == ""  # nothing to teach over a dead tree


def test_fourteen_days_away_end_honestly_or_watered_with_the_away_setting(system):
    """Home pace, 14 days (the cap) away from a sapling: left alone it dies of thirst (the honest outcome
    stays); with the Away setting a neighbour waters it at the need line and it lives on and grows."""
    import copy

    from arbor.engine.life.keep.away import live_away

    home = load_rules("assets/rules.toml", pace="home")
    garden = Garden([World(system, home, seed=3)])
    garden.world.sim.state.water_meter = 0.9
    alone, cared = copy.deepcopy(garden), copy.deepcopy(garden)
    honest = live_away(alone, 14 * 86400.0)
    assert honest.died and honest.thirsty and honest.waterings == 0 and not alone.world.sim.state.alive
    watered = live_away(cared, 14 * 86400.0, watered=True)
    s = cared.world.sim.state
    assert s.alive and not watered.died and not watered.thirsty and watered.waterings >= 14
    assert watered.grown > honest.grown and s.water_meter > home.growth.threshold


@pytest.mark.parametrize("away", [False, True])
def test_settings_away_is_kept_and_waters_the_garden_for_fourteen_days(gl_ctx, tmp_path, away):
    """Home pace: Settings -> Away (or not), quit, come back 14 days later: with it the tree lived on,
    watered, and the setting is still on; without it the honest outcome (a dead tree) stays."""
    from arbor.engine.life.world.actions import Action
    from arbor.game.screens.game import Game, GameConfig
    from tests.conftest import FakeClock

    now = 1.75e9
    make = lambda when: Game(gl_ctx, (640, 360), GameConfig(saves=tmp_path, seed=3, pace="home"),  # noqa: E731
                             clock=FakeClock(), wall_clock=lambda: when)
    game = make(now - 14 * 86400)
    game.world.sim.state.water_meter = 0.9
    if away:
        game.act(Action.AWAY, 1.0)
        assert game.menu.widget("away").label == "Away: on"
    game.quit()
    kept = tmp_path / "settings.toml"
    assert (kept.exists() and "away = true" in kept.read_text()) == away
    again = make(now)
    message = again.hud_info().message
    assert again.sound.prefs.away == away and again.world.sim.state.alive == away
    assert ("watered" in message and "died" not in message) if away else "died" in message
