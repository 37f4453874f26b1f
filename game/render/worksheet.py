"""Worksheets drawn (arbor worksheet): A4 pages as a PDF (matplotlib) or one printable HTML page (the same
parts, charts as inline SVG, the answer key on a page of its own when printed).

Page 1: the question, a box for the prediction, the setup, an empty chart with the lesson's axes and units
to sketch on; page 2: the discussion questions with lines to write on; page 3: the answer key (the chart
filled in from a real run, the table, what the numbers show).
"""

from __future__ import annotations

import html
import io
import math
import textwrap
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.backends.backend_pdf import PdfPages

A4 = (8.27, 11.69)  # inches
MARGIN = 0.75  # inches
COLORS = ((230, 90, 60), (60, 140, 230), (90, 180, 70), (200, 160, 30), (150, 80, 180), (60, 60, 60))


def nice_top(value: float) -> float:
    """A round number a little above ``value`` (1, 2, 2.5, 5 x a power of ten) for a chart's top."""
    if not value > 0 or not math.isfinite(value):
        return 1.0
    power = 10 ** math.floor(math.log10(value * 1.1))
    return next(k * power for k in (1, 1.2, 1.5, 2, 2.5, 3, 4, 5, 6, 8, 10) if k * power >= value * 1.1)


def _color(k: int):
    return np.array(COLORS[k % len(COLORS)]) / 255.0


def draw_empty(ax, chart, sketch: bool = True) -> None:
    """The chart to sketch on: the lesson's axes, units and ticks, a light grid, no data (with ``sketch``, a
    lab lesson's trees named in a legend, a line each to draw)."""
    ax.set_title(chart.title, fontsize=13, fontweight="bold")
    ax.set_xlabel(chart.x_label, fontsize=11)
    ax.set_ylabel(textwrap.fill(chart.y_label, 34), fontsize=11)
    xs = chart.x_ticks
    pad = (max(xs) - min(xs)) * 0.06 if len(xs) > 1 else 0.5
    ax.set_xlim(min(xs) - pad, max(xs) + pad)
    ax.set_xticks(xs, chart.x_names or [f"{v:g}" for v in xs])
    ax.set_ylim(0, chart.y_top or 1.0)
    ax.yaxis.set_major_locator(matplotlib.ticker.MaxNLocator(8))
    ax.minorticks_on()
    ax.grid(which="major", alpha=0.45)
    ax.grid(which="minor", alpha=0.15)
    if chart.lines and sketch:
        for k, name in enumerate(chart.lines):
            ax.plot([], [], color=_color(k), linewidth=2.5, label=f"{name}: draw its line")
        ax.legend(fontsize=9, frameon=False, loc="upper left")
    for side in ("top", "right"):
        ax.spines[side].set_visible(False)


def draw_key(ax, chart, answer) -> None:
    """The same chart filled in from the run: every run as a dot and the mean as a line (a sweep), or each
    tree's line (a lab)."""
    draw_empty(ax, chart, sketch=False)
    for k, (label, (x, y, spread)) in enumerate(answer.points.items()):
        color = _color(k) if chart.lines else (0.15, 0.35, 0.6)
        if spread:
            for xi, values in zip(x, spread, strict=True):
                ax.scatter(np.full(len(values), xi), values, s=18, color=color, alpha=0.5, linewidths=0)
        ax.plot(x, y, "-o" if spread else "-", color=color, linewidth=2.5, markersize=5,
                label=label if chart.lines else "mean over the seeds (dots: each seed)")
    ax.legend(fontsize=9, frameon=False, loc="upper left")


