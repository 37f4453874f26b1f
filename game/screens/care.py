"""What the player's actions do: care for the tree, the sun, time speed, the garden, files, tools.

:meth:`CareActions.act` is the one place an :class:`~arbor.engine.life.world.actions.Action` is
dispatched: the menu, the keys, the kiosk and the tests all come through it. The world's own actions
go on to :meth:`World.apply <arbor.engine.life.world.world.World.apply>` (which logs them for replays).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

from arbor.engine.life.rules.rules import Rules
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.commands import Replant
from arbor.engine.life.world.garden import MAX_GARDEN, MAX_ROCKS
from arbor.engine.lsystem.lsys import LSystem
from arbor.game.loop import SPEEDS
from arbor.game.render.ui import Menu, range_to_slider, slider_to_range
from arbor.game.screens.coach import Coach
from arbor.game.screens.config import PlayerSettings
from arbor.game.screens.family import FamilyScreen
from arbor.game.screens.modeler import ModelingMode
from arbor.game.screens.restoring import Restorer
from arbor.game.screens.saves import SaveKeeper
from arbor.game.screens.species_choice import SpeciesChoice
from arbor.game.screens.state import GameState
from arbor.game.strings import text

CONFIRM_SECONDS = 5.0  # a destructive key asks once; a second press within this long confirms

Handler = Callable[[float], None]


def pressed(handler: Callable[[], None]) -> Handler:
    """A button's handler: it acts when the button is pressed (value 1), not when it is let go (0)."""
    return lambda value: handler() if value else None


@dataclass
class CareParts:
    """The game's parts a player's actions reach, beside its state and rules: the menu and the modeler they
    come from, the saves, the family tree, the coach, the species' L-system, the wall clock and the sound."""

    menu: Menu
    modeling: ModelingMode
    keeper: SaveKeeper
    family: FamilyScreen
    coach: Coach
    system: LSystem
    wall_clock: Callable[[], float]
    sound: PlayerSettings | None = None


