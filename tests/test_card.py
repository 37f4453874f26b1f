"""A tree shared as a postcard: `arbor card` writes a PNG carrying the tree's save, `arbor import` plants
it in the home garden; hostile or stripped cards are refused in one line and leave the garden untouched."""

from __future__ import annotations

import dataclasses
import io
import re
import tracemalloc
import zlib

import numpy as np
import pytest

from arbor.engine.life.keep import card as card_module
from arbor.engine.life.keep.card import card_bytes, read_card
from arbor.engine.life.keep.save import SavedGarden, read_garden, write_garden
from arbor.engine.life.keep.save_check import SaveError
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import load_lsystem
from arbor.game.cli import main


@pytest.fixture(scope="module")
def saved(lsys_dir, tmp_path_factory):
    """A save of a young tree (about two game hours at the demo pace, watered when dry)."""
    world = World(load_lsystem(lsys_dir / "game_tree.lsys"), load_rules("assets/rules.toml", pace="demo"), seed=8)
    world.sim.state.sun_meter = world.sim.state.water_meter = 0.9
    for _ in range(1600):
        world.apply(Action.WATER, float(world.sim.state.water_meter < 0.6))
        world.step(0.5)
    path = tmp_path_factory.mktemp("card") / "tree.arbor"
    write_garden(SavedGarden([world]), path)
    return path


@pytest.fixture(scope="module")
def card(saved, gl_ctx):
    """The postcard of that tree, made by `arbor card`."""
    out = saved.with_name("tree.png")
    assert main(["card", str(saved), "--out", str(out)]) == 0
    return out


def _png(size=(8, 8)) -> bytes:
    """A small plain PNG (no save inside)."""
    from PIL import Image

    out = io.BytesIO()
    Image.new("RGB", size, (40, 90, 40)).save(out, "PNG")
    return out.getvalue()


def test_a_card_is_a_picture_of_the_tree_and_imports_as_the_same_tree(saved, card, tmp_path, capsys):
    from PIL import Image

    picture = np.asarray(Image.open(card).convert("RGB"))
    assert picture.shape == (720, 960, 3)
    tree_part, caption = picture[:600], picture[600:]
    green = (tree_part[..., 1] > tree_part[..., 0] + 20) & (tree_part[..., 1] > tree_part[..., 2] + 20)
    assert green.mean() > 0.05  # leaves and grass are drawn
    assert (caption.mean(axis=2) < 120).sum() > 500  # the caption's dark lettering
    home = tmp_path / "home"
    assert main(["--saves", str(home), "import", str(card)]) == 0
    assert "planted game_tree" in capsys.readouterr().out
    original, planted = read_garden(saved).world, read_garden(home / "autosave.arbor").world
    assert planted.tree.lstring.to_text() == original.tree.lstring.to_text()
    assert planted.lineage.id == original.lineage.id


def test_an_imported_tree_is_planted_beside_the_others(card, saved, tmp_path, capsys):
    home = tmp_path / "home"
    other = read_garden(saved).world
    other.lineage = dataclasses.replace(other.lineage, id="0123456789abcdef")  # another tree already there
    home.mkdir()
    write_garden(SavedGarden([other]), home / "autosave.arbor")
    was = (home / "autosave.arbor").read_bytes()
    assert main(["--saves", str(home), "import", str(card)]) == 0
    assert (home / "autosave.1.arbor").read_bytes() == was  # the garden before the import can be restored
    garden = read_garden(home / "autosave.arbor")
    assert len(garden.worlds) == 2 and garden.current == 1  # the newcomer is the one cared for
    gap = np.hypot(*np.subtract(garden.worlds[0].position, garden.worlds[1].position))
    assert gap > 3.0  # scene units: beside, not on top of, the tree already there
    before = (home / "autosave.arbor").read_bytes()
    assert main(["--saves", str(home), "import", str(card)]) == 1  # the same tree twice: refused
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "already in your garden" in err[0]
    assert (home / "autosave.arbor").read_bytes() == before


def test_a_card_survives_a_viewer_that_keeps_text_chunks_and_says_so_when_one_drops_them(card, tmp_path):
    from PIL import Image, PngImagePlugin

    image = Image.open(card)
    kept = PngImagePlugin.PngInfo()
    for key, value in image.text.items():
        kept.add_itxt(key, value, zip=True)
    image.save(tmp_path / "kept.png", pnginfo=kept)
    assert read_card(tmp_path / "kept.png").world.tree.lstring.to_text() == \
        read_card(card).world.tree.lstring.to_text()
    image.save(tmp_path / "stripped.png")  # Pillow drops text chunks unless asked to keep them
    with pytest.raises(SaveError, match="carries no Arbor save"):
        read_card(tmp_path / "stripped.png")


