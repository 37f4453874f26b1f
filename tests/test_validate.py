"""benchmarks.validate's references: the sun's and the leaves' rows lie within 2x of their references (most far
closer), and docs/plant.md shows the table a run prints (its sun and leaf rows checked against this run)."""

import pytest

from benchmarks import validate
from tests.conftest import ROOT


@pytest.fixture(scope="module")
def rows():
    from arbor.engine.lsystem.lsys import load_lsystem

    systems = {n: load_lsystem(ROOT / "assets" / "lsystems" / f"{n}.lsys") for n in ("game_tree", "game_poplar")}
    return validate.sun_rows() + validate.leaf_rows({n: s.constants for n, s in systems.items()})


def test_the_sun_and_the_leaves_agree_with_their_references(rows):
    assert all(row.ok() for row in rows), [row.cells() for row in rows if not row.ok()]
    midsummer = [r for r in rows if "midsummer" in r.quantity and "irradiation" in r.quantity]
    assert all(r.model == pytest.approx(r.low, rel=0.15) for r in midsummer)  # 0-60 N: within 15 % of FAO-56
    game = [r for r in rows if "game's sun" in r.quantity]
    assert all(r.model == pytest.approx(r.low, rel=0.15) for r in game)
    curves = [r for r in rows if "gross assimilation at" in r.quantity]
    assert all(r.model == pytest.approx(r.low, rel=0.1) for r in curves)  # the two published forms within 10 %


def test_docs_plant_shows_the_validation_table(rows):
    doc = (ROOT / "docs" / "plant.md").read_text(encoding="utf-8")
    start, end = validate.MARKERS
    assert start in doc and end in doc, "docs/plant.md lost its validation table: python -m benchmarks.validate --write"
    shown = doc.partition(start)[2].partition(end)[0]
    for row in rows:
        assert "| " + " | ".join(row.cells()) + " |" in shown, row.cells()
