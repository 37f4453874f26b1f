"""The tamagotchi game: a garden of growing trees, a fixed-step loop, input, menu/HUD, renderer and saves.

`Game` wires the parts together and owns no window: the app gives it input events and a framebuffer,
so tests drive the real game headless (SDL dummy video for events, an EGL context for pixels). The jobs
live in their own classes: :class:`~game.screens.game_input.GameInput` (routing),
:class:`~game.screens.care.CareActions` (what menu actions do), :class:`~game.screens.saves.SaveKeeper`
(load/save/autosave), :class:`~game.screens.game_view.GameView` (the 3D scene),
:class:`~game.screens.game_hud.GameHud` (the 2D layer), :class:`~game.screens.coach.Coach` (hints,
reminders, journal) and :class:`~game.screens.picking.Picker` (taps on fruit and trees).
"""

from __future__ import annotations

import copy
import os
import time
from dataclasses import dataclass, field
from pathlib import Path

import moderngl
import numpy as np
import pygame

from arbor.engine.life.form.interpret import Clocks
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import load_lsystem
from arbor.game.input.events import InputEvent, PygameTranslator
from arbor.game.input.gestures import CameraControl, Gestures
from arbor.game.loop import FixedStepLoop
from arbor.game.paths import ASSETS, default_saves
from arbor.game.render.camera import OrbitCamera
from arbor.game.render.garden import GardenRenderer
from arbor.game.render.renderer import Overlay
from arbor.game.render.ui import HudInfo, Menu
from arbor.game.screens.care import CareActions
from arbor.game.screens.coach import Coach
from arbor.game.screens.family import FamilyScreen
from arbor.game.screens.game_hud import GameHud
from arbor.game.screens.game_input import GameInput
from arbor.game.screens.game_view import GameView
from arbor.game.screens.modeler import ModelingMode
from arbor.game.screens.picking import Picker
from arbor.game.screens.saves import SaveKeeper

BASE_PITCH = 8.0


@dataclass
class GameConfig:
    """Where the game finds its data and keeps its saves."""

    lsystem: Path = ASSETS / "lsystems" / "game_tree.lsys"
    rules: Path = ASSETS / "rules.toml"
    saves: Path = field(default_factory=default_saves)
    autosave_seconds: float = 60.0  # real seconds between autosaves
    resume: bool = True
    seed: int | None = None
    pace: str | None = field(default_factory=lambda: os.environ.get("ARBOR_PACE") or None)  # None: rules.toml's