def _with_chunk(body: bytes) -> bytes:
    """A plain PNG with an iTXt 'Arbor save' chunk whose body after the keyword is ``body``."""
    png = _png()
    data = card_module.KEYWORD + b"\x00" + body
    chunk = len(data).to_bytes(4, "big") + b"iTXt" + data + zlib.crc32(b"iTXt" + data).to_bytes(4, "big")
    return png[:33] + chunk + png[33:]


def _flipped(png: bytes) -> bytes:
    """``png`` with one byte of its save chunk's text changed after the CRC was made (a damaged download)."""
    at = png.index(b"iTXt") + 4 + len(card_module.KEYWORD) + 10
    return png[:at] + bytes([png[at] ^ 0xFF]) + png[at + 1:]


@pytest.mark.parametrize("name, make, expect", [
    ("plain", lambda: _png(), "carries no Arbor save"),
    ("not a png", lambda: b"GIF89a" + bytes(100), "not a PNG picture"),
    ("cut short", lambda: _with_chunk(b"\x01\x00\x00\x00" + zlib.compress(b"format = 2"))[:40],
     "cut short|longer than"),
    ("bad crc", lambda: _flipped(_with_chunk(b"\x01\x00\x00\x00" + zlib.compress(b"format = 2" * 9))),
     "damaged PNG chunk"),
    ("not zlib", lambda: _with_chunk(b"\x01\x00\x00\x00" + b"not zlib at all"), "does not inflate"),
    ("bad toml", lambda: _with_chunk(b"\x01\x00\x00\x00" + zlib.compress(b"format = = 2")), "not a valid save"),
    ("hostile tree", lambda: _with_chunk(b"\x00\x00\x00\x00" + b"format = 2\n[[trees]]\nlstring = 'F(1e400)'\n"),
     "tree|lstring|number|system"),
])
def test_a_hostile_card_is_refused_in_one_line_naming_the_card(tmp_path, capsys, name, make, expect):
    path = tmp_path / "bad.png"
    path.write_bytes(make())
    home = tmp_path / "home"
    assert main(["--saves", str(home), "import", str(path)]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"arbor: {path}") and re.search(expect, err[0]), err
    assert not (home / "autosave.arbor").exists()


def test_a_zlib_bomb_is_stopped_at_the_save_size_limit(tmp_path, monkeypatch):
    monkeypatch.setattr(card_module, "MAX_BYTES", 10_000)
    path = tmp_path / "bomb.png"
    path.write_bytes(_with_chunk(b"\x01\x00\x00\x00" + zlib.compress(b"#" * 4_000_000)))
    tracemalloc.start()
    try:
        with pytest.raises(SaveError, match="too large"):
            read_card(path)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 1_000_000  # bytes: inflating stopped at the limit, the 4 MB inside were never made


def test_import_waits_for_no_game_it_is_refused_while_one_holds_the_garden(card, tmp_path, capsys):
    from arbor.engine.base.files import FolderLock

    home = tmp_path / "home"
    lock = FolderLock(home).acquire()
    try:
        assert main(["--saves", str(home), "import", str(card)]) == 1
    finally:
        lock.release()
    assert "in use by another Arbor" in capsys.readouterr().err
    assert not (home / "autosave.arbor").exists()


def test_card_bytes_put_the_save_before_the_picture_data(saved):
    data = card_bytes(_png(), read_garden(saved))
    assert data.index(b"iTXt") < data.index(b"IDAT")


def test_a_card_is_checked_to_its_last_chunk_and_its_errors_name_no_line(saved, tmp_path):
    """Issue 45: damage after the save chunk (a bad IEND CRC, no IHDR) was accepted, and card errors
    carried a meaningless ':1:1:'."""
    good = card_bytes(_png(), read_garden(saved))
    bad_end = good[:-4] + bytes(4)  # IEND's CRC zeroed
    no_header = card_module.SIGNATURE + good[len(card_module.SIGNATURE) + 25:]  # IHDR (25 bytes) taken out
    for name, data, says in [("end.png", bad_end, "a damaged PNG chunk 'IEND'"),
                             ("head.png", no_header, "does not start with its header chunk")]:
        path = tmp_path / name
        path.write_bytes(data)
        with pytest.raises(SaveError) as info:
            read_card(path)
        assert says in str(info.value) and str(info.value).startswith(f"{path}: ") and ":1:1:" not in str(info.value)
    (tmp_path / "ok.png").write_bytes(good)
    assert read_card(tmp_path / "ok.png").worlds
