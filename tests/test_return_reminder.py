"""A gentle reminder at every return (issue 47): the line at a normal start says when the tree will next
want water (now, in about how long, or not for days), from the simulation run ahead on a copy."""

import copy

from arbor.engine.life.world.status import need_line, water_due
from tests.test_game_life import NOW, new_game


def test_a_return_says_when_the_tree_will_want_water(gl_ctx, tmp_path):
    game = new_game(gl_ctx, tmp_path, pace="home")
    game.world.sim.state.water_meter = 0.9
    game.quit()
    back = new_game(gl_ctx, tmp_path, pace="home", now=NOW + 2 * 3600.0)  # two hours later
    assert "will want water in about" in back.keeper.start_message, back.keeper.start_message
    world = back.world
    due = water_due(world)
    ahead = copy.deepcopy(world.sim)
    for _ in range(180):
        ahead.step(due / 200)
    assert ahead.state.water_meter > need_line(world.rules)  # not before ...
    for _ in range(40):
        ahead.step(due / 200)
    assert ahead.state.water_meter <= need_line(world.rules)  # ... but by then (the estimate holds)


def test_a_thirsty_tree_at_a_return_asks_for_water_now(gl_ctx, tmp_path):
    game = new_game(gl_ctx, tmp_path, pace="home")
    game.world.sim.state.water_meter = 0.3
    game.quit()
    back = new_game(gl_ctx, tmp_path, pace="home", now=NOW + 600.0)
    assert "wants water now" in back.keeper.start_message
    assert "wants water now" in back.hud_info().message  # (said on the screen too)
