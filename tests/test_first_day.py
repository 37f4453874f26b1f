"""A new garden's first day at the home pace (issue 47): it runs the pace's first_day_speed times as fast
while the player watches, so a first session sees its tree grow within ten minutes, and says so; the can
still fills per real second; the first day ends and says that too; the demo pace has none."""

import pytest

from arbor.engine.base.units import METRE
from arbor.engine.life.rules.rules import first_day, load_rules
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.status import water_low
from tests.test_game_life import ASSETS, new_game

FRAME = 0.25  # real seconds a frame


def play(game, seconds: float) -> None:
    """Play ``seconds`` of real time as a new player does: the can held while the HUD says the water is low,
    let go once the meter is comfortable."""
    for _ in range(round(seconds / FRAME)):
        s = game.world.sim.state
        if water_low(game.world):
            game.act(Action.WATER, 1.0)
        elif s.watering and s.water_meter >= game.rules.health.comfort:
            game.act(Action.WATER, 0.0)
        game.update(FRAME)
        game.fake_clock.t += FRAME


def test_the_home_pace_lives_a_new_gardens_first_day_in_ten_minutes():
    home, demo = load_rules(ASSETS / "rules.toml", "home"), load_rules(ASSETS / "rules.toml", "demo")
    assert home.first_day_speed == 144.0 and demo.first_day_speed == 1.0
    assert first_day(home) / home.first_day_speed == pytest.approx(600.0, rel=0.01)  # 10 real minutes at 1x


def test_a_new_tree_at_the_home_pace_grows_within_its_first_ten_minutes(gl_ctx, tmp_path):
    game = new_game(gl_ctx, tmp_path, pace="home")
    assert game.state.first_day_factor() == 144.0
    play(game, 60.0)  # (the sapling's height is measured at its first light reading)
    height = game.world.tree.height / METRE
    assert "first day 144x" in game.hud_info().speed_note
    play(game, 540.0)
    assert game.world.sim.state.alive and game.world.tree.height / METRE > 1.2 * height
    assert game.world.sim.state.time > 20 * 3600.0  # most of a day of the sun lived in ten minutes


def test_the_can_fills_per_real_second_in_the_fast_first_day(gl_ctx, tmp_path):
    game = new_game(gl_ctx, tmp_path, pace="home")
    s = game.world.sim.state
    s.water_meter, before = 0.4, 0.4
    game.act(Action.WATER, 1.0)
    assert game.state.first_day_factor() == 1.0  # (time runs at the loop's speed while the can pours)
    game.update(0.25)
    game.update(0.25)
    game.update(0.25)
    game.update(0.25)
    assert s.water_meter - before == pytest.approx(game.rules.water.fill_rate * 1.0, abs=0.01)
    game.act(Action.WATER, 0.0)
    assert game.state.first_day_factor() == 144.0


def test_the_first_day_ends_and_says_so(gl_ctx, tmp_path):
    game = new_game(gl_ctx, tmp_path, pace="home")
    game.world.sim.state.time = first_day(game.rules) - 20.0  # (a step is 14.4 s of it)
    game.update(0.25)
    game.fake_clock.t += 0.25
    assert game.state.first_day_factor() == 1.0 and game.hud_info().speed_note == ""
    assert "first day is over" in game.hud_info().message
    before = game.world.sim.state.time
    game.update(0.25)
    assert game.world.sim.state.time - before == pytest.approx(0.2, abs=0.11)  # a day lasts a day again


def test_the_demo_pace_has_no_fast_first_day(gl_ctx, tmp_path):
    game = new_game(gl_ctx, tmp_path, pace="demo")
    assert game.state.first_day_factor() == 1.0 and game.hud_info().speed_note == ""
    before = game.world.sim.state.time
    game.update(0.25)
    assert game.world.sim.state.time - before == pytest.approx(0.2, abs=0.11)
