"""Sweep figures that hold up in a classroom (issue 49): panel titles never overlap, a one-level sweep is a
distribution, every dose plot shows the spread over seeds, dead trees are marked with their day of death,
and every seed's tree can be shown at one scale."""

from __future__ import annotations

import itertools
from pathlib import Path

import matplotlib.image as mpimg
import numpy as np
import pytest

from arbor.engine.life.experiment.lab import Regime
from arbor.engine.life.experiment.sweep import Factor, Sweep
from arbor.game.render import figures

LONGEST = sorted(figures.TITLES, key=lambda r: -len(figures.TITLES[r]))[:10]  # the ten longest titles


def _sweep(levels=((0.0, 0.5, 1.0), (0.004, 0.02)), responses=tuple(LONGEST), seeds=6) -> Sweep:
    factors = [Factor("Sun orbit height", "orbit_height", levels[0])]
    if len(levels) > 1:
        factors.append(Factor("Drain", "water.drain_rate", levels[1]))
    return Sweep("A sweep", factors, list(range(1, seeds + 1)), 300.0, 100.0, responses, Regime("base"))


def _finals(sweep: Sweep, seed: int = 0) -> dict:
    rng = np.random.default_rng(seed)
    return {levels: {r: rng.uniform(0.2, 0.8, len(sweep.seeds)) for r in sweep.responses}
            for levels in itertools.product(*(f.levels for f in sweep.factors))}


def _overlap(a, b) -> bool:
    return a.x0 < b.x1 and b.x0 < a.x1 and a.y0 < b.y1 and b.y0 < a.y1


def test_ten_responses_titles_never_overlap_each_other_or_a_neighbour():
    sweep = _sweep()
    fig = figures.dose_figure(sweep, _finals(sweep))
    renderer = fig.canvas.get_renderer()
    fig.canvas.draw()
    axes = [ax for ax in fig.axes if ax.get_visible() and ax.axison]
    assert len(axes) == 10
    titles = [ax.title.get_window_extent(renderer) for ax in axes]
    for i, j in itertools.permutations(range(len(axes)), 2):
        assert not _overlap(titles[i], titles[j]), (axes[i].get_title(), axes[j].get_title())
        assert not _overlap(titles[i], axes[j].get_window_extent(renderer)), (axes[i].get_title(), j)
        assert not _overlap(titles[i], axes[j].yaxis.label.get_window_extent(renderer)), axes[i].get_title()
    suptitle = fig._suptitle.get_window_extent(renderer)
    assert not any(_overlap(suptitle, t) for t in titles)


def test_every_dose_plot_shows_the_spread_over_seeds():
    sweep = _sweep(responses=("height", "alive"))
    finals = _finals(sweep)
    fig = figures.dose_figure(sweep, finals)
    ax = fig.axes[0]
    bars = [c for c in ax.collections if c.__class__.__name__ == "LineCollection"]
    assert len(bars) == 2  # one set of 10-90 % bars per line (the second factor's levels)
    for bar, drain in zip(bars, (0.004, 0.02), strict=True):
        for segment, level in zip(bar.get_segments(), (0.0, 0.5, 1.0), strict=True):
            low, high = np.percentile(finals[(level, drain)]["height"], [10, 90])
            assert np.allclose(sorted(segment[:, 1]), [low, high])
    dots = [c for c in ax.collections if c.__class__.__name__ == "PathCollection"]
    assert sum(len(d.get_offsets()) for d in dots) == 3 * 2 * 6  # every run a dot


