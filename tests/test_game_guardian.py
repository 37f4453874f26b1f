"""The fast-forward guardian through the real game, headless, with the autopilot OFF (issue 42): at 10x and
at 100x a tree coming near its need line stops time at 1x, says which tree needs what, and G goes on.
(Every other fast-forward test tends the garden first; these are the ones that fail when the guardian
stops only above 100x, or never.)"""

import pygame
import pytest

from arbor.game.screens.game import Game, GameConfig
from arbor.game.strings import text
from tests.conftest import FakeClock

SIZE = (640, 360)
SPEED_KEYS = {1.0: pygame.K_1, 10.0: pygame.K_2, 100.0: pygame.K_3}


def key(game: Game, k: int) -> None:
    """Press and let go of key ``k`` through the game's input path."""
    for kind in (pygame.KEYDOWN, pygame.KEYUP):
        game.handle_event(pygame.event.Event(kind, key=k, mod=0, unicode="", scancode=0))


def thirsty_game(ctx, tmp_path) -> Game:
    """A game whose tree is comfortable in sun but a little above the guardian's water line (read from
    the rules), so a thirst comes within a few game seconds."""
    clock = FakeClock()
    game = Game(ctx, SIZE, GameConfig(saves=tmp_path, seed=4, resume=False), clock=clock,
                wall_clock=lambda: 1.7e9 + clock.t)
    game.fake_clock = clock
    rules, s = game.rules, game.world.sim.state
    assert not game.state.autopilot
    s.sun_meter = min(rules.health.comfort + 0.05, 1.0)
    s.water_meter = rules.growth.threshold + rules.health.guard_margin + 0.03
    return game


def run(game: Game, real_seconds: float) -> None:
    """``real_seconds`` of 60 fps frames (the fake clock follows), stopping early at a guardian's stop."""
    for _ in range(int(real_seconds * 60)):
        game.fake_clock.t += 1 / 60
        game.update(1 / 60)
        if game.state.halted is not None:
            return


@pytest.mark.parametrize("speed", [10.0, 100.0])
def test_the_guardian_stops_fast_forward_for_a_thirst_with_the_autopilot_off(gl_ctx, tmp_path, speed):
    game = thirsty_game(gl_ctx, tmp_path)
    rules = game.rules
    key(game, SPEED_KEYS[speed])
    assert game.loop.speed == speed
    run(game, 3000 / speed)  # at most 3000 game seconds: the thirst comes long before
    need = game.state.halted
    assert need is not None, f"the guardian never stopped {speed:g}x"
    s = game.world.sim.state
    assert need.what == "water" and need.index == 0
    assert game.loop.speed == 1.0 and game.state.resume_speed == speed
    assert s.alive and s.water_meter > rules.growth.threshold  # stopped before the need line, not after
    message = game.hud_info().message
    assert "Tree 1" in message and f"{speed:g}x" in message
    assert game.menu.widget("speed").label == text("menu.go_on", speed=f"{speed:g}")  # the speed button
    key(game, pygame.K_g)  # go on: the can pours and time flies on at the speed it had
    assert game.state.halted is None and game.loop.speed == speed and s.watering


def test_at_1x_the_guardian_leaves_the_speed_alone(gl_ctx, tmp_path):
    game = thirsty_game(gl_ctx, tmp_path)
    watch = game.state.guardian.watch
    asked = []
    game.state.guardian.watch = lambda garden: asked.append(1) or watch(garden)
    run(game, 2.0)  # 20 steps at 1x: the guardian is not asked, nothing stops
    assert game.state.halted is None and game.loop.speed == 1.0 and not asked
