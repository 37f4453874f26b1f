"""Shoot units (engine/life/plant/units.py, engine/life/form/shoot_units.py): old leafy runs become one module
that draws as the wood and leaves it stands for, and sheds and opens its leaves as they would."""

from __future__ import annotations

import numpy as np
import pytest

from arbor.engine.base.assets import assets_dir
from arbor.engine.geometry.turtle import tip_segments
from arbor.engine.life.form.interpret import Clocks, grown_turtle, leaf_area, pipe_area, reference_constants
from arbor.engine.life.form.shoot_units import bare, leaf_count, unit_modules
from arbor.engine.life.plant.units import form_units
from arbor.engine.lsystem.derive import Deriver
from arbor.engine.lsystem.lstring import parse_lstring
from arbor.engine.lsystem.lsys import load_lsystem

NOW = 200.0


def _axis(rng: np.random.Generator, order: int, nodes: int, born: float, branch_at: tuple[int, ...]) -> str:
    """One axis of leafy nodes with small turns (a tree's twigs after its leaves fell: leaf buds V)."""
    out = []
    for k in range(nodes):
        h, u = rng.normal(0.0, 1.2, 2)
        roll = "/(137.5)" if order == 0 else ""
        leaf = "[&(60)V]" if order == 0 else f"[/({k * 137.5 + 180:g})&(60)V]"
        out.append(f"+({h:.3f})^({u:.3f}){roll}I({born + k:g},{born + k:g},{order},0,0)")
        if k in branch_at:
            twig = _axis(rng, order + 1, nodes - 4, born + k + 1, (5,) if order < 1 else ())
            out.append(f"[&(45)/({k * 90:g}){twig}]")
        out.append(leaf)
    return "".join(out)


@pytest.fixture(scope="module")
def tree():
    """A bare two-order tree: a trunk of 24 nodes with branches, every node with its leaf bud."""
    rng = np.random.default_rng(5)
    ls = parse_lstring("I(0,0,0,0,0)" + _axis(rng, 0, 24, 1.0, (6, 12, 18)) + "A(0,0,24,1,0,0)")
    const = reference_constants()
    segs = grown_turtle(ls, Clocks(NOW, NOW, 0.0), const).segments
    ls.params[ls.offsets[segs.module] + 4] = 2.5 * pipe_area(ls, segs, const)  # wood built over the years
    return ls


def _wood_volume(turtle) -> float:
    s = turtle.segments
    length = np.linalg.norm(s.end - s.start, axis=1)
    return float((np.pi * length * (s.radius ** 2 + s.radius * s.radius_end + s.radius_end ** 2) / 3).sum())


def _silhouette(turtle, axes: list[int], lo: np.ndarray, hi: np.ndarray, n: int = 400) -> np.ndarray:
    """Pixels covered by the wood seen along the remaining axis (tapered tubes)."""
    s = turtle.segments
    a, b = s.start[:, axes], s.end[:, axes]
    grid = np.stack(np.meshgrid(np.linspace(lo[0], hi[0], n), np.linspace(lo[1], hi[1], n)), -1).reshape(-1, 2)
    covered = np.zeros(len(grid), bool)
    for i in range(len(a)):
        d = b[i] - a[i]
        t = ((grid - a[i]) @ d) / max(float(d @ d), 1e-12)  # (flat ends: tubes meet at rings, not caps)
        dist = np.linalg.norm(grid - (a[i] + t[:, None] * d), axis=1)
        covered |= (dist <= s.radius[i] + t * (s.radius_end[i] - s.radius[i])) & (t >= 0) & (t <= 1)
    return covered


@pytest.mark.parametrize("way", ["at once", "via singles", "two winters"])
def test_units_keep_the_drawn_wood_within_one_percent(tree, way):
    const = reference_constants()
    merged, saved = form_units(tree, NOW, const)
    if way != "at once":  # the season's one-site units join runs in winter as plain nodes would, and a
        # winter's units join the next winter's (the lower half of the tree is old at NOW - 164)
        first = form_units(tree, NOW, const, runs=False) if way == "via singles" else form_units(tree, 36.0, const)
        runs, _ = form_units(first[0], NOW, const)
        assert len(runs) <= len(merged) + 2 < len(first[0]) // 3
        merged, saved = runs, len(tree) - len(runs)
    assert len(unit_modules(merged)) >= 5 and saved > 0.4 * len(tree)  # most of the string goes
    clocks = Clocks(NOW, NOW, 0.0)
    before, after = grown_turtle(tree, clocks, const), grown_turtle(merged, clocks, const)
    assert _wood_volume(after) == pytest.approx(_wood_volume(before), rel=0.01)
    pts = np.concatenate([before.segments.start, before.segments.end])
    for axes in ([0, 1], [2, 1]):
        lo, hi = pts[:, axes].min(axis=0) - 0.3, pts[:, axes].max(axis=0) + 0.3
        was, now = _silhouette(before, axes, lo, hi), _silhouette(after, axes, lo, hi)
        assert now.sum() == pytest.approx(was.sum(), rel=0.01), (now.sum(), was.sum())
    # everything the units do not stand for stands exactly where it stood: the tips of every axis (units made
    # at 6 elongation time constants stand for 99.75 % grown nodes: a few mm later, internodes 1 m long)
    tips = [t.segments.end[tip_segments(t.segments)] for t in (before, after)]
    np.testing.assert_allclose(tips[1][np.lexsort(tips[1].T)], tips[0][np.lexsort(tips[0].T)],
                               atol=5e-3 if way == "two winters" else 1e-9)
    assert parse_lstring(merged.to_text()).to_text() == merged.to_text()  # saves as text like any string
    _, more = form_units(merged, NOW, const)
    assert more == 0


