"""Every shipped .lsys source renders, exports and views (GeoMaTree's sources grow as a species, whose
functions Arbor supplies); the game's own sources, which need the game's values at every step, are refused
in one line that says how to render them (from a save)."""

from __future__ import annotations

from pathlib import Path

import pytest

from arbor.engine.lsystem.lsys import load_lsystem
from arbor.game.cli import main
from tests.conftest import LSYSTEMS

SOURCES = sorted(LSYSTEMS.glob("*.lsys"))


def _needs_the_game(path: Path) -> bool:
    return "#extern" in path.read_text(encoding="utf-8")


def test_the_walk_finds_the_sources():
    names = {p.name for p in SOURCES}
    assert {"abop_2_8_tree.lsys", "geomatree.lsys", "divisor_tree.lsys", "game_tree.lsys"} <= names


@pytest.fixture(scope="module")
def warm():
    """The kernels built (kernels changed since the last build would add a first start's lines)."""
    from arbor.game.first_start import warm_kernels

    warm_kernels()


@pytest.mark.parametrize("source", SOURCES, ids=lambda p: p.stem)
def test_a_shipped_source_renders_exports_and_views(source, tmp_path, capsys, gl_ctx, warm):
    png, glb = tmp_path / "t.png", tmp_path / "t.glb"
    if _needs_the_game(source):
        assert main(["render", str(source), "--out", str(png)]) == 1
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and "render its save (.arbor)" in err[0]
        return
    assert main(["render", str(source), "--lod", "2", "--size", "96x72", "--out", str(png)]) == 0
    assert main(["export", str(source), "--lod", "2", "--out", str(glb)]) == 0
    err = [line for line in capsys.readouterr().err.splitlines() if "% done" not in line]  # (progress, when slow)
    assert err == [], err  # no refusal, no budget held back, no size warning: a likely size in metres
    assert png.stat().st_size > 500 and glb.stat().st_size > 1000
    from arbor.game.screens.viewer import Viewer

    viewer = Viewer(gl_ctx, (96, 72), source)
    assert viewer.steps == min(viewer.system.iterations, 9) and len(viewer.lstring) > 1


def test_geomatree_sources_grow_as_the_species_asked_for(tmp_path, capsys):
    source = LSYSTEMS / "geomatree.lsys"
    texts = []
    for species in ("broadleaf", "weeping"):
        assert main(["derive", str(source), "--species", species]) == 0
        texts.append(capsys.readouterr().out)
    assert texts[0] != texts[1] and len(texts[0]) > 1000
    assert main(["derive", str(source), "--species", "oak"]) == 1
    assert "no such species (the species: broadleaf, weeping" in capsys.readouterr().err
    assert main(["derive", str(LSYSTEMS / "abop_2_8_tree.lsys"), "--species", "weeping"]) == 1
    assert "--species grows sources that ask for GeoMaTree's functions" in capsys.readouterr().err
    odd = tmp_path / "odd.lsys"
    odd.write_text("#host wind\nw: F\n")
    assert main(["derive", str(odd)]) == 1
    assert "supply wind()" in capsys.readouterr().err


def test_the_abop_examples_declare_their_unit():
    for source in SOURCES:
        if source.name.startswith("abop_"):
            assert load_lsystem(source).unit is not None, source.name
