"""Exported figures, drawn with matplotlib (PNG and SVG): sweep dose-response, time series per level,
a thumbnail grid of final trees, the lab's charts, and trees on one plot against the same tree alone.
Large type and thick lines for a projector."""

from __future__ import annotations

import warnings
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # files only: never a window, never a display

import matplotlib.pyplot as plt
import numpy as np

from arbor.engine.life.experiment.measure import UNITS
from arbor.engine.life.experiment.schema import FACTOR_KEYS
from arbor.engine.life.rules.schema import find_rule

TITLES = {"height": "Height", "width": "Crown width", "offset": "Lean toward the sun", "girth": "Trunk girth",
          "modules": "Modules", "leaves": "Leaf clusters", "density": "Leaf density (clusters per crown volume)",
          "shed": "Branches shed", "roots": "Root length", "sun": "Sun meter (mean)", "water": "Water meter (mean)",
          "wilt": "Wilt (mean)", "alive": "Alive (share)", "fruit": "Fruit", "biomass": "Above-ground biomass",
          "leaf_area": "Leaf area", "lai": "Leaf area index", "light_share": "Light reaching the leaves",
          "light_day": "Light intercepted a day", "net_carbon": "Net carbon (fixed - respired)",
          "pool": "Sugar in store", "day_of_death": "Day of death", "root_shoot": "Root:shoot (carbon built)",
          "pruned": "Branches cut by pruning",
          **{f"{m}_{end}": f"{name} ({word} since the last sample)"
             for m, name in (("sun", "Sun meter"), ("water", "Water meter"), ("wilt", "Wilt"))
             for end, word in (("min", "lowest"), ("max", "highest"))}}
YLABELS = {"alive": "share of seeds alive (0..1)", "modules": "modules (count)", "leaves": "clusters (count)",
           "shed": "branches (count)", "fruit": "fruit (count)", "lai": "m² of leaf per m² of ground",
           "light_share": "share of full sun (0..1)", "light_day": "m² of leaf x hours of full sun",
           "root_shoot": "g into roots per g into shoots", "pruned": "branches (count)",
           **{f"{m}{end}": "meter, 0 (empty) .. 1 (full)" for m in ("sun", "water") for end in ("", "_min", "_max")},
           **{f"wilt{end}": "wilt, 0 (none) .. 1 (fully wilted)" for end in ("", "_min", "_max")}}
plt.rcParams.update({"font.size": 13, "axes.titlesize": 15, "axes.titleweight": "bold", "lines.linewidth": 2.5,
                     "svg.hashsalt": "arbor", "axes.spines.top": False, "axes.spines.right": False})


def save_both(fig, path: Path) -> list[Path]:
    """Write ``fig`` as PNG and SVG next to each other; returns both paths."""
    png, svg = path.with_suffix(".png"), path.with_suffix(".svg")
    fig.savefig(png, dpi=110, bbox_inches="tight")
    fig.savefig(svg, bbox_inches="tight", metadata={"Date": None})
    plt.close(fig)
    return [png, svg]


def _grid(n: int, width: float = 5.2, height: float = 3.8):
    cols = min(n, 3)
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(width * cols, height * rows), squeeze=False, layout="constrained")
    for ax in axes.flat[n:]:
        ax.axis("off")
    return fig, list(axes.flat[:n])


def _positions(levels: tuple) -> tuple[np.ndarray, list[str] | None]:
    """x positions of a factor's levels: the values, or 0..k-1 with labels for names (species)."""
    if all(isinstance(v, float | int) for v in levels):
        return np.array(levels, dtype=float), None
    return np.arange(len(levels), dtype=float), [str(v).removesuffix(".lsys") for v in levels]