class Game:
    """One running game; see module docstring."""

    def __init__(self, ctx: moderngl.Context, size: tuple[int, int], config: GameConfig | None = None,
                 clock=time.monotonic, wall_clock=time.time) -> None:
        self.config = config or GameConfig()
        self.size = size
        self.clock, self.wall_clock = clock, wall_clock
        self.rules = load_rules(self.config.rules, self.config.pace)
        self.system = load_lsystem(self.config.lsystem)
        self.loop = FixedStepLoop(dt=0.1)
        self.control = CameraControl(distance=1.0, min_distance=0.25, max_distance=6.0)
        self.gestures = Gestures(self.control)
        self.menu = Menu(size)
        self.renderer = GardenRenderer(ctx)
        self.overlay = Overlay(ctx, size)
        pygame.font.init()
        self.font = pygame.font.Font(None, 32)
        self.small_font = pygame.font.Font(None, 24)
        self.message, self.message_until = "", 0.0
        self.input_log: list[tuple[int, str, float]] = []
        self.translator = PygameTranslator(size)
        self.cursor3d: tuple[float, float, float] | None = None
        self.devices: dict[str, str] = {}
        self.overlay_hooks: list = []  # extra overlay layers (kiosk attract text, PIN pad)
        self.modeling = ModelingMode(self)
        self.gestures.pinch_target = self.modeling.pinch
        self.input = GameInput(self)
        self.care = CareActions(self)
        self.view = GameView(self)
        self.hud = GameHud(self)
        self.coach = Coach(self)
        self.picker = Picker(self)
        self.family = FamilyScreen(self)
        self.menu.journal_source = self.coach.journal_lines
        self.keeper = SaveKeeper(self)
        self.garden = self.keeper.start()
        if self.keeper.fresh:
            self.coach.first_run()
        self.previous = copy.deepcopy(self.world.sim.state)
        self.alpha = 1.0
        self.cutaway = False  # the roots' view: the ground turns to soil and the roots show
        self.care.sync_sliders()

    @property
    def world(self) -> World:
        """The tree the player is caring for."""
        return self.garden.world

    @property
    def others(self) -> list[World]:
        """The rest of the garden."""
        return self.garden.others

    @property
    def triangles(self) -> int:
        """Triangles in the last built scene."""
        return self.view.triangles

    def say(self, text: str, seconds: float = 3.0) -> None:
        """Show a message at the bottom of the screen for a while."""
        self.message, self.message_until = text, self.clock() + seconds

    def act(self, action: str, value: float = 0.0) -> None:
        """Apply a player action (see :class:`CareActions`)."""
        self.care.act(action, value)

    def set_speed(self, speed: float) -> None:
        """Time speed: 0 (pause), 1, 10 or 100."""
        self.care.set_speed(speed)

    def save(self, path: Path | None = None) -> bool:
        """Save the garden (see :class:`SaveKeeper`); False (and a message) when it could not be written."""
        return self.keeper.save(path)

    def handle_event(self, e: pygame.event.Event) -> bool:
        """Handle one pygame event (through the input layer); returns False when the game should quit."""
        keep = True
        for event in self.translator.translate(e, self.clock()):
            keep = self.handle_input(event) and keep
        return keep

    def handle_input(self, e: InputEvent) -> bool:
        """Handle one device-independent input event; returns False when the game should quit."""
        return self.input.handle(e)

    def tap(self, x: float, y: float) -> None:
        """Open the menu at (x, y), or close it when it is open."""
        self.input.tap(x, y)

    def update(self, real_seconds: float) -> None:
        """Advance the simulation by one frame's worth of fixed steps; autosave when due."""
        def step(dt: float) -> None:
            self.previous = copy.copy(self.world.sim.state)
            self.garden.step(dt)

        self.alpha = self.loop.advance(real_seconds, step)
        self.keeper.autosave_if_due()

    def clocks(self) -> Clocks:
        """Growth clocks to draw: interpolated between the last two sim states."""
        return self.world.clocks(self.previous, self.alpha)

    def camera(self) -> OrbitCamera:
        """The orbit camera for this frame: gestures applied to an auto-framed view of the tree."""
        r = self.renderer
        cam = OrbitCamera(yaw=self.control.yaw, pitch=BASE_PITCH + self.control.tilt)
        r_lo, r_hi = self.modeling.bounds if self.modeling.active and self.modeling.bounds else (r.lo, r.hi)
        modeling = self.modeling.active
        height = max(float(r_hi[1]), 2.0 if modeling else 4.0)  # a sapling stands small in its garden
        width = max(float(np.max(r_hi[[0, 2]] - r_lo[[0, 2]])), 1.0)
        bottom = self.view.roots_bottom if self.cutaway and not modeling else 0.0
        lo, hi = np.array([-width / 2, bottom, -width / 2]), np.array([width / 2, height, width / 2])
        cam.frame_bounds(lo, hi, self.size[0] / self.size[1], fill=0.8)
        cam.distance *= self.control.distance
        return cam

    def draw(self, fbo: moderngl.Framebuffer) -> None:
        """Render the scene and the HUD/menu overlay into ``fbo``."""
        self.view.draw(fbo)

    def hud_info(self) -> HudInfo:
        """What the HUD shows now."""
        return self.hud.hud_info()

    def quit(self) -> None:
        """Save on the way out."""
        self.save()