class Page:
    """An A4 page laid out from the top down: text, boxes and charts at a cursor (inches from the top)."""

    def __init__(self) -> None:
        self.fig = plt.figure(figsize=A4)
        self.y = MARGIN

    def _frac(self, inches: float) -> float:
        return 1.0 - inches / A4[1]

    def text(self, words: str, size: float = 11, bold: bool = False, gap: float = 0.08) -> None:
        """A paragraph, wrapped to the page's width (a character about 0.44 of the type's size wide, on average)."""
        width = int((A4[0] - 2 * MARGIN) * 72 / (size * (0.52 if bold else 0.48)))
        lines = textwrap.wrap(words, width) or [""]
        self.fig.text(MARGIN / A4[0], self._frac(self.y), "\n".join(lines), fontsize=size, va="top",
                      fontweight="bold" if bold else "normal", linespacing=1.35)
        self.y += len(lines) * size * 1.35 / 72 + gap

    def box(self, height: float) -> None:
        """An empty framed box to write in."""
        ax = self.fig.add_axes((MARGIN / A4[0], self._frac(self.y + height), 1 - 2 * MARGIN / A4[0], height / A4[1]))
        ax.set_xticks([])
        ax.set_yticks([])
        self.y += height + 0.15

    def ruled(self, lines: int) -> None:
        """Lines to write on."""
        for _ in range(lines):
            self.y += 0.34
            self.fig.add_artist(plt.Line2D([MARGIN / A4[0], 1 - MARGIN / A4[0]], [self._frac(self.y)] * 2,
                                           color="0.6", linewidth=0.8))
        self.y += 0.2

    def chart(self, height: float):
        """Axes for a chart, ``height`` inches tall (room left for its labels)."""
        left = MARGIN + 0.9
        ax = self.fig.add_axes((left / A4[0], self._frac(self.y + height), 1 - (left + MARGIN) / A4[0],
                                (height - 0.45) / A4[1]))
        self.y += height + 0.6  # (the x axis's ticks and label below the axes)
        return ax

    def table(self, header: list[str], rows: list[list[str]]) -> None:
        """A table of the key's numbers."""
        labels = [textwrap.fill(h, 16) for h in header]
        tall = max(label.count("\n") + 1 for label in labels)
        height = 0.26 * len(rows) + 0.2 * tall + 0.1
        ax = self.fig.add_axes((MARGIN / A4[0], self._frac(self.y + height), 1 - 2 * MARGIN / A4[0], height / A4[1]))
        ax.axis("off")
        table = ax.table(cellText=rows, colLabels=labels, loc="upper center", cellLoc="center")
        table.auto_set_font_size(False)
        table.set_fontsize(9)
        for (row, _), cell in table.get_celld().items():
            cell.set_height((0.2 * tall + 0.06 if row == 0 else 0.26) / height)
        self.y += height + 0.35


def page_figures(sheet, setup: list[str], chart, answer, lesson: str) -> list:
    """The worksheet's three A4 pages as matplotlib figures."""
    title = f"Lesson: {sheet.name}"
    first = Page()
    first.text(title, 18, bold=True, gap=0.05)
    first.text("Name: ______________________________     Date: ______________", 11, gap=0.2)
    first.text("Question", 13, bold=True, gap=0.02)
    first.text(sheet.question, gap=0.2)
    first.text("My prediction", 13, bold=True, gap=0.02)
    first.text(sheet.predict, gap=0.05)
    first.box(1.5)
    first.text("The experiment", 13, bold=True, gap=0.02)
    for line in setup:
        first.text(f"- {line}", 10, gap=0.02)
    first.text(f"Run it: arbor {'lab' if chart.lines else 'sweep'} {lesson} --out results/{sheet.name}", 10,
               gap=0.15)
    draw_empty(first.chart(min(4.2, A4[1] - MARGIN - first.y)), chart)
    second = Page()
    second.text(f"{title}: discussion", 15, bold=True, gap=0.2)
    for k, question in enumerate(sheet.discuss, 1):
        second.text(f"{k}. {question}", 11, gap=0.02)
        second.ruled(5)
    key = Page()
    key.text(f"{title}: answer key", 15, bold=True, gap=0.02)
    key.text(f"From a real run of the lesson: {answer.run}.", 10, gap=0.15)
    draw_key(key.chart(4.0), chart, answer)
    key.table(answer.header, answer.rows)
    key.text("What the run shows", 13, bold=True, gap=0.02)
    for sentence in answer.sentences:
        key.text(f"- {sentence}", 10, gap=0.03)
    return [first.fig, second.fig, key.fig]


