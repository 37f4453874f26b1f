"""Issue 47: fast-forward with the gardener (Settings -> Gardener): water and light kept in the healthy band
while time flies, stops only for what a player must decide; without it the guardian stops as before."""

import math

from arbor.engine.life.world.actions import Action
from arbor.game.screens.config import read_preferences
from arbor.game.screens.game import Game, GameConfig
from tests.conftest import FakeClock

FRAME = 0.25  # real seconds a frame (the loop's clamp)


def _fly(gl_ctx, saves, gardener: bool, days: float):
    """The real game (demo pace, a garden of two) at 100x for ``days`` days of the sun, the player pressing
    only "go on" at each stop. Returns the stops (what), the most wilt and whether all trees live."""
    clock = FakeClock(0.0)
    game = Game(gl_ctx, (640, 360), GameConfig(saves=saves, seed=11, pace="demo"), clock=clock,
                wall_clock=lambda: 1.7e9 + clock.t)
    game.loop.max_steps = 1000
    if gardener:
        game.act(Action.GARDENER, 1.0)
    game.act(Action.PLANT, 1.0)
    stops, wilt = [], 0.0
    game.state.on_halt.append(lambda: stops.append(game.state.halted.what))
    game.set_speed(100.0)
    day = 2 * math.pi / game.world.sim.state.sun_speed
    while game.world.sim.state.time < days * day:
        clock.t += FRAME
        game.update(FRAME)
        wilt = max([wilt] + [w.sim.state.wilt for w in game.garden.worlds])
        if game.state.halted is not None:
            game.act(Action.GO_ON, 1.0)
    return game, stops, wilt


def test_thirty_days_at_100x_with_the_gardener_stop_only_to_decide(gl_ctx, tmp_path):
    """30 game days at 100x with the gardener: at most 5 stops, each a decision, and no wilt (the guardian
    alone stopped 161 times in 30 days for needs, issue 47)."""
    game, stops, wilt = _fly(gl_ctx, tmp_path, gardener=True, days=30)
    assert len(stops) <= 5 and set(stops) <= {"season", "fruit"}, stops
    assert "season" in stops  # (30 days cross a season's first day: the player is told)
    assert wilt < 0.05 and all(w.sim.state.alive for w in game.garden.worlds), wilt
    assert read_preferences(tmp_path / "settings.toml").gardener or game.sound.prefs.gardener


def test_without_the_gardener_the_guardian_stops_for_needs(gl_ctx, tmp_path):
    """Gardener off (the default): the guardian stops time for the trees' needs, as before."""
    game, stops, _ = _fly(gl_ctx, tmp_path, gardener=False, days=3)
    assert not game.sound.prefs.gardener
    assert stops and set(stops) <= {"water", "sun", "drown", "wilt"}, stops


def test_the_gardener_setting_is_kept(gl_ctx, tmp_path):
    """Settings -> Gardener toggles, says so, shows on its button and is written to settings.toml."""
    game = Game(gl_ctx, (640, 360), GameConfig(saves=tmp_path, seed=2, resume=False), clock=FakeClock())
    game.act(Action.GARDENER, 1.0)
    assert game.sound.prefs.gardener and game.menu.widget("gardener").label == "Gardener: on"
    assert "Gardener on" in game.state.shown_message()
    game.quit()
    assert read_preferences(tmp_path / "settings.toml").gardener