def test_a_one_level_sweep_is_a_distribution_not_a_degenerate_dose_plot(tmp_path):
    sweep = _sweep(levels=((0.35,),), responses=("height", "alive"), seeds=20)
    finals = _finals(sweep)
    finals[(0.35,)]["alive"] = np.ones(20)
    fig = figures.distribution_figure(sweep, finals)
    height, alive = fig.axes[:2]
    v = finals[(0.35,)]["height"]
    assert sum(p.get_height() for c in height.containers for p in c) == 20  # a histogram of the 20 seeds
    low, high = height.get_xlim()
    assert low <= v.min() and v.max() <= high and high - low < 2 * np.ptp(v)  # the values' range, not 0.34..0.36
    assert len(height.collections[-1].get_offsets()) == 20  # and every run as a dot
    assert sum(p.get_height() for c in alive.containers for p in c) == 20 and np.ptp(alive.get_xlim()) > 0.3
    paths = figures.dose_response(sweep, finals, tmp_path / "dose")
    assert "histogram" in paths[1].read_text(encoding="utf-8")  # dose_response chose the distribution
    two = _sweep(levels=((0.35,), (0.004, 0.02)), responses=("height",))  # one level x two: across the second
    fig = figures.dose_figure(two, _finals(two))
    assert fig.axes[0].get_xlabel().startswith("Drain") and "Sun orbit height = 0.35" in fig._suptitle.get_text()


def _red(png: Path) -> float:
    img = mpimg.imread(png)[..., :3]
    return float(((img[..., 0] > 0.65) & (img[..., 1] < 0.35) & (img[..., 2] < 0.3)).mean())


def test_dead_trees_are_marked_with_their_day_of_death(tmp_path):
    sweep = _sweep(levels=((0.0, 1.0),), responses=("height",))
    sky = np.zeros((90, 75, 3), np.uint8) + np.array([140, 180, 230], np.uint8)
    images = {(0.0,): sky, (1.0,): sky}
    alive = figures.thumbnails(sweep, images, tmp_path / "alive")
    dead = figures.thumbnails(sweep, images, tmp_path / "dead", {(1.0,): "died on day 2.5"})
    assert _red(alive[0]) == 0 and _red(dead[0]) > 0.005
    assert "died on day 2.5" in dead[1].read_text(encoding="utf-8")


def test_every_seeds_tree_in_one_grid(tmp_path):
    sweep = _sweep(levels=((0.0, 1.0),), responses=("height",), seeds=12)
    images = {((level,), seed): np.full((60, 50, 3), 40 * seed % 255, np.uint8) for level in (0.0, 1.0)
              for seed in sweep.seeds}
    svg = figures.seed_grid(sweep, images, tmp_path / "seeds", {((1.0,), 3): "dead by day 1.0"})[1]
    text = svg.read_text(encoding="utf-8")
    for seed in sweep.seeds:
        assert f"seed {seed}" in text
    assert text.count("<image") == 24 and "dead by day 1.0" in text


@pytest.mark.parametrize("rows, note", [
    ([{"time_s": "0", "alive": "1", "stop": "died", "stop_time_s": "314.15"}], "died on day 2.5"),
    ([{"time_s": "0", "alive": "1"}, {"time_s": "251.3", "alive": "0"}], "dead by day 2.0"),
    ([{"time_s": "0", "height": "1"}], "dead"),
])
def test_the_day_of_death_comes_from_the_run(rows, note):
    from arbor.game.commands.sweep import death_note

    assert death_note(rows, 125.66) == note


def test_a_sweep_marks_its_dead_trees_and_draws_every_seed_when_all_are_kept(tmp_path):
    from arbor.game.commands.sweep import run_sweep

    path = tmp_path / "dry.toml"
    path.write_text("""title = "Dry"
duration = 300
sample_every = 100
seeds = [1, 2]
seasons = false
responses = ["height", "alive"]

[base]
watering = "never"

[stop]
dies = true

[[factor]]
name = "Drain"
key = "water.drain_rate"
levels = [0.03]
""", encoding="utf-8")
    out = tmp_path / "out"
    assert run_sweep(path, out, workers=1, echo=lambda _: None, keep="all") == 0
    assert _red(out / "thumbnails.png") > 0.005 and "died on day" in (out / "thumbnails.svg").read_text()
    grid = (out / "seeds.svg").read_text(encoding="utf-8")
    assert "seed 1" in grid and "seed 2" in grid and grid.count("died on day") == 2
    assert "histogram" in (out / "dose_response.svg").read_text(encoding="utf-8")  # one level: a distribution