class CareActions:
    """Turns player actions (action, value) into changes of the garden, the loop and the modeler."""

    def __init__(self, state: GameState, rules: Rules, parts: CareParts) -> None:
        modeling, family, sound = parts.modeling, parts.family, parts.sound
        self.state, self.rules, self.menu, self.modeling, self.family = state, rules, parts.menu, modeling, family
        self.keeper, self.coach, self.system, self.sound = parts.keeper, parts.coach, parts.system, sound
        self.wall_clock = parts.wall_clock
        self.crossing = None  # the mother of a cross, while the player picks the father
        self.replant_asked, self.replant_at = None, 0.0  # the tree a first Replant press asked about, and when
        self.restoring = Restorer(state, self.keeper, self.wall_clock, self.sync_sliders)
        self.species = SpeciesChoice(self.system, lambda: state.garden, *(  # Garden -> Species
            (sound.unlocked, sound.unlock) if sound is not None else ()))
        state.on_halt.append(self.sync_sliders)
        tool = lambda switch: pressed(lambda: self._tool(switch))  # noqa: E731
        self.handlers: dict[Action, Handler] = {
            Action.WATER: self._water, Action.ORBIT_HEIGHT: lambda value: self._sun(Action.ORBIT_HEIGHT, value),
            Action.SUN_SPEED: lambda value: self._sun(Action.SUN_SPEED, value),
            Action.REPLANT: pressed(self.replant), Action.SPEED: pressed(self._next_speed),
            Action.GO_ON: pressed(self.go_on),
            Action.SAVE: pressed(self._save), Action.LOAD: pressed(self._load),
            Action.RESTORE: pressed(self.restore), Action.PLANT: pressed(self.plant),
            Action.SPECIES: pressed(lambda: (state.say(self.species.next(), 6), self.sync_sliders())),
            Action.SOW: pressed(self.sow), Action.CROSS: pressed(self.start_cross),
            Action.FAMILY: pressed(family.open), Action.ROCK: pressed(self.place_rock),
            Action.ROOTS: pressed(self._roots), Action.NEXT: pressed(self._next_tree),
            Action.MODELER: tool(modeling.toggle), Action.DRAW: tool(lambda: modeling.tool("draw")),
            Action.CROWN: tool(lambda: modeling.tool("crown")),
            Action.SHAPE: tool(lambda: modeling.tool("shaping")), Action.PRUNE: tool(lambda: modeling.tool("pruning")),
            Action.SYMBOLS: tool(lambda: modeling.tool("symbols")), Action.EDIT: pressed(self._next_edit),
            Action.UNDO: pressed(modeling.undo), Action.REDO: pressed(modeling.redo),
            Action.DEVICES: pressed(self._devices),
            Action.AWAY: pressed(self._away),
            Action.GARDENER: pressed(self._gardener),
        }
        if sound is not None:  # Settings -> Volume and Mute (see config.PlayerSettings)
            self.handlers.update(sound.handlers(self.sync_sliders))

    def act(self, action: Action, value: float = 0.0) -> None:
        """Apply a player action (see module docstring): sliders carry their position, buttons 1 when
        pressed and 0 when let go."""
        self.handlers[action](value)

    def _water(self, value: float) -> None:
        if value:
            self.coach.done("water")
        self.state.hold_can(self.state.world, bool(value))

    def _sun(self, action: Action, value: float) -> None:
        """A sun slider: one sun over the whole garden."""
        self.coach.done("sun")
        self.state.garden.apply_sun(action, self.slider_value(action, value))

    def replant(self, confirmed: bool = False) -> None:
        """A fresh sapling, of a new line, in the cared-for tree's place: the first press only asks, a
        second within CONFIRM_SECONDS replants (one key never destroys a tree)."""
        state = self.state
        world = state.world
        asked = self.replant_asked is world and state.clock() - self.replant_at <= CONFIRM_SECONDS
        if not (confirmed or asked):
            self.replant_asked, self.replant_at = world, state.clock()
            state.say(text("messages.replant_confirm", number=state.garden.current + 1), CONFIRM_SECONDS)
            return
        self.replant_asked = None
        world.apply(Replant(planted=self.wall_clock()))
        state.garden.family.add(world.lineage)
        state.remember()
        state.sow()  # (the new sapling is seen rising from its seed)
        self.modeling.replanted()  # (in the modeler: drawing starts anew on the sapling, no old overlay left)
        self.sync_sliders()
        state.say(text("messages.planted"))

    def go_on(self) -> None:
        """After the guardian's stop: the garden is tended and time flies on (see GameState.go_on)."""
        if self.state.halted is not None:
            self.state.go_on()
            self.sync_sliders()

    def _next_speed(self) -> None:
        if self.state.halted is not None:  # the speed button after a stop is "go on"
            self.go_on()
            return
        speed = self.state.loop.speed
        i = SPEEDS.index(speed) if speed in SPEEDS else 1
        self.set_speed(SPEEDS[(i + 1) % len(SPEEDS)])

    def _save(self) -> None:
        if self.keeper.save():
            self.state.say(text("messages.saved"))

    def _load(self) -> None:
        path = self.keeper.autosave_path
        garden = self.keeper.load(path) if path.exists() else None
        if garden is not None:
            self.state.use(garden)
            self.state.say(text("messages.loaded"))

    def restore(self) -> None:
        """Settings -> Restore: the kept autosaves listed, then brought back as saved (restoring.py)."""
        self.restoring.press()

    def _roots(self) -> None:
        self.state.cutaway = not self.state.cutaway
        self.sync_sliders()

    def _next_tree(self) -> None:
        if len(self.state.garden.worlds) > 1:
            self.state.garden.next()
            self.state.remember()
            self.sync_sliders()

    def _tool(self, switch: Callable[[], None]) -> None:
        """Switch a modeler tool (or the modeler itself) and show what the edit button now does."""
        switch()
        self.menu.widget("edit").label = self.modeling.option_label()
        self.sync_sliders()
        if self.modeling.active:  # the next drag draws with the tool, not into the menu
            self.menu.hide()

    def _next_edit(self) -> None:
        self.menu.widget("edit").label = self.modeling.next_option()

    def _away(self) -> None:
        """Settings -> Away: the garden is watered while you are gone (up to the time-away cap), or not."""
        if self.sound is not None:
            on = self.sound.toggle_away()
            self.state.say(text("messages.away_on" if on else "messages.away_off",
                                days=f"{self.rules.away.cap_days:g}"), 6)
            self.sync_sliders()

    def _gardener(self) -> None:
        """Settings -> Gardener: at 10x and 100x the gardener tends the garden and stops only for what the
        player must decide (engine/life/world/guardian.Gardener), or the guardian stops for every need."""
        if self.sound is not None:
            on = self.sound.toggle_gardener()
            self.state.say(text("messages.gardener_on" if on else "messages.gardener_off"), 6)
            self.sync_sliders()

    def _devices(self) -> None:
        names = sorted(self.state.devices) or [text("messages.no_devices")]
        self.state.say(text("messages.devices", names=", ".join(names)), 8)
    def plant(self) -> None:
        """A new sapling in the garden, beside the others; it becomes the tree you care for."""
        state = self.state
        if state.garden.full:
            state.say(text("messages.garden_full", count=MAX_GARDEN), 5)
            return
        state.garden.plant(self.species.system(), self.rules, now=self.wall_clock())
        state.remember()
        state.say(text("messages.garden_planted", count=len(state.garden.worlds)), 4)

    def sow(self) -> None:
        """Plant the oldest seed from the bag beside the others: a cross of its parent and the tree whose
        pollen reached it (engine/life/world/garden.py)."""
        state = self.state
        if not state.garden.seeds:
            state.say(text("messages.no_seeds"), 5)
            return
        if state.garden.full:
            state.say(text("messages.garden_full", count=MAX_GARDEN), 5)
            return
        parent = state.garden.seeds[0].parent_seed
        number = next((i + 1 for i, w in enumerate(state.garden.worlds) if w.seed == parent), 1)
        state.garden.plant_seed(self.rules, self.system, self.wall_clock())
        state.remember()
        self.sync_sliders()
        state.say(text("messages.sown", parent=number, count=len(state.garden.worlds)), 5)

    def place_rock(self) -> None:
        """A boulder beside the cared-for tree (each next one further round it): shoots grow around it."""
        state = self.state
        rocks = state.garden.rocks
        if len(rocks) >= MAX_ROCKS:
            state.say(text("messages.rocks_full", count=MAX_ROCKS), 5)
            return
        x, z = state.world.position
        angle = len(rocks) * 2.39996 + 0.6
        rocks.append((x + 2.6 * math.cos(angle), 0.5, z + 2.6 * math.sin(angle), 1.4))
        state.say(text("messages.rock"), 5)

    def care_for(self, index: int) -> None:
        """Care for tree ``index`` of the garden (the meters, the can and the modeler act on it)."""
        state = self.state
        state.care_for(index)
        self.sync_sliders()
        state.say(text("messages.caring_for", number=index + 1), 4)

    def start_cross(self) -> None:
        """The cared-for tree will be the mother: the next tap on another tree picks the father."""
        state = self.state
        if len(state.garden.worlds) < 2:
            state.say(text("messages.cross_alone"), 5)
        elif state.garden.full:
            state.say(text("messages.garden_full", count=MAX_GARDEN), 5)
        else:
            self.crossing = state.world
            self.menu.hide()
            state.say(text("messages.cross_pick", number=state.garden.current + 1), 30)

    def cross_with(self, index: int | None) -> None:
        """Cross the mother chosen by :meth:`start_cross` with tree ``index`` (None or herself: cancel)."""
        state, mother = self.state, self.crossing
        self.crossing = None
        worlds = state.garden.worlds
        number = next((i + 1 for i, w in enumerate(worlds) if w is mother), None)
        if index is None or number is None or worlds[index] is mother:
            state.say(text("messages.cross_cancelled"), 4)
            return
        father = worlds[index]
        seed = (mother.seed * 1_000_003 + father.seed * 7919 + len(state.garden.family.members)) % 2**31
        state.garden.breed(mother, father, seed, self.rules, self.wall_clock())
        state.remember()
        self.sync_sliders()
        state.say(text("messages.crossed", a=number, b=index + 1, count=len(worlds)), 6)

    def slider_value(self, action: Action, value: float) -> float:
        """A sun slider's position (0..1) as the simulation value it stands for."""
        r = self.rules.sun
        if action is Action.ORBIT_HEIGHT:
            return slider_to_range(value, r.orbit_height_min, r.orbit_height_max)
        return slider_to_range(value, r.speed_min, r.speed_max, log=True)

    def sync_sliders(self) -> None:
        """Show the cared-for tree's sun and the loop's speed on the menu."""
        state = self.state
        r, s = self.rules.sun, state.world.sim.state
        menu = self.menu
        menu.widget("orbit_height").value = range_to_slider(s.orbit_height, r.orbit_height_min, r.orbit_height_max)
        menu.widget("sun_speed").value = range_to_slider(s.sun_speed, r.speed_min, r.speed_max, log=True)
        speed = state.loop.speed
        label = text("menu.paused") if speed == 0 else text("menu.speed", speed=f"{speed:g}")
        menu.widget("speed").label = text("menu.go_on", speed=f"{state.resume_speed:g}") if state.halted else label
        menu.widget("sow").label = text("menu.sow", count=len(state.garden.seeds))
        menu.widget("species").label = text("menu.species", name=self.species.name())
        menu.widget("roots").label = text("menu.roots_hide" if state.cutaway else "menu.roots")
        menu.widget("modeler").label = text("menu.modeler_done" if self.modeling.active else "menu.modeler")
        menu.lit = {self.modeling.current_tool} if self.modeling.active else set()  # (the tools page lights it too)
        if self.sound is not None:
            self.sound.show(menu)
            menu.widget("away").label = text("menu.away_on" if self.sound.prefs.away else "menu.away_off")
            menu.widget("gardener").label = text("menu.gardener_on" if self.sound.prefs.gardener
                                                 else "menu.gardener_off")

    def set_speed(self, speed: float) -> None:
        """Time speed: 0 (pause), 1, 10 or 100 (a speed chosen by hand answers a guardian's stop)."""
        self.state.halted = None
        self.state.loop.speed = speed
        self.sync_sliders()
