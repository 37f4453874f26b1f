"""The player's volume and mute (issue 29): Settings -> Volume and Mute set the mixer's channels and are
kept in the saves folder's settings.toml; a kiosk plays at kiosk.toml's volume. By state, through
pygame's mixer on SDL's dummy driver."""

import os
import time

import pygame
import pytest

os.environ.setdefault("SDL_AUDIODRIVER", "dummy")

from arbor.engine.base.errors import LSysError
from arbor.engine.life.world.actions import Action
from arbor.game.audio.sounds import FADE_MS, Soundscape
from arbor.game.screens.config import PREFERENCES, SAVE_AFTER
from arbor.game.screens.game import Game, GameConfig
from arbor.game.screens.kiosk import Kiosk, KioskConfig, load_kiosk_config
from tests.conftest import FakeClock

SIZE = (1280, 720)


def new_game(ctx, folder, clock=None):
    clock = clock or FakeClock()
    game = Game(ctx, SIZE, GameConfig(saves=folder, seed=4), clock=clock, wall_clock=lambda: 1.7e9 + clock.t)
    game.fake_clock = clock
    return game


def press(game, name, x=None):
    """Press (and let go of) widget ``name`` on the Settings page, at ``x`` along a slider."""
    widget = game.menu.reveal(name)
    at = (widget.rect.centerx if x is None else widget.rect.left + 10 + x * (widget.rect.width - 20),
          widget.rect.centery)
    for action, value in game.menu.press(*at) + game.menu.release():
        game.act(action, value)


def pour_volume(game):
    """How loud the watering can pours (its mixer channel's volume; 0 once a muted pour has faded out)."""
    audio = game.audio
    audio.hear(Soundscape(watering=True), 1 / 60)
    assert audio.mixer is not None, "pygame's mixer starts on the dummy driver"
    if audio.levels["pour"] == 0.0:
        time.sleep(3 * FADE_MS / 1000)
        return float(audio.playing("pour"))
    return audio.channels["pour"].get_volume()


def test_the_volume_slider_and_mute_set_the_mixer_and_are_kept_for_the_next_start(gl_ctx, tmp_path):
    game = new_game(gl_ctx, tmp_path)
    game.menu.reveal("volume")
    assert {"volume", "mute"} <= {w.name for w in game.menu.shown()} and game.menu.page == "settings"
    loud = pour_volume(game)
    press(game, "volume", 0.25)
    assert game.audio.volume == pytest.approx(0.25, abs=0.02)
    quiet = pour_volume(game)
    assert 0.0 < quiet < loud * 0.6
    press(game, "mute")
    assert game.audio.muted and pour_volume(game) == 0.0 and game.menu.widget("mute").label == "Sound on"
    assert not (tmp_path / PREFERENCES).exists()  # (written once the change has settled)
    game.fake_clock.t += SAVE_AFTER + 0.1
    game.update(1 / 60)
    saved = (tmp_path / PREFERENCES).read_text()
    assert "volume = 0.25" in saved and "muted = true" in saved
    again = new_game(gl_ctx, tmp_path)
    assert again.audio.muted and again.audio.volume == pytest.approx(0.25, abs=0.02)
    assert pour_volume(again) == 0.0
    press(again, "mute")  # sound back on, at the volume it had
    assert pour_volume(again) == pytest.approx(quiet, abs=0.02)
    again.quit()  # a change not yet written is written on the way out
    assert "muted = false" in (tmp_path / PREFERENCES).read_text()


def test_a_broken_settings_file_is_one_line_and_the_defaults(gl_ctx, tmp_path):
    (tmp_path / PREFERENCES).write_text("volume = 3\nmuted = false\n")
    game = new_game(gl_ctx, tmp_path)
    message = game.state.message
    assert f"{PREFERENCES}:1:1: volume must be from 0 to 1" in message and "\n" not in message
    assert game.audio.volume == pytest.approx(0.7) and not game.audio.muted
    (tmp_path / PREFERENCES).write_text("loudness = 0.5\n")
    assert "unknown setting 'loudness'" in new_game(gl_ctx, tmp_path).state.message
    assert not (tmp_path / PREFERENCES).exists()  # (set aside: the player's file is kept, not read again)
    assert (tmp_path / f"{PREFERENCES}.2.broken").read_text() == "loudness = 0.5\n"
    os.mkfifo(tmp_path / PREFERENCES)  # (a FIFO must not block the start)
    assert "not a regular file" in new_game(gl_ctx, tmp_path).state.message


def test_the_kiosk_plays_at_its_own_volume_for_every_visitor(gl_ctx, tmp_path):
    clock = FakeClock(50.0)
    folder = tmp_path / "kiosk"
    kiosk = Kiosk(lambda: new_game(gl_ctx, folder, clock), KioskConfig(volume=0.3, reset_after=30.0), folder, clock)
    assert kiosk.game.audio.volume == pytest.approx(0.3) and kiosk.game.menu.widget("volume").value == 0.3
    kiosk.game.act(Action.MUTE, 1.0)  # a visitor mutes it
    assert kiosk.game.audio.master == 0.0
    clock.t += 31.0
    kiosk.update(0.0)  # the visitor is gone: the next one hears it again
    assert kiosk.visitor_saved and kiosk.game.audio.master == pytest.approx(0.3)


def test_the_kiosk_volume_is_range_checked_in_one_line(tmp_path):
    assert 0.0 <= load_kiosk_config("assets/kiosk.toml").volume <= 1.0
    bad = tmp_path / "kiosk.toml"
    bad.write_text('pin = "2468"\nvolume = 1.5\n')
    with pytest.raises(LSysError) as err:
        load_kiosk_config(bad)
    assert str(err.value) == f"{bad}:2:1: volume must be from 0 to 1 (0 silent, 1 loudest), not 1.5"
    bad.write_text('volume = "loud"\n')
    with pytest.raises(LSysError, match="must be a number"):
        load_kiosk_config(bad)


def test_settings_page_draws_the_volume_slider_and_mute_button(gl_ctx, tmp_path):
    game = new_game(gl_ctx, tmp_path)
    press(game, "volume", 0.8)
    game.menu.reveal("mute")
    surface = pygame.Surface(SIZE, pygame.SRCALPHA)
    game.menu.draw(surface, game.font)
    slider = game.menu.widget("volume").rect
    knob_x = int(slider.left + 10 + 0.8 * (slider.width - 20))
    assert surface.get_at((knob_x, slider.bottom - 16))[:3] == (250, 204, 40)  # the knob where it was let go
