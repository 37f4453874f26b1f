"""The crown panel of the modeler (issue 48's parameter panel with presets): with the Crown tool, its option
button (under the tools) opens a panel down the left of the screen with the crown's presets and options
(assets/crowns.toml: each with its default, range, step, unit and meaning; engine/modeling/crown_style.py).
A press on the preset row takes the next preset; - and + move an option by its step. Each change regrows
the crown into its lobes as one undoable step (the world's Crown command with the style); with no
lobes drawn yet it is how the next crown will grow. The meaning of the option last changed is shown
under the panel."""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import pygame

from arbor.engine.life.world.commands import Crown
from arbor.engine.modeling.crown_style import DEFAULT_STYLE, CrownStyle, load_styles, stepped
from arbor.game.render.ui import ACCENT, PAD, TEXT, _shade, _wrap, draw_button
from arbor.game.strings import text
from arbor.game.tools.told import counted

PANEL_X, PANEL_Y, PANEL_W = 16, 170, 360  # pixels: under the meters, at the left edge
ROW, BUTTON = 52, 48  # a row's height and the -/+ buttons' size (touch targets >= 48 px)


@dataclass
class PanelButton:
    """A button of the panel (drawn as the tool bar's are)."""

    label: str
    rect: pygame.Rect = field(default_factory=lambda: pygame.Rect(0, 0, 0, 0))
    icon: str = ""
    pressed: bool = False


class CrownPanel:
    """The crown panel of one modeling mode (see module docstring)."""

    def __init__(self, mode) -> None:
        self.mode = mode
        self.visible = False
        self.options, self.presets = load_styles()
        self.preset = next(iter(self.presets), "")
        self.told = ""  # the meaning of the option last changed
        self.buttons: dict[tuple[str, str], PanelButton] = {}
        self.layout()

    def layout(self) -> None:
        """The preset row, then a row per option with its - and + buttons."""
        self.buttons = {("preset", ""): PanelButton("")}
        self.buttons[("preset", "")].rect = pygame.Rect(PANEL_X + PAD, PANEL_Y + PAD, PANEL_W - 2 * PAD, BUTTON)
        for k, name in enumerate(self.options, 1):
            y = PANEL_Y + PAD + k * ROW
            for j, sign in enumerate(("minus", "plus")):
                w = PanelButton("-" if sign == "minus" else "+")
                w.rect = pygame.Rect(PANEL_X + PANEL_W - PAD - (2 - j) * (BUTTON + 6), y, BUTTON, BUTTON)
                self.buttons[(sign, name)] = w

    @property
    def rect(self) -> pygame.Rect:
        """The panel: round its rows."""
        return pygame.Rect(PANEL_X, PANEL_Y, PANEL_W, PAD * 2 + (len(self.options) + 1) * ROW)

    def style(self) -> CrownStyle:
        """The style the crown grew with (else the one chosen for the next crown, else the defaults)."""
        crown = self.mode.state.world.crown
        if crown is not None and crown.style is not None:
            return crown.style
        return self.mode.crown_tool.style or self.presets.get(self.preset, DEFAULT_STYLE)

    def over(self, x: float, y: float) -> bool:
        """Whether (x, y) is on the panel while it is shown (a press there never draws)."""
        return self.visible and self.rect.collidepoint(x, y)

    def press(self, x: float, y: float) -> bool:
        """A press on the panel: the next preset, or an option one step down or up. True: on a button."""
        hit = next((key for key, w in self.buttons.items() if w.rect.collidepoint(x, y)), None)
        if hit is None:
            return False
        sign, name = hit
        if sign == "preset":
            names = list(self.presets)
            self.preset = names[(names.index(self.preset) + 1) % len(names)] if self.preset in names else names[0]
            self.told = text("crown_panel.preset_meaning", name=self.preset)
            self._apply(self.presets[self.preset], text("crown_panel.preset", name=self.preset))
            return True
        option = self.options[name]
        style = stepped(self.style(), option, -1 if sign == "minus" else 1)
        self.told = option.meaning
        value = getattr(style, name)
        self._apply(style, text("crown_panel.changed", option=text(f"crown_panel.{name}"), value=value,
                                unit=option.unit))
        return True

    def _apply(self, style: CrownStyle, what: str) -> None:
        """Grow the crown again with ``style`` (one undoable step), or keep it for the next crown."""
        mode = self.mode
        mode.crown_tool.style = style
        state = mode.crown_tool.state()
        if not state.lobes:
            mode.state.say(text("crown_panel.next_crown", what=what))
            return
        start = time.perf_counter()
        grown = mode.state.world.apply(Crown(state.base, tuple(state.lobes), style=style))
        mode.crown_tool.remember(mode.state.world.tree.lstring, state)
        ms = (time.perf_counter() - start) * 1e3
        mode.state.say(text("crown_panel.regrown", what=what, pieces=counted(grown.added, "branch piece"),
                            lobes=counted(len(state.lobes), "lobe"), ms=ms))

    def key(self) -> tuple:
        """What the panel shows (the HUD repaints when it changes)."""
        return (self.visible, self.preset, self.told, self.style()) if self.visible else (False,)

    def draw(self, surface: pygame.Surface, font: pygame.font.Font, small: pygame.font.Font) -> None:
        """The panel: the preset, each option's name, value and unit with its - and + buttons, and the
        meaning of the option last changed under it."""
        if not self.visible:
            return
        _shade(surface, self.rect, 170, (20, 30, 24))
        preset = self.buttons[("preset", "")]
        preset.label = text("crown_panel.preset_button", name=self.preset)
        draw_button(surface, font, preset)
        style = self.style()
        for k, (name, option) in enumerate(self.options.items(), 1):
            y = PANEL_Y + PAD + k * ROW
            label = text("crown_panel.row", option=text(f"crown_panel.{name}"), value=getattr(style, name),
                         unit=option.unit)
            surface.blit(small.render(label, True, TEXT), (PANEL_X + PAD, y + 14))
            for sign in ("minus", "plus"):
                draw_button(surface, font, self.buttons[(sign, name)])
        y = self.rect.bottom + 6
        for line in _wrap(small, self.told, PANEL_W - 2 * PAD)[:4] if self.told else []:
            _shade(surface, pygame.Rect(PANEL_X, y - 2, PANEL_W, 22), 150, (20, 30, 24))
            surface.blit(small.render(line, True, ACCENT), (PANEL_X + PAD, y))
            y += 22
