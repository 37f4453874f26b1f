"""What the menu's buttons and sliders do: care for the tree, the sun, time speed, the garden, files, tools."""

from __future__ import annotations

import copy
import math
from typing import TYPE_CHECKING

from arbor.engine.life.lineage.lineage import new_lineage
from arbor.engine.life.world.garden import MAX_GARDEN, MAX_ROCKS
from arbor.game.loop import SPEEDS
from arbor.game.render.ui import range_to_slider, slider_to_range
from arbor.game.screens.modeler import TOOLS
from arbor.game.strings import text

if TYPE_CHECKING:
    from arbor.game.screens.game import Game

WORLD_ACTIONS = ("water", "orbit_height", "sun_speed", "replant")


class CareActions:
    """Turns menu actions (name, value) into changes of the garden, the loop and the modeler."""

    def __init__(self, game: Game) -> None:
        self.game = game
        self.crossing = None  # the mother of a cross, while the player picks the father

    def act(self, action: str, value: float = 0.0) -> None:
        """Apply a player action; world actions are logged against the sim step (replayable)."""
        game = self.game
        if action in WORLD_ACTIONS:
            self._world_action(action, value)
        elif not value:
            return
        elif action == "speed":
            i = SPEEDS.index(game.loop.speed) if game.loop.speed in SPEEDS else 1
            self.set_speed(SPEEDS[(i + 1) % len(SPEEDS)])
        elif action == "save":
            if game.keeper.save():
                game.say(text("messages.saved"))
        elif action == "plant":
            self.plant()
        elif action == "sow":
            self.sow()
        elif action == "cross":
            self.start_cross()
        elif action == "family":
            game.family.open()
        elif action == "rock":
            self.place_rock()
        elif action == "roots":
            game.cutaway = not game.cutaway
            self.sync_sliders()
        elif action == "next" and len(game.garden.worlds) > 1:
            game.garden.next()
            game.previous = copy.deepcopy(game.world.sim.state)
            self.sync_sliders()
        elif action in TOOLS:
            TOOLS[action](game.modeling)
            game.menu.widget("edit").label = game.modeling.option_label()
            self.sync_sliders()
        elif action == "edit":
            game.menu.widget("edit").label = game.modeling.next_option()
        elif action in ("undo", "redo"):
            getattr(game.modeling, action)()
        elif action == "devices":
            names = sorted(game.devices) or [text("messages.no_devices")]
            game.say(text("messages.devices", names=", ".join(names)), 8)
        elif action == "load":
            self._load()

    def _world_action(self, action: str, value: float) -> None:
        game = self.game
        if action == "water" and value:
            game.coach.done("water")
        if action == "replant" and value == 0.0:
            return
        sim_value = self.slider_value(action, value)
        game.input_log.append((game.world.steps, action, sim_value))
        if action in ("orbit_height", "sun_speed"):  # one sun over the whole garden
            game.garden.apply_sun(action, sim_value)
        else:
            game.world.apply(action, sim_value)
        if action == "replant":
            lineage = game.world.lineage
            game.world.lineage = new_lineage(lineage.seed, game.wall_clock(), lineage.species)
            game.garden.family.add(game.world.lineage)
            game.previous = copy.deepcopy(game.world.sim.state)
            game.say(text("messages.planted"))

    def _load(self) -> None:
        game = self.game
        path = game.keeper.autosave_path
        garden = game.keeper.load(path) if path.exists() else None
        if garden is not None:
            game.garden, game.previous = garden, copy.deepcopy(garden.world.sim.state)
            game.say(text("messages.loaded"))

    def plant(self) -> None:
        """A new sapling in the garden, beside the others; it becomes the tree you care for."""
        game = self.game
        if game.garden.full:
            game.say(text("messages.garden_full", count=MAX_GARDEN), 5)
            return
        world = game.garden.plant(game.system, game.rules, now=game.wall_clock())
        game.previous = copy.deepcopy(world.sim.state)
        game.say(text("messages.garden_planted", count=len(game.garden.worlds)), 4)

    def sow(self) -> None:
        """Plant the oldest seed from the bag beside the others: a cross of its parent and the tree whose
        pollen reached it (engine/life/garden.py)."""
        game = self.game
        if not game.garden.seeds:
            game.say(text("messages.no_seeds"), 5)
            return
        if game.garden.full:
            game.say(text("messages.garden_full", count=MAX_GARDEN), 5)
            return
        parent = game.garden.seeds[0].parent_seed
        number = next((i + 1 for i, w in enumerate(game.garden.worlds) if w.seed == parent), 1)
        world = game.garden.plant_seed(game.rules, game.system, game.wall_clock())
        game.previous = copy.deepcopy(world.sim.state)
        self.sync_sliders()
        game.say(text("messages.sown", parent=number, count=len(game.garden.worlds)), 5)

    def place_rock(self) -> None:
        """A boulder beside the cared-for tree (each next one further round it): shoots grow around it."""
        game = self.game
        rocks = game.garden.rocks
        if len(rocks) >= MAX_ROCKS:
            game.say(text("messages.rocks_full", count=MAX_ROCKS), 5)
            return
        x, z = game.world.position
        angle = len(rocks) * 2.39996 + 0.6
        rocks.append((x + 2.6 * math.cos(angle), 0.5, z + 2.6 * math.sin(angle), 1.4))
        game.say(text("messages.rock"), 5)

    def care_for(self, index: int) -> None:
        """Care for tree ``index`` of the garden (the meters, the can and the modeler act on it)."""
        game = self.game
        game.garden.current = index
        game.previous = copy.deepcopy(game.world.sim.state)
        self.sync_sliders()
        game.say(text("messages.caring_for", number=index + 1), 4)

    def start_cross(self) -> None:
        """The cared-for tree will be the mother: the next tap on another tree picks the father."""
        game = self.game
        if len(game.garden.worlds) < 2:
            game.say(text("messages.cross_alone"), 5)
        elif game.garden.full:
            game.say(text("messages.garden_full", count=MAX_GARDEN), 5)
        else:
            self.crossing = game.world
            game.menu.hide()
            game.say(text("messages.cross_pick", number=game.garden.current + 1), 30)

    def cross_with(self, index: int | None) -> None:
        """Cross the mother chosen by :meth:`start_cross` with tree ``index`` (None or herself: cancel)."""
        game, mother = self.game, self.crossing
        self.crossing = None
        worlds = game.garden.worlds
        number = next((i + 1 for i, w in enumerate(worlds) if w is mother), None)
        if index is None or number is None or worlds[index] is mother:
            game.say(text("messages.cross_cancelled"), 4)
            return
        father = worlds[index]
        seed = (mother.seed * 1_000_003 + father.seed * 7919 + len(game.garden.family.members)) % 2**31
        child = game.garden.breed(mother, father, seed, game.rules, game.wall_clock())
        game.previous = copy.deepcopy(child.sim.state)
        self.sync_sliders()
        game.say(text("messages.crossed", a=number, b=index + 1, count=len(worlds)), 6)

    def slider_value(self, action: str, value: float) -> float:
        """A slider position (0..1) as the simulation value it stands for."""
        r = self.game.rules.sun
        if action == "orbit_height":
            return slider_to_range(value, r.orbit_height_min, r.orbit_height_max)
        if action == "sun_speed":
            return slider_to_range(value, r.speed_min, r.speed_max, log=True)
        return value

    def sync_sliders(self) -> None:
        """Show the cared-for tree's sun and the loop's speed on the menu."""
        game = self.game
        r, s = game.rules.sun, game.world.sim.state
        menu = game.menu
        menu.widget("orbit_height").value = range_to_slider(s.orbit_height, r.orbit_height_min, r.orbit_height_max)
        menu.widget("sun_speed").value = range_to_slider(s.sun_speed, r.speed_min, r.speed_max, log=True)
        speed = game.loop.speed
        menu.widget("speed").label = text("menu.paused") if speed == 0 else text("menu.speed", speed=f"{speed:g}")
        menu.widget("sow").label = text("menu.sow", count=len(game.garden.seeds))
        menu.widget("roots").label = text("menu.roots_hide" if game.cutaway else "menu.roots")
        menu.widget("modeler").label = text("menu.modeler_done" if game.modeling.active else "menu.modeler")

    def set_speed(self, speed: float) -> None:
        """Time speed: 0 (pause), 1, 10 or 100."""
        self.game.loop.speed = speed
        self.sync_sliders()