def _svg(draw, *args) -> str:
    """A chart drawn by ``draw`` as inline SVG text."""
    fig, ax = plt.subplots(figsize=(6.6, 3.8), layout="constrained")
    draw(ax, *args)
    buf = io.StringIO()
    with plt.rc_context({"svg.fonttype": "none"}):  # the labels as text: read by a screen reader, found by a search
        fig.savefig(buf, format="svg", metadata={"Date": None})
    plt.close(fig)
    text = buf.getvalue()
    return text[text.index("<svg"):]


CSS = """body { font-family: sans-serif; max-width: 48em; margin: 2em auto; line-height: 1.45; color: #111; }
h1 { margin-bottom: 0.2em; } h2 { margin: 1.2em 0 0.3em; font-size: 1.2em; }
.box { border: 2px solid #333; min-height: 9em; margin: 0.5em 0 1em; }
.line { border-bottom: 1px solid #999; height: 2em; }
table { border-collapse: collapse; margin: 1em 0; } td, th { border: 1px solid #888; padding: 0.25em 0.7em; }
.page { page-break-before: always; break-before: page; }
svg { max-width: 100%; height: auto; }
@page { size: A4; margin: 18mm; }"""


def sheet_html(sheet, setup: list[str], chart, answer, lesson: str) -> str:
    """The worksheet as one HTML page (print it: the discussion and the answer key start pages of their own)."""
    e = html.escape
    title = f"Lesson: {sheet.name}"
    command = f"arbor {'lab' if chart.lines else 'sweep'} {lesson} --out results/{sheet.name}"
    parts = [f"<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><title>{e(title)}</title>"
             f"<style>{CSS}</style></head><body>",
             f"<h1>{e(title)}</h1><p>Name: ______________________ &nbsp; Date: __________</p>",
             f"<h2>Question</h2><p>{e(sheet.question)}</p>",
             f"<h2>My prediction</h2><p>{e(sheet.predict)}</p><div class='box' aria-label='your prediction'></div>",
             "<h2>The experiment</h2><ul>" + "".join(f"<li>{e(line)}</li>" for line in setup) + "</ul>",
             f"<p>Run it: <code>{e(command)}</code></p>",
             f"<figure aria-label='an empty chart to sketch on'>{_svg(draw_empty, chart)}</figure>",
             "<section class='page'><h2>Discussion</h2><ol>"
             + "".join(f"<li>{e(q)}" + "<div class='line'></div>" * 4 + "</li>" for q in sheet.discuss)
             + "</ol></section>",
             f"<section class='page'><h2>Answer key</h2><p>From a real run of the lesson: {e(answer.run)}.</p>",
             f"<figure>{_svg(draw_key, chart, answer)}</figure>",
             "<table><tr>" + "".join(f"<th>{e(h)}</th>" for h in answer.header) + "</tr>"
             + "".join("<tr>" + "".join(f"<td>{e(c)}</td>" for c in row) + "</tr>" for row in answer.rows)
             + "</table>",
             "<h2>What the run shows</h2><ul>" + "".join(f"<li>{e(s)}</li>" for s in answer.sentences) + "</ul>",
             "</section></body></html>\n"]
    return "\n".join(parts)


def write(out: Path, sheet, setup: list[str], chart, answer, lesson: str) -> list[Path]:
    """Write the worksheet to ``out``: a three-page PDF, or one HTML page."""
    from arbor.engine.base.files import atomic_write

    if out.suffix.lower() == ".html":
        atomic_write(out, sheet_html(sheet, setup, chart, answer, lesson).encode("utf-8"))
        return [out]
    figures = page_figures(sheet, setup, chart, answer, lesson)
    buf = io.BytesIO()
    with PdfPages(buf, metadata={"Title": f"Arbor worksheet: {sheet.name}", "CreationDate": None}) as pdf:
        for fig in figures:
            pdf.savefig(fig)
            plt.close(fig)
    atomic_write(out, buf.getvalue())
    return [out]