def _season(ls, system, externs: dict[str, float], steps: int, t0: float, seed: int = 1):
    deriver = Deriver(system, seed=seed, budget=None)
    base = {"T": t0, "G": t0, "DT": 1.0, "R": 1.0, "B": 0.0, "WL": 1.0, "C": 1.0, "SF": 1.0, "AF": 0.0, "SP": 0.0,
            "SL": 1.0, "LG": 1.0}
    for k in range(steps):
        ls, _ = deriver.step(ls, {**base, **externs, "T": t0 + k + 1, "G": t0 + k + 1})
    return ls


@pytest.mark.parametrize("name", ["game_tree.lsys", "game_poplar.lsys"])
def test_a_unit_opens_sheds_and_loses_leaves_as_its_nodes_would(tree, name):
    system = load_lsystem(assets_dir() / "lsystems" / name)
    const = reference_constants()
    merged, _ = form_units(tree, NOW, const)
    sites = leaf_count(_season(tree, system, {"SF": 3.0}, 1, NOW))
    # the spring flush: every site of a unit opens, like the leaf buds it stands for, the same size
    nodes, units = _season(tree, system, {"SF": 3.0}, 1, NOW), _season(merged, system, {"SF": 3.0}, 1, NOW)
    assert leaf_count(units) == leaf_count(nodes) == sites > 100
    assert leaf_area(units, NOW + 20, const) == pytest.approx(leaf_area(nodes, NOW + 20, const), rel=1e-9)
    # autumn: leaves fall at the same rate (the nodes' leaves one by one at random, the units' share alike;
    # the trunk's apex grows a few new leafy nodes meanwhile in both)
    fall = {"AF": 0.02}
    summer = leaf_count(_season(units, system, {}, 30, NOW + 1))  # (no fall: what the apex adds)
    kept_nodes = np.mean([leaf_count(_season(nodes, system, fall, 30, NOW + 1, seed)) for seed in range(4)])
    autumn = _season(units, system, fall, 30, NOW + 1)
    kept_units = leaf_count(autumn)
    assert kept_units == pytest.approx(kept_nodes, rel=0.12) and kept_units < 0.8 * summer
    # winter strips the units; the next spring opens every site again (autumn's leaves left buds)
    bare_units, fell = bare(autumn)
    assert leaf_count(bare_units) == np.count_nonzero(bare_units.sym == ord("L")) == kept_units - fell
    assert leaf_count(_season(bare_units, system, {"SF": 3.0}, 1, NOW + 40)) >= sites
    # drought in summer: leaves are lost for good, as many from units as from nodes
    dry = {"WL": 0.45}
    lost_nodes = np.mean([leaf_count(_season(nodes, system, dry, 25, NOW + 1, seed)) for seed in range(4)])
    lost_units = leaf_count(_season(units, system, dry, 25, NOW + 1))
    assert lost_units == pytest.approx(lost_nodes, rel=0.12) and lost_units < 0.8 * summer


def test_leafy_nodes_in_summer_become_units_with_their_leaves(tree):
    system = load_lsystem(assets_dir() / "lsystems" / "game_tree.lsys")
    const = reference_constants()
    leafy = _season(tree, system, {"SF": 3.0}, 1, NOW)  # every bud open: leaves born at NOW + 1
    later = NOW + 40
    units, saved = form_units(leafy, later, const, runs=False)
    assert saved > 0.4 * len(leafy) and np.count_nonzero(units.sym == ord("L")) < 10
    assert leaf_count(units) == leaf_count(leafy)
    assert leaf_area(units, later, const) == pytest.approx(leaf_area(leafy, later, const), rel=1e-12)
    clocks = Clocks(later, later, 0.0)
    before, after = grown_turtle(leafy, clocks, const), grown_turtle(units, clocks, const)
    np.testing.assert_allclose(np.sort(after.leaves.position, axis=0), np.sort(before.leaves.position, axis=0),
                               atol=1e-9)  # a one-site unit's leaf stands where its node's stood


def test_a_unit_joins_the_nodes_its_axis_grew_after_it():
    """Last winter's unit before the apex keeps the apex's frame in one set of turns; the nodes the apex grows
    after it join it next winter across those turns, drawn as the same axis grown as plain nodes."""
    rng = np.random.default_rng(8)
    older, newer = _axis(rng, 0, 5, 1.0, ()), _axis(rng, 0, 5, 6.0, ())
    plain = parse_lstring("I(0,0,0,0,0)" + older + newer + "A(0,0,10,1,0,0)")
    const = reference_constants()
    last_winter, _ = form_units(parse_lstring("I(0,0,0,0,0)" + older + "A(0,0,5,1,0,0)"), NOW, const)
    grown = parse_lstring(last_winter.to_text().replace("A(0,0,5,1,0,0)", newer + "A(0,0,10,1,0,0)"))
    joined, _ = form_units(grown, NOW, const)
    at_once, _ = form_units(plain, NOW, const)
    assert len(joined) == len(at_once) < len(grown) // 3
    assert len(unit_modules(joined)) == 1  # one unit of ten sites
    clocks = Clocks(NOW, NOW, 0.0)
    before, after = grown_turtle(plain, clocks, const), grown_turtle(joined, clocks, const)
    np.testing.assert_allclose(after.segments.end[-1], before.segments.end[-1], atol=1e-9)  # the apex's place
