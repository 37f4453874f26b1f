"""Menu and HUD, drawn with pygame into a transparent overlay surface (composited over the 3D view).

The menu (the tamagotchi thesis, 2.4.2) appears at the tap point: a sun-orbit height slider, a sun-speed slider,
the watering can (water while held), the sapling (replant), time speed, save and load. Every touch
target is at least 48 px tall. The HUD shows the yellow sun meter, the blue water meter, the growth
state, the tree's age and messages (budget reached, saved, load problems).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import pygame

from arbor.engine.life.world.actions import Action
from arbor.game.render.icons import draw_icon
from arbor.game.strings import text

SUN_YELLOW = (250, 204, 40)
WATER_BLUE = (60, 140, 240)
PANEL = (20, 30, 24, 200)
TEXT = (245, 245, 240)
ACCENT = (120, 190, 90)
LIT, LIT_TEXT = (250, 204, 40), (30, 35, 20)  # the active tool's button: yellow, dark label
ROW_H = 64  # touch targets: >= 48 px
JOURNAL_LINE = 26
MENU_W = 420
PAD = 10


@dataclass
class Widget:
    """A slider (value 0..1) or a button on one page of the menu; ``hold`` buttons act while pressed. Its
    ``action`` is what it does (none for the buttons that only turn the page)."""

    name: str
    label: str
    kind: str  # "slider" or "button"
    page: str = "care"
    icon: str = ""
    rect: pygame.Rect = field(default_factory=lambda: pygame.Rect(0, 0, 0, 0))
    value: float = 0.0
    hold: bool = False
    pressed: bool = False
    action: Action | None = field(init=False)

    def __post_init__(self) -> None:
        self.action = None if self.name in NAV else Action(self.name)


# Pages of the menu, row by row. The first page is for caring (big targets with icons); the garden,
# the modeler's tools, settings and the journal are one tap further.
PAGES = {
    "care": [["orbit_height"], ["sun_speed"], ["water", "speed"], ["garden", "tools", "settings", "journal"]],
    "garden": [["plant", "species"], ["sow", "cross"], ["family", "next"], ["replant", "rock"], ["import", "back"]],
    "tools": [["modeler", "crown", "shape"], ["prune", "symbols", "edit"], ["undo", "redo", "back"]],
    "settings": [["save", "load", "share"], ["restore", "roots", "devices"], ["volume"], ["away", "gardener"],
                 ["mute", "back"]],
    "journal": [["back"]],
}
ICONS = {"orbit_height": "sun", "sun_speed": "clock", "water": "can", "speed": "clock", "garden": "sapling",
         "tools": "pencil", "settings": "gear", "journal": "book", "plant": "sapling", "sow": "seed",
         "replant": "sapling", "back": "back", "modeler": "pencil", "cross": "seed", "family": "book",
         "roots": "sapling", "rock": "stone", "volume": "speaker", "mute": "speaker",
         "away": "can", "gardener": "can", "share": "card", "import": "card"}
NAV = {"garden", "tools", "settings", "journal", "back"}  # buttons that only change the page


class Menu:
    """The tap menu: pages of widgets laid out at a point, hit testing, drag/press handling, drawing."""

    def __init__(self, screen: tuple[int, int]) -> None:
        self.screen = screen
        self.visible = False
        self.page = "care"
        self.presses = 0  # widgets pressed so far (the click sound follows it: game/audio)
        self.journal_lines: list[str] = []
        self.journal_source = None  # () -> the journal page's lines, asked each time the page opens
        self.on_toggle: Callable[[bool], None] | None = None  # told when it opens (True) and closes (False)
        names = {name for rows in PAGES.values() for row in rows for name in row}
        page_of = {name: page for page, rows in PAGES.items() for row in rows for name in row if name != "back"}
        self.widgets = [
            Widget("orbit_height", text("menu.orbit_height"), "slider", icon="sun"),
            Widget("sun_speed", text("menu.sun_speed"), "slider", icon="clock"),
            Widget("volume", text("menu.volume"), "slider", "settings", icon="speaker"),
            Widget("water", text("menu.water"), "button", hold=True, icon="can"),
            Widget("speed", text("menu.speed", speed="1"), "button", icon="clock"),
            *(Widget(name, text(f"menu.{name}"), "button", page_of.get(name, "care"), ICONS.get(name, ""))
              for name in sorted(names - {"orbit_height", "sun_speed", "volume", "water", "speed", "edit", "sow",
                                          "species"})),
            Widget("sow", text("menu.sow", count=0), "button", "garden", "seed"),
            Widget("species", text("menu.species", name=text("menu.species_own")), "button", "garden", "sapling"),
            Widget("edit", text("menu.edit", name=text("edits.add_leaves")), "button", "tools"),
        ]
        self.active: Widget | None = None
        self.lit: set[str] = set()  # buttons drawn lit: the modeler's tool in use
        self.rect = pygame.Rect(0, 0, MENU_W, 0)
        self._at = (0.0, 0.0)

    def widget(self, name: str) -> Widget:
        """The widget called ``name``."""
        return next(w for w in self.widgets if w.name == name)

    def shown(self) -> list[Widget]:
        """The widgets on the page being shown."""
        names = {n for row in PAGES[self.page] for n in row}
        return [w for w in self.widgets if w.name in names]

    def reveal(self, name: str) -> Widget:
        """Open the page that holds widget ``name`` (where the menu is) and return the widget."""
        page = next(p for p, rows in PAGES.items() if any(name in row for row in rows))
        self.show_at(*self._at, page)
        return self.widget(name)

    def show_at(self, x: float, y: float, page: str | None = None) -> None:
        """Open the menu (on ``page``, else the care page) with its corner at the tap point, kept inside
        the screen."""
        self.page = page or "care"
        self._at = (x, y)
        rows = PAGES[self.page]
        if self.page == "journal" and self.journal_source is not None:
            self.journal_lines = list(self.journal_source())
        extra = (len(self.journal_lines) * JOURNAL_LINE + PAD) if self.page == "journal" else 0
        height = len(rows) * (ROW_H + PAD) + PAD + extra
        left = int(min(max(x, PAD), self.screen[0] - MENU_W - PAD))
        top = int(min(max(y, PAD), self.screen[1] - height - PAD))
        self.rect = pygame.Rect(left, top, MENU_W, height)
        for w in self.widgets:
            w.rect = pygame.Rect(0, 0, 0, 0)
        for r, names in enumerate(rows):
            width = (MENU_W - PAD * (len(names) + 1)) // len(names)
            for c, name in enumerate(names):
                self.widget(name).rect = pygame.Rect(left + PAD + c * (width + PAD),
                                                     top + PAD + extra + r * (ROW_H + PAD), width, ROW_H)
        opened, self.visible = not self.visible, True
        if opened and self.on_toggle is not None:
            self.on_toggle(True)

    def hide(self) -> list[tuple[Action, float]]:
        """Close the menu; releases a held button (returns the actions that causes)."""
        closed, self.visible = self.visible, False
        if closed and self.on_toggle is not None:
            self.on_toggle(False)
        return self.release()

    def hit(self, x: float, y: float) -> Widget | None:
        """The widget under (x, y), if the menu is visible."""
        if not self.visible:
            return None
        return next((w for w in self.shown() if w.rect.collidepoint(x, y)), None)

    def press(self, x: float, y: float) -> list[tuple[Action, float]]:
        """Pointer down at (x, y): start dragging a slider, press a button or turn the page."""
        w = self.hit(x, y)
        self.active = w
        if w is None:
            return []
        self.presses += 1
        if w.name in NAV:
            self.active = None
            self.show_at(*self._at, "care" if w.name == "back" else w.name)
            return []
        w.pressed = True
        if w.kind == "slider":
            return self.drag(x, y)
        return [(w.action, 1.0)]

    def drag(self, x: float, y: float) -> list[tuple[Action, float]]:
        """Pointer moved while pressed: sliders follow it."""
        w = self.active
        if w is None or w.kind != "slider":
            return []
        inner = w.rect.inflate(-2 * PAD, 0)
        w.value = min(max((x - inner.left) / max(inner.width, 1), 0.0), 1.0)
        return [(w.action, w.value)]

    def release(self) -> list[tuple[Action, float]]:
        """Pointer up: a held button stops acting."""
        w, self.active = self.active, None
        if w is None:
            return []
        w.pressed = False
        return [(w.action, 0.0)] if w.hold else []

    def draw(self, surface: pygame.Surface, font: pygame.font.Font) -> None:
        """Draw the menu panel and the widgets of its page (icons beside the labels)."""
        if not self.visible:
            return
        panel = pygame.Surface(self.rect.size, pygame.SRCALPHA)
        panel.fill(PANEL)
        surface.blit(panel, self.rect.topleft)
        if self.page == "journal":
            y = self.rect.top + PAD
            for line in self.journal_lines:
                label = font.render(line, True, TEXT)
                if label.get_width() > MENU_W - 2 * PAD:
                    label = pygame.transform.smoothscale_by(label, (MENU_W - 2 * PAD) / label.get_width())
                surface.blit(label, (self.rect.left + PAD, y))
                y += JOURNAL_LINE
        for w in self.shown():
            if w.kind == "slider":
                _draw_slider(surface, font, w)
            else:
                draw_button(surface, font, w, lit=w.name in self.lit)


def draw_button(surface: pygame.Surface, font: pygame.font.Font, w: Widget, lit: bool = False) -> None:
    """A menu or tool bar button: its icon and label (shrunk to fit); ``lit`` (the tool in use) fills it
    yellow with a white rim, so the active tool stands out at a glance."""
    color = LIT if lit else (70, 110, 60) if w.pressed else (45, 70, 42)
    pygame.draw.rect(surface, color, w.rect, border_radius=10)
    pygame.draw.rect(surface, TEXT if lit else ACCENT, w.rect, width=4 if lit else 2, border_radius=10)
    room = w.rect.inflate(-8, -8)
    if w.icon:
        box = pygame.Rect(room.left, room.top, room.height, room.height)
        draw_icon(surface, w.icon, box)
        room.width -= room.height
        room.left = box.right
    label = font.render(w.label, True, LIT_TEXT if lit else TEXT)
    if label.get_width() > room.width:  # shrink long labels to fit their button
        label = pygame.transform.smoothscale_by(label, room.width / label.get_width())
    surface.blit(label, label.get_rect(center=room.center))


BAR_W, BAR_H, BAR_GAP = 160, 56, 6  # the modeler's tool bar: touch targets >= 48 px
BAR_TOOLS = ("draw", "crown", "shape", "prune", "symbols")


class ToolBar:
    """The modeler's tool bar down the right edge of the screen: one touch-sized button per tool (the one
    in use lit), under them the option of that tool (the lobe operation of Shape, the region edit of
    Symbols; none for the others), then Undo, Redo and Done. Like the menu it acts when a button is pressed;
    every button is an :class:`Action` for the one dispatcher (game/screens/care.py)."""

    def __init__(self, screen: tuple[int, int]) -> None:
        self.screen = screen
        self.visible = False  # (in the modeler only)
        self.tool = "draw"  # the tool in use: one of BAR_TOOLS
        self.option = ""  # the option button's label ('' when the tool has none)
        names = (*BAR_TOOLS, "edit", "undo", "redo", "modeler")
        self.widgets = {name: Widget(name, text(f"menu.{name}"), "button", "bar") for name in names}
        self.widgets["modeler"].label = text("menu.modeler_done")
        self.active: Widget | None = None
        self.layout()

    def show(self, visible: bool, tool: str, option: str = "") -> None:
        """Show the bar (or not) with ``tool`` lit and ``option`` as its option button ('' hides it)."""
        self.visible, self.tool, self.option = visible, tool, option
        self.widgets["edit"].label = option
        self.layout()

    def shown(self) -> list[Widget]:
        """The buttons on the bar now, top to bottom."""
        names = [*BAR_TOOLS, *(["edit"] if self.option else []), "undo", "redo", "modeler"]
        return [self.widgets[name] for name in names]

    def layout(self) -> None:
        """Place the buttons in a column at the right edge: the tools, a gap, the option, a gap, Undo
        and Redo, a gap, Done."""
        x, y = self.screen[0] - BAR_W - PAD, PAD + 6
        for w in self.widgets.values():
            w.rect = pygame.Rect(0, 0, 0, 0)
        for w in self.shown():
            if w.name in ("edit", "undo", "modeler"):
                y += 2 * BAR_GAP  # (groups: tools, their option, history, leaving)
            w.rect = pygame.Rect(x, y, BAR_W, BAR_H)
            y += BAR_H + BAR_GAP

    @property
    def rect(self) -> pygame.Rect:
        """The bar's panel: round all its buttons."""
        rects = [w.rect for w in self.shown()]
        return rects[0].unionall(rects[1:]).inflate(PAD, PAD)

    def over(self, x: float, y: float) -> bool:
        """Whether (x, y) is on the bar's panel while it is shown (a press there never draws a stroke)."""
        return self.visible and self.rect.collidepoint(x, y)

    def hit(self, x: float, y: float) -> Widget | None:
        """The button under (x, y) while the bar is shown."""
        if not self.over(x, y):
            return None
        return next((w for w in self.shown() if w.rect.collidepoint(x, y)), None)

    def press(self, x: float, y: float) -> list[tuple[Action, float]]:
        """Pointer down at (x, y): the action of the button there (value 1), if any."""
        self.active = w = self.hit(x, y)
        if w is None:
            return []
        w.pressed = True
        return [(w.action, 1.0)]

    def release(self) -> None:
        """Pointer up: the pressed button is let go (bar buttons act on the press)."""
        if self.active is not None:
            self.active.pressed = False
        self.active = None

    def key(self) -> tuple:
        """What the bar shows (the HUD repaints when it changes)."""
        return self.visible, self.tool, self.option, self.active.name if self.active else ""

    def draw(self, surface: pygame.Surface, font: pygame.font.Font) -> None:
        """The panel and its buttons, the tool in use lit."""
        if not self.visible:
            return
        _shade(surface, self.rect, 150, (20, 30, 24))
        for w in self.shown():
            draw_button(surface, font, w, lit=w.name == self.tool)


