"""Exported figures, drawn with matplotlib (PNG and SVG): sweep dose-response, time series per level,
a thumbnail grid of final trees, the lab's charts, and trees on one plot against the same tree alone.
Large type and thick lines for a projector."""

from __future__ import annotations

import textwrap
import warnings
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # files only: never a window, never a display

import matplotlib.pyplot as plt
import matplotlib.ticker
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


TITLE_WIDTH = 28  # characters a line of a panel's title holds (a 5.2-inch panel at 15 pt bold: about 34)
LABEL_WIDTH = 34  # ... of an axis label at 13 pt


def _title(ax, text: str) -> None:
    """A panel's title, wrapped so that it never reaches over its neighbours'."""
    ax.set_title(textwrap.fill(text, TITLE_WIDTH))


def _labels(ax, x: str, y: str) -> None:
    """A panel's axis labels, wrapped to the panel."""
    ax.set_xlabel(textwrap.fill(x, LABEL_WIDTH))
    ax.set_ylabel(textwrap.fill(y, LABEL_WIDTH - 6))


def dose_response(sweep, finals: dict, path: Path, day_seconds: float = 125.66) -> list[Path]:
    """Each response at the end of the runs against a factor's levels (a sweep whose levels are all one: the
    distribution over seeds instead, :func:`distribution`); see :func:`dose_figure`."""
    if all(len(f.levels) == 1 for f in sweep.factors):
        return save_both(distribution_figure(sweep, finals, day_seconds), path)
    return save_both(dose_figure(sweep, finals, day_seconds), path)


def _axes_of(sweep) -> tuple[int, int | None]:
    """Which factor runs across the x axis (the first with more than one level) and which gives the lines."""
    across = next(i for i, f in enumerate(sweep.factors) if len(f.levels) > 1)
    lines = next((i for i in range(len(sweep.factors)) if i != across), None)
    return across, lines


def dose_figure(sweep, finals: dict, day_seconds: float = 125.66):
    """Each response at the end of the runs against the levels of the first factor with more than one: the
    mean over seeds (a line), the spread over seeds (a 10-90 % bar at each level and every run as a dot,
    the dots of each line set a little apart), one line per level of the other factor (the title gives the
    runs' length in game days of ``day_seconds``)."""
    across, lines = _axes_of(sweep)
    first = sweep.factors[across]
    second = sweep.factors[lines].levels if lines is not None else (None,)
    x, labels = _positions(first.levels)
    step = float(np.min(np.diff(np.sort(x)))) if len(x) > 1 else 1.0
    colors = plt.cm.viridis(np.linspace(0.05, 0.85, len(second)))
    fig, axes = _grid(len(sweep.responses))
    for ax, response in zip(axes, sweep.responses, strict=True):
        for k, (color, other) in enumerate(zip(colors, second, strict=True)):
            shift = (k - (len(second) - 1) / 2) * step * 0.06  # (the lines' dots side by side, not on one another)
            stats = []
            for xi, level in zip(x, first.levels, strict=True):
                key = [None] * len(sweep.factors)
                key[across] = level
                if lines is not None:
                    key[lines] = other
                values = finals.get(tuple(key), {}).get(response, np.zeros(0))
                if len(values):
                    ax.scatter(np.full(len(values), xi + shift), values, s=14, color=color, alpha=0.55,
                               linewidths=0, zorder=3)
                    stats.append((xi + shift, values.mean(), *np.percentile(values, [10, 90])))
            if stats:
                sx, mean, low, high = np.array(stats).T
                ax.fill_between(sx, low, high, color=color, alpha=0.12, linewidth=0)
                ax.vlines(sx, low, high, color=color, linewidth=2, alpha=0.8)
                label = None if other is None else f"{sweep.factors[lines].name} = {_text(other)}"
                ax.plot(sx, mean, "-o", color=color, label=label, markersize=5)
        _limits(ax, response)
        _title(ax, TITLES.get(response, response))
        _labels(ax, axis_label(first), y_label(response))
        if labels:
            ax.set_xticks(x, labels)
        ax.grid(alpha=0.3)
    if len(second) > 1:
        axes[0].legend(fontsize=10, frameon=False)
    fixed = [f"{f.name} = {_text(f.levels[0])}" for i, f in enumerate(sweep.factors)
             if i != across and len(f.levels) == 1]
    fig.suptitle(textwrap.fill(f"{sweep.title}: {_when(sweep, day_seconds)}, "
                               f"{len(sweep.seeds)} seeds per level{''.join(', ' + f for f in fixed)} "
                               "(line: mean; bar and band: 10-90 %; dots: every run)", 110), fontsize=16)
    return fig