def dose_response(sweep, finals: dict, path: Path, day_seconds: float = 125.66) -> list[Path]:
    """Each response at the end of the runs against the first factor's levels: the mean over seeds, a
    10-90 % band and every run as a dot; one line per level of the second factor (the title gives the
    runs' length in game days of ``day_seconds``)."""
    first = sweep.factors[0]
    second = sweep.factors[1].levels if len(sweep.factors) > 1 else (None,)
    x, labels = _positions(first.levels)
    colors = plt.cm.viridis(np.linspace(0.05, 0.85, len(second)))
    fig, axes = _grid(len(sweep.responses))
    for ax, response in zip(axes, sweep.responses, strict=True):
        for color, other in zip(colors, second, strict=True):
            stats = []
            for xi, level in zip(x, first.levels, strict=True):
                key = (level,) if other is None else (level, other)
                values = finals.get(key, {}).get(response, np.zeros(0))
                if len(values):
                    ax.scatter(np.full(len(values), xi), values, s=9, color=color, alpha=0.35, linewidths=0)
                    stats.append((xi, values.mean(), *np.percentile(values, [10, 90])))
            if stats:
                sx, mean, low, high = np.array(stats).T
                ax.fill_between(sx, low, high, color=color, alpha=0.2, linewidth=0)
                label = None if other is None else f"{sweep.factors[1].name} = {_text(other)}"
                ax.plot(sx, mean, "-o", color=color, label=label, markersize=5)
        _limits(ax, response)
        ax.set_title(TITLES.get(response, response))
        ax.set_xlabel(axis_label(first))
        ax.set_ylabel(y_label(response))
        if labels:
            ax.set_xticks(x, labels)
        ax.grid(alpha=0.3)
    if len(second) > 1:
        axes[0].legend(fontsize=10, frameon=False)
    fig.suptitle(f"{sweep.title}: after {_duration(sweep.duration, day_seconds)}, {len(sweep.seeds)} seeds per level "
                 "(line: mean; band: 10-90 %)", fontsize=16)
    return save_both(fig, path)


def time_series(sweep, series: dict, path: Path, day_seconds: float = 125.66) -> list[Path]:
    """Each response over time (in game days of ``day_seconds``): per combination of levels, the mean over
    seeds and a 10-90 % band. ``series`` maps levels -> (times, {response: array seeds x samples})."""
    fig, axes = _grid(len(sweep.responses))
    colors = plt.cm.viridis(np.linspace(0.05, 0.85, max(len(series), 1)))
    for ax, response in zip(axes, sweep.responses, strict=True):
        for color, (levels, (times, values)) in zip(colors, series.items(), strict=True):
            v = values[response]
            days = times / day_seconds
            with np.errstate(all="ignore"), warnings.catch_warnings():  # (runs stopped early: NaN, skipped)
                warnings.simplefilter("ignore", RuntimeWarning)
                low, high = np.nanpercentile(v, [10, 90], axis=0)
                mean = np.nanmean(v, axis=0)
            ax.fill_between(days, low, high, color=color, alpha=0.15, linewidth=0)
            ax.plot(days, mean, color=color, label=", ".join(_text(x) for x in levels))
        _limits(ax, response)
        ax.set_title(TITLES.get(response, response))
        ax.set_xlabel(f"time (game days of {day_seconds:.0f} s)")
        ax.set_ylabel(y_label(response))
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=9, frameon=False, title=" x ".join(f.name for f in sweep.factors), title_fontsize=9)
    fig.suptitle(f"{sweep.title}: mean over {len(sweep.seeds)} seeds (band: 10-90 %)", fontsize=16)
    return save_both(fig, path)


def thumbnails(sweep, images: dict, path: Path) -> list[Path]:
    """The final tree of each combination of levels (its first seed), in a grid: first factor across,
    second factor down. ``images`` maps levels -> RGB array."""
    across = sweep.factors[0].levels
    down = sweep.factors[1].levels if len(sweep.factors) > 1 else (None,)
    fig, axes = plt.subplots(len(down), len(across), figsize=(2.6 * len(across), 3.2 * len(down)), squeeze=False,
                             layout="constrained")
    for r, other in enumerate(down):
        for c, level in enumerate(across):
            ax = axes[r][c]
            ax.axis("off")
            key = (level,) if other is None else (level, other)
            if key in images:
                ax.imshow(images[key])
            title = _text(level)
            if other is not None and c == 0:
                title = f"{sweep.factors[1].name} = {_text(other)}\n{title}"
            ax.set_title(title, fontsize=11, fontweight="normal")
    fig.suptitle(f"{sweep.title}: final trees (seed {sweep.seeds[0]}); across: {sweep.factors[0].name}", fontsize=13)
    return save_both(fig, path)


