"""rotate() (the autosave's earlier generations) never follows a link nor waits on a FIFO planted under a
generation's name (issue 45: with autosave.1.arbor a FIFO, `arbor import` hung and the game's quit hung
past 30 s with nothing saved)."""

from __future__ import annotations

import os
import threading

from arbor.engine.life.keep.generations import generation, rotate


def _rotate_within(path, seconds: float = 5.0) -> None:
    done = threading.Event()

    def run():
        rotate(path)
        done.set()

    worker = threading.Thread(target=run, daemon=True)
    worker.start()
    if not done.wait(seconds):
        fifo = generation(path, 1).with_name("autosave.2.arbor")
        for name in (generation(path, 1), fifo):  # (unblock the stuck reader, so the test run goes on)
            if name.exists() and not name.is_file():
                with open(os.open(name, os.O_WRONLY | os.O_NONBLOCK), "wb"):
                    pass
        raise AssertionError("rotate() blocked")


def test_a_fifo_as_generation_one_does_not_block_and_the_garden_is_kept(tmp_path):
    save = tmp_path / "autosave.arbor"
    save.write_text("garden 2\n")
    os.mkfifo(generation(save, 1))
    _rotate_within(save)
    assert generation(save, 1).read_text() == "garden 2\n"
    assert not generation(save, 2).is_file()  # (the FIFO moved down the line, never read)


def test_a_link_as_the_save_or_a_generation_is_never_followed(tmp_path):
    outside = tmp_path / "outside.txt"
    outside.write_text("someone else's file\n")
    save = tmp_path / "autosave.arbor"
    save.write_text("garden\n")
    generation(save, 1).symlink_to(outside)
    _rotate_within(save)
    assert outside.read_text() == "someone else's file\n" and generation(save, 1).read_text() == "garden\n"
    assert generation(save, 2).is_symlink()
    save.unlink()
    save.symlink_to(outside)  # a link as the autosave itself: not copied into the generations
    _rotate_within(save)
    assert generation(save, 1).read_text() == "garden\n"


def test_an_unchanged_save_is_not_kept_twice(tmp_path):
    save = tmp_path / "autosave.arbor"
    save.write_text("garden\n")
    rotate(save)
    rotate(save)
    assert generation(save, 1).read_text() == "garden\n" and not generation(save, 2).exists()