def distribution_figure(sweep, finals: dict, day_seconds: float = 125.66):
    """A sweep of one level (every factor at one value): each response's final values over the seeds as a
    histogram with every run as a dot beneath it (a strip), the mean as a line and the 10-90 % range shaded."""
    values = next(iter(finals.values())) if finals else {}
    fig, axes = _grid(len(sweep.responses))
    for ax, response in zip(axes, sweep.responses, strict=True):
        v = np.asarray(values.get(response, np.zeros(0)), dtype=float)
        if len(v):
            low, high = np.percentile(v, [10, 90])
            span = float(np.ptp(v))
            if span > 0:
                counts, _, _ = ax.hist(v, bins=min(12, max(3, len(v) // 2)), range=(v.min() - span * 0.05,
                                       v.max() + span * 0.05), color="#5b8c3a", alpha=0.75, edgecolor="white")
            else:  # every run alike: one bar, the axis wide enough to show it is one value
                width = max(abs(float(v[0])) * 0.1, 0.1)
                counts, _, _ = ax.hist(v, bins=1, range=(v[0] - width / 2, v[0] + width / 2), color="#5b8c3a",
                                       alpha=0.75, edgecolor="white")
                ax.set_xlim(v[0] - 3 * width, v[0] + 3 * width)
            top = max(float(counts.max()), 1.0)
            ax.axvspan(low, high, color="0.5", alpha=0.12, linewidth=0)
            ax.axvline(float(v.mean()), color="#c0392b", linewidth=2.5, label=f"mean {v.mean():.3g}")
            jitter = np.random.default_rng(0).uniform(-0.06, 0.06, len(v)) * top
            ax.scatter(v, -0.15 * top + jitter, s=16, color="#1d4e89", alpha=0.7, linewidths=0, clip_on=False)
            ax.set_ylim(-0.25 * top, top * 1.15)
            ax.yaxis.set_major_locator(matplotlib.ticker.MaxNLocator(integer=True))
            ax.set_yticks([t for t in ax.get_yticks() if 0 <= t <= top * 1.15])
            ax.spines["left"].set_bounds(0, top * 1.15)
            ax.legend(fontsize=10, frameon=False, loc="upper right")
        _title(ax, TITLES.get(response, response))
        _labels(ax, y_label(response) or response, "runs (count)")
        ax.grid(alpha=0.3)
    setting = ", ".join(f"{f.name} = {_text(f.levels[0])}" for f in sweep.factors)
    fig.suptitle(textwrap.fill(f"{sweep.title}: {setting}; final values of {len(sweep.seeds)} seeds after "
                               f"{_duration(sweep.duration, day_seconds)} (bars: histogram; dots: every run; "
                               "line: mean; shade: 10-90 %)", 110), fontsize=16)
    return fig


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
        _title(ax, TITLES.get(response, response))
        _labels(ax, f"time (game days of {day_seconds:.0f} s)", y_label(response))
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=9, frameon=False, title=" x ".join(f.name for f in sweep.factors), title_fontsize=9)
    fig.suptitle(f"{sweep.title}: mean over {len(sweep.seeds)} seeds (band: 10-90 %)", fontsize=16)
    return save_both(fig, path)


