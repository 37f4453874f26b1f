"""Sound by state (issue 29): which sounds play in which state of the garden and how loud, through
pygame's mixer on SDL's dummy driver (silent, but channels really play and stop)."""

import os
import time

import numpy as np
import pytest

os.environ.setdefault("SDL_AUDIODRIVER", "dummy")

from arbor.game.audio.sounds import FADE_MS, Audio, Soundscape, loop_levels, soundscape


@pytest.fixture(scope="module")
def audio():
    a = Audio(volume=0.8)
    assert a.mixer is not None, "pygame's mixer starts on the dummy driver"
    return a


def test_watering_pours_and_the_pour_stops_when_watering_stops(audio):
    audio.hear(Soundscape(watering=True), 1 / 60)
    assert audio.playing("pour") and audio.levels["pour"] > 0.3
    assert audio.channels["pour"].get_volume() == pytest.approx(audio.levels["pour"], abs=0.01)
    audio.hear(Soundscape(watering=False), 1 / 60)
    assert audio.levels["pour"] == 0.0
    time.sleep(3 * FADE_MS / 1000)
    assert not audio.playing("pour")


def test_the_wind_is_as_loud_as_it_blows_and_still_air_is_silent():
    still, breeze, gale = (loop_levels(Soundscape(wind=w))["wind"] for w in (0.0, 0.35, 3.0))
    assert still == 0.0 and 0.0 < breeze < gale <= 1.0


def test_rain_is_heard_while_it_rains_and_crickets_only_at_night(audio):
    audio.hear(Soundscape(rain=True, daylight=1.0), 1 / 60)
    assert audio.playing("rain") and audio.levels["night"] == 0.0
    audio.hear(Soundscape(rain=False, daylight=0.0), 1 / 60)
    assert audio.levels["rain"] == 0.0 and audio.playing("night") and audio.levels["night"] > 0.2
    audio.hear(Soundscape(daylight=1.0), 1 / 60)


def test_birds_sing_by_day_and_not_at_night():
    day, night = Audio(seed=1), Audio(seed=1)
    for _ in range(60 * 60):  # a minute of frames
        day.hear(Soundscape(daylight=1.0), 1 / 60)
        night.hear(Soundscape(daylight=0.0), 1 / 60)
    assert sum(name.startswith("bird") for name in day.heard) >= 3
    assert not any(name.startswith("bird") for name in night.heard)


def test_a_new_milestone_chimes_once_and_a_loaded_journal_does_not():
    a = Audio(seed=2)
    a.hear(Soundscape(daylight=0.0, milestones=4), 1 / 60)  # a save with four milestones: nothing new
    a.hear(Soundscape(daylight=0.0, milestones=4), 1 / 60)
    assert "chime" not in a.heard
    a.hear(Soundscape(daylight=0.0, milestones=5), 1 / 60)
    a.hear(Soundscape(daylight=0.0, milestones=5), 1 / 60)
    assert a.heard.count("chime") == 1


def test_muted_nothing_plays_and_the_volume_scales_every_loop():
    a = Audio(volume=0.5)
    a.hear(Soundscape(wind=1.0, watering=True), 1 / 60)
    half = dict(a.levels)
    a.set_volume(1.0)
    a.hear(Soundscape(wind=1.0, watering=True), 1 / 60)
    assert a.levels["pour"] == pytest.approx(2 * half["pour"]) and a.levels["wind"] == pytest.approx(2 * half["wind"])
    a.set_volume(1.0, muted=True)
    a.hear(Soundscape(wind=1.0, watering=True), 1 / 60)
    time.sleep(3 * FADE_MS / 1000)
    assert all(level == 0.0 for level in a.levels.values())
    assert not a.playing("pour") and not a.playing("wind")


def test_the_soundscape_follows_the_world(lsys_dir):
    from arbor.engine.life.rules.rules import load_rules
    from arbor.engine.life.world.actions import Action
    from arbor.engine.life.world.world import World
    from arbor.engine.lsystem.lsys import load_lsystem

    world = World(load_lsystem(lsys_dir / "game_tree.lsys"), load_rules("assets/rules.toml"), seed=1)
    assert not soundscape(world, 0.35).watering
    world.apply(Action.WATER, 1.0)
    scape = soundscape(world, 0.35)
    assert scape.watering and scape.wind == 0.35 and scape.milestones == len(world.journal.entries)
    world.apply(Action.WATER, 0.0)
    assert not soundscape(world, 0.35).watering


def test_a_pressed_menu_button_clicks(gl_ctx, tmp_path):
    from arbor.game.screens.game import Game, GameConfig

    game = Game(gl_ctx, (640, 360), GameConfig(saves=tmp_path, seed=5, resume=False), clock=lambda: 100.0)
    game.update(1 / 60)
    assert "click" not in game.audio.heard
    game.tap(320, 180)  # the menu opens
    widget = next(w for w in game.menu.shown() if w.kind != "slider")
    game.menu.press(*widget.rect.center)  # (what the input layer does with a pointer down on it)
    game.update(1 / 60)
    assert game.audio.heard.count("click") == 1


def test_the_wind_heard_is_the_wind_the_trees_sway_in_and_a_shower_blows_it_harder(gl_ctx, tmp_path):
    from arbor.game.screens.game import Game, GameConfig

    game = Game(gl_ctx, (640, 360), GameConfig(saves=tmp_path, seed=5, resume=False), clock=lambda: 100.0)
    game.update(1 / 60)
    dry = game.audio.levels["wind"]
    strength = game.view.wind_strength()
    height = max(float(game.renderer.hi[1]), 1.0)
    assert np.linalg.norm(game.view.wind()) == pytest.approx(strength * 0.1 * height)  # (one number for both)
    game.world.sim.raining = lambda: True
    game.update(1 / 60)
    assert game.view.wind_strength() == pytest.approx(strength * game.rules.weather.rain_wind)
    assert game.audio.levels["wind"] > dry > 0.0 and game.audio.playing("rain")


def test_crickets_sing_at_night_but_not_under_the_noon_light_shown_when_days_fly_by(gl_ctx, tmp_path):
    from arbor.game.screens.game import Game, GameConfig

    game = Game(gl_ctx, (640, 360), GameConfig(saves=tmp_path, seed=5, resume=False), clock=lambda: 100.0)
    sim = game.world.sim
    sim.state.sun_angle = next(a for a in np.linspace(0.0, 2 * np.pi, 64) if _sun_height(sim, a) < -0.4)
    game.update(1 / 60)
    assert game.audio.levels["night"] > 0.2  # a night at 1x: dark on the screen, crickets
    game.set_speed(100.0)
    game.update(1 / 60)
    assert game.view.scene_sun()[1] > 0.3 and sim.sun_direction()[1] < 0.0  # the screen shows day light
    assert game.audio.levels["night"] == 0.0  # so no crickets


def _sun_height(sim, angle: float) -> float:
    sim.state.sun_angle = angle
    return float(sim.sun_direction()[1])