def _draw_slider(surface: pygame.Surface, font: pygame.font.Font, w: Widget) -> None:
    pygame.draw.rect(surface, (35, 50, 35), w.rect, border_radius=10)
    left = w.rect.left + PAD
    if w.icon:
        draw_icon(surface, w.icon, pygame.Rect(left, w.rect.top + 4, 30, 30))
        left += 36
    label = font.render(w.label, True, TEXT)
    surface.blit(label, (left, w.rect.top + 4))
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
    season: str = ""  # e.g. "Summer, day 3" ('' without seasons)
    raining: bool = False
    hint: str = ""  # a first-run hint, shown large at the top
    reminder: str = ""  # one calm line about what is worth doing now
    height_m: float = 0.0  # the tree's height, the top of its wood (engine.geometry.tree.tree_height; 0: none)
    speed_note: str = ""  # after the speed: a new garden's faster first day, while it lasts ('' otherwise)
    need: float = 0.0  # the meters' need line (0..1; 0: none): the hints and the fast-forward's stops start below it


def draw_hud(surface: pygame.Surface, font: pygame.font.Font, info: HudInfo) -> None:
    """Meters (yellow sun, blue water), season, what the tree needs, age and speed, a reminder and a
    first-run hint (the message is :func:`draw_toast`'s, over the menu)."""
    x, y = 20, 20
    for label, value, color in ((text("hud.sun"), info.sun, SUN_YELLOW), (text("hud.water"), info.water, WATER_BLUE)):
        _shade(surface, pygame.Rect(x, y, 300, 40), 120)
        pygame.draw.rect(surface, color, (x + 90, y + 8, int(200 * min(max(value, 0.0), 1.0)), 24), border_radius=6)
        pygame.draw.rect(surface, TEXT, (x + 90, y + 8, 200, 24), width=2, border_radius=6)
        pygame.draw.line(surface, TEXT, (x + 190, y + 4), (x + 190, y + 36), 1)  # the half mark
        if info.need > 0:  # a notch under the bar where the hints and the fast-forward's stops begin
            at = x + 90 + int(200 * min(info.need, 1.0))
            pygame.draw.polygon(surface, TEXT, [(at, y + 31), (at - 5, y + 38), (at + 5, y + 38)])
        surface.blit(font.render(label, True, TEXT), (x + 8, y + 6))
        y += 48
    width = surface.get_width() - 2 * x
    if info.season:
        season = info.season + (" - " + text("hud.raining") if info.raining else "")
        y = _text_lines(surface, font, season, (x, y + 4), width)
    if info.status:
        y = _text_lines(surface, font, info.status, (x, y + 4), width)
    minutes = info.age_seconds / 60
    age = (text("hud.minutes", minutes=minutes) if minutes < 120 else text("hud.hours", hours=minutes / 60)
           if minutes < 2880 else text("hud.days", days=minutes / 1440))
    speed = text("hud.paused") if info.speed == 0 else text("hud.speed", speed=info.speed)
    if info.speed_note:
        speed += " - " + info.speed_note
    line = text("hud.line", age=age, speed=speed)
    if info.height_m > 0:
        line = text("hud.tall", metres=info.height_m) + " - " + line
    y = _text_lines(surface, font, line, (x, y + 4), width)
    if info.reminder:
        _boxed(surface, font, info.reminder, (x, y + 10), width, (20, 40, 25, 150), anchor="topleft")
    if info.hint:
        _boxed(surface, font, info.hint, (surface.get_width() // 2, 24), min(width, 640), (60, 50, 10, 215),
               anchor="midtop", border=SUN_YELLOW)


def draw_toast(surface: pygame.Surface, font: pygame.font.Font, message: str) -> None:
    """The current message, boxed at the bottom centre; drawn after the menu so it is never hidden."""
    if message:
        width = surface.get_width() - 40
        _boxed(surface, font, message, (surface.get_width() // 2, surface.get_height() - 24), width,
               (0, 0, 0, 190), anchor="midbottom")


def _shade(surface: pygame.Surface, rect: pygame.Rect, alpha: int, colour=(0, 0, 0)) -> None:
    back = pygame.Surface(rect.size, pygame.SRCALPHA)
    back.fill((*colour, alpha))
    surface.blit(back, rect.topleft)


def _wrap(font: pygame.font.Font, line: str, width: int) -> list[str]:
    """Words of ``line`` in rows no wider than ``width`` pixels."""
    rows: list[str] = []
    for word in line.split():
        if rows and font.size(rows[-1] + " " + word)[0] <= width:
            rows[-1] += " " + word
        else:
            rows.append(word)
    return rows or [""]


def _text_lines(surface: pygame.Surface, font: pygame.font.Font, line: str, at: tuple[int, int], width: int) -> int:
    """Draw ``line`` wrapped to ``width`` with a soft shadow; returns the y below it."""
    x, y = at
    for row in _wrap(font, line, width):
        surface.blit(font.render(row, True, (0, 0, 0)), (x + 1, y + 1))
        surface.blit(font.render(row, True, TEXT), (x, y))
        y += font.get_linesize()
    return y


def _boxed(surface: pygame.Surface, font: pygame.font.Font, line: str, at: tuple[int, int], width: int,
           fill: tuple, anchor: str, border: tuple | None = None) -> None:
    """``line`` wrapped in a rounded box placed by ``anchor`` at ``at``."""
    rows = _wrap(font, line, width - 24)
    size = (max(font.size(r)[0] for r in rows) + 24, len(rows) * font.get_linesize() + 12)
    box = pygame.Rect((0, 0), size)
    setattr(box, anchor, at)
    pygame.draw.rect(surface, fill, box, border_radius=10)
    if border:
        pygame.draw.rect(surface, border, box, width=2, border_radius=10)
    for k, row in enumerate(rows):
        label = font.render(row, True, TEXT)
        surface.blit(label, label.get_rect(midtop=(box.centerx, box.top + 6 + k * font.get_linesize())))


def draw_joint(surface: pygame.Surface, project, point) -> None:
    """The joint point where the stroke being drawn will join the tree (Onishi et al. 2003 shows it)."""
    for x, y in project(np.asarray(point, float)[None]):
        pygame.draw.circle(surface, (255, 225, 90, 240), (int(x), int(y)), 11, 3)
        pygame.draw.circle(surface, (255, 225, 90, 240), (int(x), int(y)), 3)


def draw_rain(surface: pygame.Surface, t: float) -> None:
    """A shower over the whole view: slanted streaks that fall (deterministic in ``t``)."""
    w, h = surface.get_size()
    rng = np.random.default_rng(7)
    xs, phase = rng.uniform(0, w + h * 0.3, 160), rng.uniform(0, 1, 160)
    y = ((phase + t * 1.4) % 1.0) * (h + 60) - 30
    x = xs - y * 0.3
    for x0, y0 in zip(x, y, strict=True):
        pygame.draw.line(surface, (200, 215, 235, 150), (x0, y0), (x0 - 6, y0 + 22), 1)


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
