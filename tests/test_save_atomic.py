"""A save is replaced whole or not at all: crashes injected at fixed points of the write, not by timing.

Each test saves a garden, then crashes a second save at one point of engine/base/files.py's
write (half-way through writing the new bytes; after they are written but before the rename) and
checks what a player would find on restarting: the old save, byte for byte, still loading as the old
garden, and no temp file left beside it. The kill test in test_save.py does the same with real
SIGKILLs, but where those land depends on timing.
"""

from __future__ import annotations

import pytest

from arbor.engine.base import files
from arbor.engine.life.keep.save import SavedGarden, read_garden, write_garden
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import load_lsystem


class Crash(BaseException):
    """The process dying at the injected point (a BaseException: no ``except Exception`` catches it)."""


@pytest.fixture(scope="module")
def gardens(lsys_dir) -> tuple[SavedGarden, SavedGarden]:
    """An old garden already on disk and a different new one being saved over it."""
    system, rules = load_lsystem(lsys_dir / "game_tree.lsys"), load_rules("assets/rules.toml", pace="demo")
    old = World(system, rules, seed=1)
    new = World(system, rules, seed=2)
    for _ in range(200):
        new.step(0.5)
    assert not new.tree.lstring.equals(old.tree.lstring)
    return SavedGarden([old], saved_at=1.0), SavedGarden([new, World(system, rules, seed=3)], saved_at=2.0)


def _old_save_survived(path, before: bytes, old: SavedGarden) -> None:
    """What a restarted game finds: the old file unchanged, loading as the old garden, no temp files."""
    assert path.read_bytes() == before
    back = read_garden(path, old.world.rules)
    assert len(back.worlds) == 1 and back.saved_at == 1.0
    assert back.world.tree.lstring.equals(old.world.tree.lstring)
    assert [p.name for p in path.parent.iterdir()] == [path.name]


def test_crash_between_writing_and_renaming_keeps_the_old_save(gardens, tmp_path, monkeypatch):
    old, new = gardens
    path = tmp_path / "autosave.arbor"
    write_garden(old, path)
    before = path.read_bytes()

    def crash(*_args, **_kwargs):
        raise Crash

    monkeypatch.setattr(files.os, "replace", crash)
    with pytest.raises(Crash):
        write_garden(new, path)
    _old_save_survived(path, before, old)
    monkeypatch.undo()
    write_garden(new, path)  # the next save goes through whole
    assert len(read_garden(path, old.world.rules).worlds) == 2
    assert [p.name for p in tmp_path.iterdir()] == [path.name]


class _HalfWriter:
    """A file that dies half-way through the first write given to it (what was written reaches disk)."""

    def __init__(self, fh) -> None:
        self.fh = fh

    def __enter__(self) -> _HalfWriter:
        return self

    def __exit__(self, *exc) -> None:
        self.fh.close()

    def write(self, data: bytes) -> int:
        self.fh.write(data[: len(data) // 2])
        self.fh.flush()
        raise Crash

    def __getattr__(self, name: str):
        return getattr(self.fh, name)


def test_crash_half_way_through_writing_keeps_the_old_save(gardens, tmp_path, monkeypatch):
    old, new = gardens
    path = tmp_path / "autosave.arbor"
    write_garden(old, path)
    before = path.read_bytes()
    opened = []

    def half_open(file, mode="r", *args, **kwargs):
        opened.append(file)
        return _HalfWriter(open(file, mode, *args, **kwargs))

    monkeypatch.setattr(files, "open", half_open, raising=False)
    with pytest.raises(Crash):
        write_garden(new, path)
    assert opened  # the crash happened inside the write, where it was meant to
    _old_save_survived(path, before, old)