def lab_charts(series: list, path: Path, title: str = "", colors=((230, 90, 60), (60, 140, 230), (90, 180, 70),
                                                                   (200, 160, 30), (150, 80, 180), (60, 60, 60)),
               metrics=("height", "biomass", "leaf_area", "light_share", "light_day", "net_carbon", "water",
                        "wilt")) -> list[Path]:
    """The lab's time series as small multiples, one line per tree in the live charts' colours (the
    exported twin of the lab screen's charts), against game days; a dead tree's line ends in a cross."""
    fig, axes = _grid(len(metrics))
    for ax, metric in zip(axes, metrics, strict=True):
        for k, s in enumerate(series):
            color = np.array(colors[k % len(colors)]) / 255.0
            ax.plot(s.day, s.values[metric], label=s.name, color=color)
            dead = [i for i, alive in enumerate(s.values["alive"]) if not alive]
            if dead:
                ax.plot(s.day[dead[0]], s.values[metric][dead[0]], "x", color=color, markersize=14, mew=3)
        _limits(ax, metric)
        ax.set_title(TITLES.get(metric, metric))
        ax.set_xlabel("time (game days)")
        ax.set_ylabel(y_label(metric))
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=10, frameon=False)
    if title:
        fig.suptitle(title, fontsize=16)
    return save_both(fig, path)


def competition(series: list, alone, path: Path, title: str = "",
                colors=((230, 90, 60), (60, 140, 230), (90, 180, 70))) -> list[Path]:
    """Trees sharing a plot against the same tree alone, against game days: the light each intercepts a day
    (m² x h), and the light reaching its leaves (a share of full sun: the shade on each m² of leaf, whatever
    the tree's size) as % more or less than on the lone tree's leaves the same day, with each tree's mean
    over the run in the legend. ``alone`` is the lone tree's series (same seed and regime, own plot)."""
    fig, axes = _grid(2, width=6.4, height=4.4)
    lone = np.asarray(alone.values["light_share"])
    for k, s in enumerate(series):
        color = np.array(colors[k % len(colors)]) / 255.0
        axes[0].plot(s.day, s.values["light_day"], color=color, label=s.name)
        less = 100.0 * (np.asarray(s.values["light_share"]) / np.maximum(lone, 1e-9) - 1.0)
        axes[1].plot(s.day[3:], less[3:], color=color,  # (the first days: a seedling's few leaves)
                     label=f"{s.name}: {less[3:].mean():+.1f} % on average")
    axes[0].plot(alone.day, alone.values["light_day"], "--", color="0.35", label="alone (same seed, own plot)")
    axes[1].axhline(0.0, color="0.35", linestyle="--", linewidth=2, label="alone")
    axes[0].set_title(TITLES["light_day"])
    axes[0].set_ylabel(YLABELS["light_day"] + " per day")
    axes[1].set_title("Light on the leaves, against the tree alone")
    axes[1].set_ylabel("% more (+) or less (-) than alone")
    axes[1].legend(fontsize=10, frameon=False)
    for ax in axes:
        ax.set_xlabel("time (game days)")
        ax.grid(alpha=0.3)
    axes[0].set_ylim(bottom=0)
    axes[0].legend(fontsize=10, frameon=False)
    if title:
        fig.suptitle(title, fontsize=15)
    return save_both(fig, path)


def axis_label(factor) -> str:
    """A factor's name for its axis, with the unit of what it varies (the experiment schema's sun and
    watering keys, the rule schema's rules, e.g. "Drain (meter per s)"), so a figure says what its numbers
    count; a species axis is named, it has no unit."""
    if factor.key == "species":
        return factor.name
    key = FACTOR_KEYS.get(factor.key)
    unit = key.unit if key else getattr(find_rule(factor.key), "unit", "")
    return f"{factor.name} ({unit})" if unit and f"({unit})" not in factor.name else factor.name


def y_label(response: str) -> str:
    """A response's axis label: its unit (measure.UNITS), in words where a bare unit says too little."""
    return YLABELS.get(response, UNITS.get(response, ""))


def _limits(ax, response: str) -> None:
    """Shares and meters on 0..1; counts and sizes from 0, so small differences do not look large."""
    if response.split("_")[0] in ("sun", "water", "wilt") or response in ("alive", "light_share"):
        ax.set_ylim(-0.02, 1.05)
    elif response not in ("offset", "net_carbon"):
        ax.set_ylim(bottom=0)


def _text(value) -> str:
    return str(value).removesuffix(".lsys") if isinstance(value, str) else f"{value:g}"


def _duration(seconds: float, day_seconds: float) -> str:
    """A run's length in game days (one turn of the sun, ``day_seconds`` of game time)."""
    return f"{seconds / day_seconds:.3g} game days"
