"""Menu and HUD, drawn with pygame into a transparent overlay surface (composited over the 3D view).

The menu (seed 003, 2.4.2) appears at the tap point: a sun-orbit height slider, a sun-speed slider,
the watering can (water while held), the sapling (replant), time speed, save and load. Every touch
target is at least 48 px tall. The HUD shows the yellow sun meter, the blue water meter, the growth
state, the tree's age and messages (budget reached, saved, load problems).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import pygame

from game.strings import text

SUN_YELLOW = (250, 204, 40)
WATER_BLUE = (60, 140, 240)
PANEL = (20, 30, 24, 200)
TEXT = (245, 245, 240)
ACCENT = (120, 190, 90)
ROW_H = 64  # touch targets: >= 48 px
MENU_W = 420
PAD = 10


@dataclass
class Widget:
    """A slider (value 0..1) or a button; ``hold`` buttons act while pressed."""

    name: str
    label: str
    kind: str  # "slider" or "button"
    rect: pygame.Rect = field(default_factory=lambda: pygame.Rect(0, 0, 0, 0))
    value: float = 0.0
    hold: bool = False
    pressed: bool = False


class Menu:
    """The tap menu: layout at a point, hit testing, drag/press handling, drawing."""

    def __init__(self, screen: tuple[int, int]) -> None:
        self.screen = screen
        self.visible = False
        self.widgets = [
            Widget("orbit_height", text("menu.orbit_height"), "slider"),
            Widget("sun_speed", text("menu.sun_speed"), "slider"),
            Widget("water", text("menu.water"), "button", hold=True),
            Widget("replant", text("menu.replant"), "button"),
            Widget("speed", text("menu.speed", speed="1"), "button"),
            *(Widget(name, text(f"menu.{name}"), "button") for name in ("save", "load", "devices", "modeler",
                                                                         "crown", "shape", "prune", "symbols", "undo",
                                                                         "redo",
                                                                         "plant", "next")),
            Widget("edit", text("menu.edit", name=text("edits.add_leaves")), "button"),
        ]
        self.active: Widget | None = None
        self.rect = pygame.Rect(0, 0, MENU_W, 0)

    def widget(self, name: str) -> Widget:
        """The widget called ``name``."""
        return next(w for w in self.widgets if w.name == name)

    def show_at(self, x: float, y: float) -> None:
        """Open the menu with its corner at the tap point, kept inside the screen."""
        rows = [["orbit_height"], ["sun_speed"], ["water", "replant"], ["speed", "save", "load", "devices"],
                ["modeler", "crown", "shape"], ["prune", "symbols", "undo", "redo"], ["edit"], ["plant", "next"]]
        height = len(rows) * (ROW_H + PAD) + PAD
        left = int(min(max(x, PAD), self.screen[0] - MENU_W - PAD))
        top = int(min(max(y, PAD), self.screen[1] - height - PAD))
        self.rect = pygame.Rect(left, top, MENU_W, height)
        for r, names in enumerate(rows):
            width = (MENU_W - PAD * (len(names) + 1)) // len(names)
            for c, name in enumerate(names):
                self.widget(name).rect = pygame.Rect(left + PAD + c * (width + PAD), top + PAD + r * (ROW_H + PAD),
                                                     width, ROW_H)
        self.visible = True

    def hide(self) -> list[tuple[str, float]]:
        """Close the menu; releases a held button (returns the actions that causes)."""
        self.visible = False
        return self.release()

    def hit(self, x: float, y: float) -> Widget | None:
        """The widget under (x, y), if the menu is visible."""
        if not self.visible:
            return None
        return next((w for w in self.widgets if w.rect.collidepoint(x, y)), None)

    def press(self, x: float, y: float) -> list[tuple[str, float]]:
        """Pointer down at (x, y): start dragging a slider or press a button."""
        w = self.hit(x, y)
        self.active = w
        if w is None:
            return []
        w.pressed = True
        if w.kind == "slider":
            return self.drag(x, y)
        if w.hold:
            return [(w.name, 1.0)]
        return [(w.name, 1.0)]

    def drag(self, x: float, y: float) -> list[tuple[str, float]]:
        """Pointer moved while pressed: sliders follow it."""
        w = self.active
        if w is None or w.kind != "slider":
            return []
        inner = w.rect.inflate(-2 * PAD, 0)
        w.value = min(max((x - inner.left) / max(inner.width, 1), 0.0), 1.0)
        return [(w.name, w.value)]

    def release(self) -> list[tuple[str, float]]:
        """Pointer up: a held button stops acting."""
        w, self.active = self.active, None
        if w is None:
            return []
        w.pressed = False
        return [(w.name, 0.0)] if w.hold else []

    def draw(self, surface: pygame.Surface, font: pygame.font.Font) -> None:
        """Draw the menu panel and its widgets."""
        if not self.visible:
            return
        panel = pygame.Surface(self.rect.size, pygame.SRCALPHA)
        panel.fill(PANEL)
        surface.blit(panel, self.rect.topleft)
        for w in self.widgets:
            if w.kind == "slider":
                _draw_slider(surface, font, w)
            else:
                color = (70, 110, 60) if w.pressed else (45, 70, 42)
                pygame.draw.rect(surface, color, w.rect, border_radius=10)
                pygame.draw.rect(surface, ACCENT, w.rect, width=2, border_radius=10)
                label = font.render(w.label, True, TEXT)
                if label.get_width() > w.rect.width - 8:  # shrink long labels to fit their button
                    scale = (w.rect.width - 8) / label.get_width()
                    label = pygame.transform.smoothscale_by(label, scale)
                surface.blit(label, label.get_rect(center=w.rect.center))


def _draw_slider(surface: pygame.Surface, font: pygame.font.Font, w: Widget) -> None:
    pygame.draw.rect(surface, (35, 50, 35), w.rect, border_radius=10)
    label = font.render(w.label, True, TEXT)
    surface.blit(label, (w.rect.left + PAD, w.rect.top + 4))
    inner = w.rect.inflate(-2 * PAD, 0)
    track_y = w.rect.bottom - 16
    pygame.draw.line(surface, (120, 120, 110), (inner.left, track_y), (inner.right, track_y), 4)
    knob_x = inner.left + w.value * inner.width
    pygame.draw.circle(surface, SUN_YELLOW, (int(knob_x), track_y), 12)


@dataclass
class HudInfo:
    """What the HUD shows this frame."""

    sun: float
    water: float
    status: str
    age_seconds: float
    speed: float
    message: str = ""
    watering: bool = False


def draw_hud(surface: pygame.Surface, font: pygame.font.Font, info: HudInfo) -> None:
    """Meters (yellow sun, blue water), growth state, age, speed and the current message."""
    x, y = 20, 20
    for label, value, color in ((text("hud.sun"), info.sun, SUN_YELLOW), (text("hud.water"), info.water, WATER_BLUE)):
        back = pygame.Surface((300, 40), pygame.SRCALPHA)
        back.fill((0, 0, 0, 120))
        surface.blit(back, (x, y))
        pygame.draw.rect(surface, color, (x + 90, y + 8, int(200 * min(max(value, 0.0), 1.0)), 24), border_radius=6)
        pygame.draw.rect(surface, TEXT, (x + 90, y + 8, 200, 24), width=2, border_radius=6)
        pygame.draw.line(surface, TEXT, (x + 190, y + 4), (x + 190, y + 36), 1)  # the half mark
        surface.blit(font.render(label, True, TEXT), (x + 8, y + 6))
        y += 48
    minutes = info.age_seconds / 60
    age = text("hud.minutes", minutes=minutes) if minutes < 120 else text("hud.hours", hours=minutes / 60)
    speed = text("hud.paused") if info.speed == 0 else text("hud.speed", speed=info.speed)
    surface.blit(font.render(text("hud.line", status=info.status, age=age, speed=speed), True, TEXT), (x, y + 4))
    if info.message:
        msg = font.render(info.message, True, TEXT)
        box = msg.get_rect(midbottom=(surface.get_width() // 2, surface.get_height() - 24)).inflate(24, 12)
        back = pygame.Surface(box.size, pygame.SRCALPHA)
        back.fill((0, 0, 0, 150))
        surface.blit(back, box.topleft)
        surface.blit(msg, msg.get_rect(center=box.center))


def draw_polyline(surface: pygame.Surface, project, points, colour, closed: bool, width: int) -> None:
    """A 3D polyline over the scene (``project``: 3D points -> the pixels of those in view)."""
    pixels = project(points)
    if len(pixels) >= (3 if closed else 2):
        pygame.draw.lines(surface, colour, closed, pixels, width)


def draw_rain_cloud(surface: pygame.Surface, center: tuple[float, float], size: float, t: float) -> None:
    """A grey cloud with falling rain, drawn while the watering can is held."""
    cx, cy = center
    for dx, dy, r in ((-0.5, 0.05, 0.32), (0.0, -0.1, 0.42), (0.5, 0.05, 0.3), (0.22, 0.12, 0.3), (-0.2, 0.14, 0.3)):
        pygame.draw.circle(surface, (200, 205, 215, 235), (int(cx + dx * size), int(cy + dy * size)), int(r * size))
    for k in range(14):
        x = cx + (k / 13 - 0.5) * size * 1.2
        phase = (t * 1.7 + k * 0.37) % 1.0
        y0 = cy + size * (0.3 + phase * 1.2)
        pygame.draw.line(surface, (90, 150, 255, 220), (int(x), int(y0)), (int(x - 3), int(y0 + size * 0.12)), 2)


def slider_to_range(value: float, lo: float, hi: float, log: bool = False) -> float:
    """Map a slider position 0..1 onto [lo, hi] (logarithmically for speeds)."""
    if log:
        return math.exp(math.log(lo) + value * (math.log(hi) - math.log(lo)))
    return lo + value * (hi - lo)


def range_to_slider(x: float, lo: float, hi: float, log: bool = False) -> float:
    """Inverse of :func:`slider_to_range`."""
    if log:
        return (math.log(x) - math.log(lo)) / (math.log(hi) - math.log(lo))
    return (x - lo) / (hi - lo)
