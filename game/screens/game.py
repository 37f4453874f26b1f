"""The tamagotchi game: a garden of growing trees, a fixed-step loop, input, menu/HUD, renderer and saves.

`Game` wires the parts together and owns no window: the app gives it input events and a framebuffer,
so tests drive the real game headless (SDL dummy video for events, an EGL context for pixels). Its
:class:`~game.screens.stack.ScreenStack` says which screen takes input and what is drawn over what (the
garden at the bottom; the modeler, the menu, the family tree and the title pushed over it while they
are up; the kiosk adds its own). The jobs live in their own classes: :class:`~game.screens.game_input.GameInput`
(the garden's input: camera gestures, taps, keys),
:class:`~game.screens.care.CareActions` (what menu actions do), :class:`~game.screens.saves.SaveKeeper`
(load/save/autosave), :class:`~game.screens.game_view.GameView` (the 3D scene),
:class:`~game.screens.game_hud.GameHud` (the 2D layer), :class:`~game.screens.coach.Coach` (hints,
reminders, journal) and :class:`~game.screens.picking.Picker` (taps on fruit and trees). Each gets the
:class:`~game.screens.state.GameState` (the garden, speed, camera gestures, messages) and the few
services it uses, never the game itself.
"""

from __future__ import annotations

import time
from pathlib import Path

import moderngl
import pygame

from arbor.engine.life.form.interpret import Clocks
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.status import water_low
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import load_lsystem
from arbor.game.audio.sounds import Audio, soundscape
from arbor.game.input.events import InputEvent, PygameTranslator
from arbor.game.input.gestures import CameraControl, Gestures
from arbor.game.loop import FixedStepLoop
from arbor.game.render.camera import OrbitCamera
from arbor.game.render.garden import GardenRenderer
from arbor.game.render.renderer import Overlay
from arbor.game.render.ui import HudInfo, Menu
from arbor.game.screens.bell import NeedBell
from arbor.game.screens.care import CareActions, CareParts
from arbor.game.screens.coach import Coach
from arbor.game.screens.config import GameConfig, PlayerSettings
from arbor.game.screens.family import FamilyScreen
from arbor.game.screens.game_hud import GameHud, HudParts
from arbor.game.screens.game_input import GameInput
from arbor.game.screens.game_view import GameView
from arbor.game.screens.menu_screen import MenuScreen
from arbor.game.screens.modeler import ModelingMode
from arbor.game.screens.modeler_screen import ModelerScreen
from arbor.game.screens.picking import Picker
from arbor.game.screens.saves import SaveKeeper
from arbor.game.screens.sharing import Sharing
from arbor.game.screens.stack import ScreenStack
from arbor.game.screens.state import GameState
from arbor.game.screens.title import TitleScreen, box_corners
from arbor.game.strings import set_touch

__all__ = ["Game", "GameConfig"]


