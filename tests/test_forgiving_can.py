"""A forgiving can (issue 47): 20 s of held water on a new seedling at the home pace and on the kiosk (10x)
do no harm: the can stops at the top of the soil by itself and says why (and pours again once the meter
falls below comfortable), the meter never passes the drowning line, the roots never start to drown,
nothing wilts and the guardian has nothing to stop for. A new hold on a full soil pours on in the game
(too much water is the player's choice), never on the kiosk."""

import pytest

from arbor.engine.life.world.actions import Action
from arbor.game.screens.game import Game, GameConfig
from arbor.game.screens.kiosk import Kiosk, load_kiosk_config
from tests.conftest import FakeClock
from tests.test_game_life import new_game

FRAME = 0.25  # real seconds a frame
SIZE = (1280, 720)


def hold(game, seconds: float, update) -> list[str]:
    """Hold the can for ``seconds`` of real time, frame by frame; returns every status word and message
    seen."""
    seen = []
    game.act(Action.WATER, 1.0)
    for _ in range(round(seconds / FRAME)):
        update(FRAME)
        seen += [game.world.status(), game.state.shown_message()]
    game.act(Action.WATER, 0.0)
    return seen


def harmless(game, seen: list[str]) -> None:
    """What 'no harm' means: never 'too much water', the roots not drowning, no wilt, no stop."""
    s = game.world.sim.state
    assert "drowning" not in seen and s.drowning == 0.0 and s.wilt == 0.0 and s.alive
    assert game.rules.health.comfort - 0.02 <= s.water_meter <= game.rules.water.drown_level
    assert game.state.halted is None
    assert any("soil is full" in line for line in seen)


def test_twenty_seconds_of_water_on_a_home_seedling_do_no_harm(gl_ctx, tmp_path):
    game = new_game(gl_ctx, tmp_path, pace="home")
    game.world.sim.state.water_meter = 0.6

    def update(dt):
        game.update(dt)
        game.fake_clock.t += dt

    seen = hold(game, 20.0, update)
    harmless(game, seen)
    game.world.sim.state.water_meter = game.state.can_top()  # (still full when the can is held again)
    seen = hold(game, 2.0, update)  # a new hold on a full soil pours on: the player's choice
    assert "drowning" in seen


@pytest.fixture
def kiosk(gl_ctx, tmp_path):
    """The kiosk with kiosk.toml's speed (10x) and pace (demo) on a fake clock."""
    clock = FakeClock(100.0)
    config = load_kiosk_config("assets/kiosk.toml")
    kiosk = Kiosk(lambda: Game(gl_ctx, SIZE, GameConfig(saves=tmp_path, seed=4, resume=False, pace="demo"),
                               clock=clock), config, tmp_path, clock=clock)
    kiosk.fake = clock
    return kiosk


def test_twenty_seconds_of_water_on_the_kiosk_do_no_harm(kiosk):
    game = kiosk.game
    assert game.loop.speed == 10.0  # (the kiosk's speed: the can pours 1.2 of the meter a real second)
    game.world.sim.state.water_meter = 0.6
    game.world.rules.weather.rain_fill = 0.0  # (the can alone: 40 s at 10x are 3 days, a shower floods a full soil)

    def update(dt):
        kiosk.fake.t += dt
        kiosk.update(dt)

    harmless(game, hold(game, 20.0, update))
    harmless(game, hold(game, 20.0, update))  # (and again: on the kiosk a full soil never takes more)