def class_figure(sweep, finals: dict, day_seconds: float = 125.66):
    """A class's sweeps in one figure (arbor compare): each response at the end of the runs, every student's
    runs as dots in the student's colour (set a little apart), and the class's mean over every run with its
    10-90 % bar in black (one black line per level of a second factor). ``finals`` maps a student's name to
    their final values ({levels: {response: values over seeds}}). A sweep of one level: the students
    across, each one's runs as a strip."""
    names = list(finals)
    palette = plt.cm.tab10.colors if len(names) <= 10 else plt.cm.tab20.colors
    colors = [palette[n % len(palette)] for n in range(len(names))]
    one = all(len(f.levels) == 1 for f in sweep.factors)
    across, lines = (None, None) if one else _axes_of(sweep)
    x_levels = ("",) if one else sweep.factors[across].levels
    others = (None,) if lines is None or one else sweep.factors[lines].levels
    x, labels = (np.zeros(1), None) if one else _positions(x_levels)
    step = float(np.min(np.diff(np.sort(x)))) if len(x) > 1 else 1.0
    fig, axes = _grid(len(sweep.responses))

    def key(level, other) -> tuple:
        if one:
            return tuple(f.levels[0] for f in sweep.factors)
        k = [None] * len(sweep.factors)
        k[across] = level
        if lines is not None:
            k[lines] = other
        return tuple(k)

    for ax, response in zip(axes, sweep.responses, strict=True):
        for m, other in enumerate(others):
            pooled = []
            for xi, level in zip(x, x_levels, strict=True):
                everyone = []
                for n, (name, color) in enumerate(zip(names, colors, strict=True)):
                    values = finals[name].get(key(level, other), {}).get(response, np.zeros(0))
                    place = n if one else xi + (n - (len(names) - 1) / 2) * step * 0.3 / max(len(names), 1)
                    ax.scatter(np.full(len(values), place), values, s=16, color=color, alpha=0.75, linewidths=0,
                               label=name if (m, xi, response) == (0, x[0], sweep.responses[0]) else None, zorder=3)
                    everyone.extend(values)
                if everyone:
                    v = np.asarray(everyone, dtype=float)
                    pooled.append((xi, v.mean(), *np.percentile(v, [10, 90])))
            if pooled:
                px, mean, low, high = np.array(pooled).T
                if one:
                    ax.axhline(mean[0], color="black", linewidth=2, label="class mean" if response ==
                               sweep.responses[0] else None)
                    ax.axhspan(low[0], high[0], color="0.5", alpha=0.12, linewidth=0)
                else:
                    style = ("-", "--", ":", "-.")[m % 4]
                    tag = "class mean" if other is None else f"class mean, {sweep.factors[lines].name} = {_text(other)}"
                    ax.vlines(px, low, high, color="black", linewidth=2, alpha=0.6)
                    ax.plot(px, mean, style, marker="o", color="black", markersize=5,
                            label=tag if response == sweep.responses[0] else None)
        _limits(ax, response)
        _title(ax, TITLES.get(response, response))
        if one:
            ax.set_xticks(np.arange(len(names)), names, rotation=45 if len(names) > 4 else 0, ha="right"
                          if len(names) > 4 else "center")
            _labels(ax, "student", y_label(response))
        else:
            _labels(ax, axis_label(sweep.factors[across]), y_label(response))
            if labels:
                ax.set_xticks(x, labels)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=9, frameon=False, ncols=2 if len(names) > 6 else 1)
    fig.suptitle(textwrap.fill(f"{sweep.title}: {len(names)} students' runs after "
                               f"{_duration(sweep.duration, day_seconds)} (dots: each student's runs; black: the "
                               "class's mean and 10-90 %)", 110), fontsize=16)
    return fig


DEAD = "#c0392b"  # the colour of a dead tree's mark


def _mark_dead(ax, note: str) -> None:
    """A dead tree's thumbnail: a red cross over the picture's corner and ``note`` (the day of death) below."""
    ax.text(0.96, 0.95, "\u2020", transform=ax.transAxes, ha="right", va="top", fontsize=26, color=DEAD,
            fontweight="bold")
    for side in ax.spines.values():
        side.set_visible(True)
        side.set_color(DEAD)
        side.set_linewidth(3)
    ax.set_xlabel(note, color=DEAD, fontsize=11, fontweight="bold")


def _picture(ax, image, note: str | None) -> None:
    """One thumbnail: the picture without ticks, marked when the tree is dead (``note``: the day of death)."""
    ax.set_xticks([])
    ax.set_yticks([])
    for side in ax.spines.values():
        side.set_visible(False)
    if image is not None:
        ax.imshow(image)
    if note:
        _mark_dead(ax, note)