class Game:
    """One running game; see module docstring."""

    def __init__(self, ctx: moderngl.Context, size: tuple[int, int], config: GameConfig | None = None,
                 clock=time.monotonic, wall_clock=time.time) -> None:
        self.config = config or GameConfig()
        set_touch(False)  # (the keyboard's texts; the kiosk, a touch screen, turns its own on after this)
        self.size = size
        self.clock, self.wall_clock = clock, wall_clock
        self.rules = load_rules(self.config.rules, self.config.pace)
        self.system = load_lsystem(self.config.lsystem)
        self.loop = FixedStepLoop(dt=0.1)
        self.control = CameraControl(distance=1.0, min_distance=0.25, max_distance=6.0)
        self.gestures = Gestures(self.control)
        self.menu = Menu(size)
        self.renderer = GardenRenderer(ctx)
        self.audio = Audio()
        self.sound = PlayerSettings(self.audio, self.config.saves, clock)  # (volume, mute and Away)
        self.bell = NeedBell()  # (a thirsty tree while the window is elsewhere: its taskbar entry flashes)
        self.overlay = Overlay(ctx, size)
        pygame.font.init()
        self.font = pygame.font.Font(None, 32)
        self.small_font = pygame.font.Font(None, 24)
        self.translator = PygameTranslator(size)
        self.screens = ScreenStack()  # (the garden at the bottom, then whatever is up over it)
        self.title = TitleScreen(size)
        self.title.subject = lambda: box_corners(self.renderer.lo, self.renderer.hi)  # (kept clear of the tree)
        self.state = state = GameState(self.loop, self.control, clock, self.rules)
        state.sprouts = self.config.sprout
        state.gardening = lambda: self.sound.prefs.gardener
        self.keeper = SaveKeeper(state, self.config, self.rules, self.system, wall_clock,
                                 away=lambda: self.sound.prefs.away)
        state.use(self.keeper.start())
        self._parts()
        if self.keeper.fresh:
            state.daylight()  # a new player meets daylight, whatever the clock says
            state.sow()  # (and sees its seedling rise from the seed)
            self.coach.first_run()
        if self.sound.problem:
            self.say(self.sound.problem, 8)
        self.care.sync_sliders()
        if self.config.title:
            self.screens.push(self.title)
            self.title.on_close.append(self._tell_catch_up)

    def _parts(self) -> None:
        """The game's parts, each given the state and the services it uses."""
        state, size = self.state, self.size
        self.modeling = ModelingMode(state, self.renderer, size, camera=self.camera)
        self.gestures.pinch_target = self.modeling.pinch
        self.view = GameView(state, self.renderer, self.modeling, self.rules, size)
        self.coach = Coach(state, self.view.views)
        self.menu.journal_source = lambda: self.coach.journal_lines() + self.care.species.goals()
        self.family = FamilyScreen(state, self.menu, size, self.screens, (self.font, self.small_font))
        self.care = CareActions(state, self.rules, CareParts(self.menu, self.modeling, self.keeper, self.family,
                                                             self.coach, self.system, self.wall_clock, self.sound))
        self.sharing = Sharing(state, self.config.saves, self.rules, self.config.lsystem.name, self.renderer.ctx)
        self.care.handlers.update(self.sharing.handlers())  # (Settings -> Share, Garden -> Import)
        self.picker = Picker(state, self.view.views, size, self.care)
        self.hud = GameHud(state, self.rules, size, HudParts(
            screens=self.screens, overlay=self.overlay, renderer=self.renderer, views=self.view.views,
            fonts=(self.font, self.small_font), modeling=self.modeling, coach=self.coach,
            scene_sun=self.view.scene_sun))
        self.input = GameInput(state, size, self.camera, screens=self.screens, menu=self.menu,
                               gestures=self.gestures, care=self.care, picker=self.picker)
        self.screens.push(self.input)  # the garden: the bottom of the stack
        self.family.on_choose = self.care.care_for
        self.menu_screen = MenuScreen(self.menu, self.screens, gestures=self.gestures, care=self.care,
                                      font=self.font)
        self.modeling.screen = ModelerScreen(self.modeling, self.screens, menu=self.menu, gestures=self.gestures,
                                             care=self.care, tap=self.input.tap, fonts=(self.font, self.small_font),
                                             left=self.input.guard_quit)

    @property
    def garden(self):
        """The garden being played (see :class:`GameState`)."""
        return self.state.garden

    @property
    def world(self) -> World:
        """The tree the player is caring for."""
        return self.state.world

    @property
    def others(self) -> list[World]:
        """The rest of the garden."""
        return self.state.garden.others

    @property
    def triangles(self) -> int:
        """Triangles in the last built scene."""
        return self.view.triangles

    def say(self, text: str, seconds: float = 3.0) -> None:
        """Show a message at the bottom of the screen for a while."""
        self.state.say(text, seconds)

    def act(self, action: Action, value: float = 0.0) -> None:
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
        """Handle one device-independent input event (the screens take it top first); returns False when
        the game should quit (a quit no screen took)."""
        self.input.note_device(e)
        return self.screens.handle_input(e)

    def tap(self, x: float, y: float) -> None:
        """Open the menu at (x, y), or close it when it is open."""
        self.input.tap(x, y)

    def update(self, real_seconds: float) -> None:
        """Advance the simulation by one frame's worth of fixed steps; autosave when due."""
        self.state.advance(real_seconds)
        self.audio.hear(soundscape(self.world, self.view.wind_strength(), self.menu.presses, self.view.scene_sun()),
                        real_seconds)
        problem = self.sound.save_if_due()
        if problem:
            self.say(problem, 8)
        self.keeper.autosave_if_due()
        if int(self.clock()) != int(self.clock() - real_seconds):  # (once a second: a new species opened?)
            opened = self.care.species.watch()
            if opened:
                self.say(opened, 8)
            if self.sound.prefs.remind:  # (a thirsty tree while the window is elsewhere: screens/bell.py)
                self.bell.update(water_low(self.world))

    def clocks(self) -> Clocks:
        """Growth clocks to draw: interpolated between the last two sim states."""
        return self.state.clocks()

    def camera(self) -> OrbitCamera:
        """The orbit camera for this frame (see :meth:`GameView.camera`)."""
        return self.view.camera()

    def draw(self, fbo: moderngl.Framebuffer) -> None:
        """Render the scene and the HUD/menu overlay into ``fbo``."""
        self.hud.draw(self.view.draw(fbo))

    def hud_info(self) -> HudInfo:
        """What the HUD shows now."""
        return self.hud.hud_info()

    def _tell_catch_up(self) -> None:
        """The title is down: say again what the start's catch-up did (the title covered the line)."""
        if self.keeper.start_message:
            self.say(self.keeper.start_message, 10)
            self.keeper.start_message = ""

    def quit(self) -> None:
        """Save on the way out (the garden and a settings change not yet written)."""
        self.sound.flush()
        self.save()
