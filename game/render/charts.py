"""Live line charts of lab time series, drawn with pygame in the lab screen (exports: figures.py).

Small multiples: one panel per measurement, one coloured line per tree, with a shared legend; the line of
a tree that died ends in a cross (its day of death). Thick lines and large type so a class can read
them on a projector.
"""

from __future__ import annotations

import pygame

COLORS = ((230, 90, 60), (60, 140, 230), (90, 180, 70), (200, 160, 30))
TITLES = {"height": "Height (m)", "girth": "Trunk girth (cm)", "modules": "Modules", "leaves": "Leaves",
          "sun": "Sun meter", "water": "Water meter", "wilt": "Wilt (0..1)", "leaf_area": "Leaf area (m²)",
          "light_share": "Light on the leaves (0..1)", "biomass": "Biomass (kg)"}
BACK, GRID, INK = (250, 250, 246), (215, 215, 205), (40, 40, 36)


def _nice(value: float) -> str:
    if value >= 1000:
        return f"{value / 1000:.1f}k"
    return f"{value:.2g}" if value < 10 else f"{value:.0f}"


def draw_panel(surface: pygame.Surface, rect: pygame.Rect, metric: str, series: list, font: pygame.font.Font,
               small: pygame.font.Font) -> None:
    """One chart: a metric over time for every tree."""
    pygame.draw.rect(surface, BACK, rect)
    surface.blit(font.render(TITLES.get(metric, metric), True, INK), (rect.left + 10, rect.top + 4))
    plot = pygame.Rect(rect.left + 64, rect.top + 40, rect.width - 80, rect.height - 76)
    values = [v for s in series for v in s.values[metric]]
    times = [t for s in series for t in s.time]
    if not values or len(times) < 2:
        return
    top = max(max(values), 1e-9) * 1.05
    if metric in ("sun", "water", "wilt", "light_share"):
        top = 1.0
    t_end = max(times) or 1.0
    for k in range(5):
        y = plot.bottom - plot.height * k / 4
        pygame.draw.line(surface, GRID, (plot.left, y), (plot.right, y), 1)
        label = small.render(_nice(top * k / 4), True, INK)
        surface.blit(label, (plot.left - label.get_width() - 6, y - label.get_height() // 2))
    days = [d for s in series for d in s.day]
    minutes = small.render(f"day {max(days):.0f}" if days else f"{t_end / 60:.0f} min", True, INK)
    surface.blit(minutes, (plot.right - minutes.get_width(), plot.bottom + 4))
    surface.blit(small.render("0", True, INK), (plot.left, plot.bottom + 4))
    for i, s in enumerate(series):
        pts = [(plot.left + plot.width * t / t_end, plot.bottom - plot.height * min(v / top, 1.0))
               for t, v in zip(s.time, s.values[metric], strict=True)]
        if len(pts) > 1:
            pygame.draw.lines(surface, COLORS[i % len(COLORS)], False, pts, 4)
        dead = [k for k, alive in enumerate(s.values.get("alive", ())) if not alive]
        if dead and dead[0] < len(pts):  # the line of a tree that died ends in a cross, as in the export
            draw_cross(surface, pts[dead[0]], COLORS[i % len(COLORS)])


def draw_cross(surface: pygame.Surface, at: tuple[float, float], color, arm: int = 11) -> None:
    """An X centred on ``at``: where a tree's line shows that it died."""
    x, y = at
    pygame.draw.line(surface, color, (x - arm, y - arm), (x + arm, y + arm), 5)
    pygame.draw.line(surface, color, (x - arm, y + arm), (x + arm, y - arm), 5)


def draw_charts(surface: pygame.Surface, rect: pygame.Rect, series: list,
                metrics=("height", "girth", "leaf_area", "light_share", "water", "wilt")) -> None:
    """All panels in a grid inside ``rect``, with a legend on top."""
    pygame.font.init()
    font, small = pygame.font.Font(None, 34), pygame.font.Font(None, 26)
    legend_h = 40
    x = rect.left + 10
    for i, s in enumerate(series):
        pygame.draw.rect(surface, COLORS[i % len(COLORS)], (x, rect.top + 12, 28, 16))
        label = font.render(s.name, True, INK)
        surface.blit(label, (x + 36, rect.top + 6))
        x += 36 + label.get_width() + 30
    cols = 3
    rows = (len(metrics) + cols - 1) // cols
    w, h = rect.width // cols, (rect.height - legend_h) // rows
    for k, metric in enumerate(metrics):
        panel = pygame.Rect(rect.left + (k % cols) * w + 4, rect.top + legend_h + (k // cols) * h + 4, w - 8, h - 8)
        draw_panel(surface, panel, metric, series, font, small)
