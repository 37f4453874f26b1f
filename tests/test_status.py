"""Issue 47: what the HUD says comes from one ranking of the real state (engine/life/world/status.py), in the
game and in the kiosk. Each row scripts a state of the real Game's tree and reads the HUD it shows."""

import math

import pytest

from arbor.engine.life.plant import seasons
from arbor.engine.life.world.guardian import Need
from arbor.engine.life.world.status import need_line
from arbor.engine.lsystem.lstring import parse_lstring
from arbor.game.screens.game import Game, GameConfig
from arbor.game.strings import set_language, text
from tests.conftest import FakeClock

SIZE = (640, 360)


@pytest.fixture
def game(gl_ctx, tmp_path):
    set_language("en")
    g = Game(gl_ctx, SIZE, GameConfig(saves=tmp_path, seed=3, resume=False), clock=FakeClock())
    s = g.world.sim.state
    s.sun_meter, s.water_meter, s.sun_angle = 0.85, 0.85, math.pi / 2  # noon, both meters comfortable
    s.sun_cycle.rate = s.water_cycle.rate = 1.0  # growth earned
    g.world.tree.mean_light = g.world.tree.geometry_constants["SHQ"] + 0.1  # (leaves in good light)
    return g


def winter_blend(g):
    """Late winter, while its growth already blends into spring's (the tree is still bare)."""
    r = g.rules.seasons
    g.world.sim.state.sun_turns = r.year_days * ((3.97 / 4 - r.start) % 1.0)
    assert g.world.sim.season().name == "winter"
    assert seasons.growth_factor(g.world.sim.state.sun_turns, g.rules) > 0  # (the case that said "growing")


def bare_autumn(g):
    """Late autumn: the leaves have fallen (the tree is drawn bare) though the season is not winter yet."""
    r = g.rules.seasons
    g.world.sim.state.sun_turns = r.year_days * ((2.97 / 4 - r.start) % 1.0)
    assert g.world.sim.season().name == "autumn" and seasons.leaf_keep(g.world.sim.state.sun_turns, g.rules) < 0.05


def night(g, speed=1.0):
    g.world.sim.state.sun_angle = -math.pi / 2  # midnight
    g.loop.speed = speed


def dead_with_fruit(g):
    g.world.sim.state.alive = False
    g.world.tree.lstring = parse_lstring("F(1)[+F(0.5)O(0)]O(0)")


def dead(g):
    g.world.sim.state.alive = False


def water(level):
    def set_water(g):
        g.world.sim.state.water_meter = level(g.rules)
    return set_water


def sun(level):
    def set_sun(g):
        g.world.sim.state.sun_meter = level(g.rules)
    return set_sun


ROWS = [  # (what, scripted state, the status's key, the hint shown)
    ("day, comfortable", lambda g: None, "growing", False),
    ("late winter rests", winter_blend, "winter", False),
    ("a bare tree in late autumn rests", bare_autumn, "winter", False),
    ("night under the dark sky of 1x", night, "resting", False),
    ("night of the sim drawn as day at 100x", lambda g: night(g, 100.0), "growing", False),
    ("dead", dead, "dead", False),
    ("dead with fruit says so", dead_with_fruit, "dead_fruit", False),
    ("water between comfortable and the need line: no hint", water(lambda r: need_line(r) + 0.05), "growing", False),
    ("water down to the need line: the can's hint", water(lambda r: need_line(r) - 0.01), "growing", True),
    ("water at the threshold: thirsty", water(lambda r: r.growth.threshold - 0.01), "thirsty", True),
    ("sun between comfortable and the need line: no hint", sun(lambda r: need_line(r) + 0.05), "growing", False),
    ("sun down to the need line: the sun's hint", sun(lambda r: need_line(r) - 0.01), "growing", "sun"),
]


@pytest.mark.parametrize("what, script, key, hint", ROWS, ids=[r[0] for r in ROWS])
def test_the_hud_says_what_the_state_is(game, what, script, key, hint):
    game.coach.first_run()  # (a new player: every hint still to learn)
    script(game)
    info = game.hud.hud_info()
    expected = text(f"status.{key}", hold="", fruit=2)
    assert info.status == expected, (what, info.status)
    if hint:
        assert info.hint == text("hints.sun" if hint == "sun" else "hints.water"), (what, info.hint)
    else:
        assert info.hint not in (text("hints.water"), text("hints.sun")), (what, info.hint)
    if key == "dead_fruit":
        assert "2 fruit" in info.status


def test_no_thirst_warning_above_the_need_line(game):
    """The guardian's stop line stands while its tree is under the need line, and goes once the tree is
    watered past it (or the stop is answered by a speed chosen by hand)."""
    s = game.world.sim.state
    s.water_meter = need_line(game.rules) - 0.02
    game.loop.speed = 100.0
    game.state.halt(Need(0, "water"))
    assert "thirsty" in game.hud.hud_info().message
    s.water_meter = need_line(game.rules) + 0.02  # the player poured a little: above the line
    assert game.hud.hud_info().message == ""
    s.water_meter = need_line(game.rules) - 0.02
    assert "thirsty" in game.hud.hud_info().message
    game.care.set_speed(10.0)
    assert game.hud.hud_info().message == ""


def test_the_kiosk_says_the_same(gl_ctx, tmp_path):
    """The kiosk plays the game's HUD: late winter rests there too, the can's hint waits for low water,
    and no thirst warning stands beside a tree watered past the need line at 1x."""
    from arbor.game.screens.kiosk import Kiosk, load_kiosk_config

    set_language("en")
    clock = FakeClock(100.0)
    kiosk = Kiosk(lambda: Game(gl_ctx, SIZE, GameConfig(saves=tmp_path, seed=4, resume=False, pace="demo"),
                               clock=clock), load_kiosk_config("assets/kiosk.toml"), tmp_path, clock=clock)
    g = kiosk.game
    s = g.world.sim.state
    s.sun_meter, s.water_meter, s.sun_angle = 0.85, need_line(g.rules) + 0.05, math.pi / 2
    s.sun_cycle.rate = s.water_cycle.rate = 1.0
    g.coach.first_run()
    winter_blend(g)
    info = g.hud.hud_info()
    assert info.status == text("status.winter") and info.hint != text("hints.water")
    s.water_meter = need_line(g.rules) - 0.02
    g.loop.speed = 10.0
    g.state.halt(Need(0, "water"))
    assert "thirsty" in g.hud.hud_info().message and g.hud.hud_info().hint == text("hints.water")
    s.water_meter = need_line(g.rules) + 0.05  # the visitor watered it
    info = g.hud.hud_info()
    assert g.loop.speed == 1.0 and info.message == "" and info.status == text("status.winter")