def thumbnails(sweep, images: dict, path: Path, dead: dict | None = None) -> list[Path]:
    """The final tree of each combination of levels (its first seed), in a grid: first factor across,
    second factor down. ``images`` maps levels -> RGB array; ``dead`` maps the levels of a tree that died
    to the words under it ("died on day 3.2"): it gets a red cross and frame."""
    dead = dead or {}
    across = sweep.factors[0].levels
    down = sweep.factors[1].levels if len(sweep.factors) > 1 else (None,)
    fig, axes = plt.subplots(len(down), len(across), figsize=(2.6 * len(across), 3.4 * len(down)), squeeze=False,
                             layout="constrained")
    for r, other in enumerate(down):
        for c, level in enumerate(across):
            ax = axes[r][c]
            key = (level,) if other is None else (level, other)
            _picture(ax, images.get(key), dead.get(key))
            title = _text(level)
            if other is not None and c == 0:
                title = f"{sweep.factors[1].name} = {_text(other)}\n{title}"
            ax.set_title(title, fontsize=11, fontweight="normal")
    fig.suptitle(textwrap.fill(f"{sweep.title}: final trees (seed {sweep.seeds[0]}); across: {sweep.factors[0].name}"
                               + ("; \u2020 dead" if dead else ""), 90), fontsize=13)
    return save_both(fig, path)


SEED_COLUMNS = 10  # thumbnails in a row of the seeds' grid


def seed_grid(sweep, images: dict, path: Path, dead: dict | None = None) -> list[Path]:
    """Every seed's final tree at one scale, a block of rows per combination of levels (for lessons on
    variation: the same conditions, different seeds). ``images`` maps (levels, seed) -> RGB array; ``dead``
    maps (levels, seed) of a tree that died to the words under it."""
    dead = dead or {}
    combos = list(dict.fromkeys(levels for levels, _ in images))
    seeds = [s for s in sweep.seeds if any((levels, s) in images for levels in combos)]
    cols = min(len(seeds), SEED_COLUMNS)
    per = -(-len(seeds) // cols)  # rows per combination
    fig, axes = plt.subplots(per * len(combos), cols, figsize=(1.9 * cols, 2.6 * per * len(combos)), squeeze=False,
                             layout="constrained")
    for b, levels in enumerate(combos):
        for k, seed in enumerate(seeds):
            ax = axes[b * per + k // cols][k % cols]
            _picture(ax, images.get((levels, seed)), dead.get((levels, seed)))
            ax.set_title(f"seed {seed}", fontsize=10, fontweight="normal")
            if k == 0:
                ax.set_ylabel(textwrap.fill(", ".join(f"{f.name} = {_text(v)}" for f, v in
                                                      zip(sweep.factors, levels, strict=True)), 22), fontsize=10)
        for k in range(len(seeds), per * cols):
            axes[b * per + k // cols][k % cols].axis("off")
    fig.suptitle(textwrap.fill(f"{sweep.title}: every seed's final tree, one scale (metre bar at the left)"
                               + ("; \u2020 dead" if dead else ""), 90), fontsize=13)
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
        _title(ax, TITLES.get(metric, metric))
        _labels(ax, "time (game days)", y_label(metric))
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
    unit = factor_unit(factor)
    return f"{factor.name} ({unit})" if unit and f"({unit})" not in factor.name else factor.name


def factor_unit(factor) -> str:
    """The unit of what a factor varies (the experiment schema's or the rule schema's; "" for species)."""
    if factor.key == "species":
        return ""
    key = FACTOR_KEYS.get(factor.key)
    return key.unit if key else getattr(find_rule(factor.key), "unit", "")


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


def _when(sweep, day_seconds: float) -> str:
    """When the final values were taken: after the runs' length, or at each run's stop when a [stop] table
    ended some runs early (a run's last sample then)."""
    end = f"after {_duration(sweep.duration, day_seconds)}"
    return end if getattr(sweep, "stop", None) is None else f"at each run's stop, or {end}"


def _duration(seconds: float, day_seconds: float) -> str:
    """A run's length in game days (one turn of the sun, ``day_seconds`` of game time)."""
    return f"{seconds / day_seconds:.3g} game days"
