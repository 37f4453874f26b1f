"""The saves folder as a hostile operating system leaves it (issue 33): links and FIFOs are neither read
nor written through; a full disk keeps the last good save, says so on the HUD and the game goes on."""

import errno
import os

import pytest

from arbor.engine.base import files
from arbor.engine.base.files import atomic_write
from arbor.engine.life.keep.save import read_garden
from arbor.engine.life.keep.save_check import SaveError
from arbor.game.screens.game import Game, GameConfig
from tests.conftest import FakeClock

SIZE = (1280, 720)


def test_a_symlinked_autosave_is_neither_read_nor_written_through(gl_ctx, tmp_path):
    outside = tmp_path / "outside.txt"
    outside.write_text("precious")
    saves = tmp_path / "saves"
    saves.mkdir()
    (saves / "autosave.arbor").symlink_to(outside)
    with pytest.raises(SaveError) as info:
        read_garden(saves / "autosave.arbor")
    assert "it is a link" in info.value.message  # refused as a link, not read as a bad save
    clock = FakeClock()
    game = Game(gl_ctx, SIZE, GameConfig(saves=saves, seed=1), clock=clock, wall_clock=lambda: 1.7e9)
    assert "Could not load autosave.arbor" in game.hud_info().message
    game.quit()
    assert outside.read_text() == "precious"
    assert not (saves / "autosave.arbor").is_symlink() and read_garden(saves / "autosave.arbor").worlds


def test_a_link_planted_at_the_temp_name_is_not_written_through(tmp_path):
    outside = tmp_path / "outside.txt"
    outside.write_text("precious")
    (tmp_path / f".autosave.arbor.{os.getpid()}.tmp").symlink_to(outside)
    atomic_write(tmp_path / "autosave.arbor", b"new")
    assert outside.read_text() == "precious" and (tmp_path / "autosave.arbor").read_bytes() == b"new"


def test_a_fifo_save_is_refused_without_blocking(tmp_path):
    os.mkfifo(tmp_path / "autosave.arbor")
    with pytest.raises(SaveError) as info:
        read_garden(tmp_path / "autosave.arbor")
    assert "not a regular file" in info.value.message


def test_a_full_disk_keeps_the_last_good_save_and_the_game_goes_on(gl_ctx, tmp_path, monkeypatch):
    clock = FakeClock()
    game = Game(gl_ctx, SIZE, GameConfig(saves=tmp_path, seed=1), clock=clock, wall_clock=lambda: 1.7e9)
    game.quit()
    good = (tmp_path / "autosave.arbor").read_bytes()

    def full(fd, data):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(files.os, "fsync", lambda fd: full(fd, b""))
    game.world.sim.state.time += 100.0
    assert not game.keeper.save()
    assert "No space left on device" in game.hud_info().message
    assert (tmp_path / "autosave.arbor").read_bytes() == good
    assert not [p for p in tmp_path.iterdir() if p.name.endswith(".tmp")]
    for _ in range(20):
        game.update(0.1)  # the game goes on
    monkeypatch.undo()
    assert game.keeper.save()  # and saves once there is room again
