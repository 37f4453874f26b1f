"""What the menu's buttons and sliders do: care for the tree, the sun, time speed, the garden, files, tools."""

from __future__ import annotations

import copy
from typing import TYPE_CHECKING

from engine.life.garden import MAX_GARDEN
from game.loop import SPEEDS
from game.render.ui import range_to_slider, slider_to_range
from game.screens.modeler import TOOLS
from game.strings import text

if TYPE_CHECKING:
    from game.screens.game import Game

WORLD_ACTIONS = ("water", "orbit_height", "sun_speed", "replant")


class CareActions:
    """Turns menu actions (name, value) into changes of the garden, the loop and the modeler."""

    def __init__(self, game: Game) -> None:
        self.game = game

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
        world = game.garden.plant(game.system, game.rules)
        game.previous = copy.deepcopy(world.sim.state)
        game.say(text("messages.garden_planted", count=len(game.garden.worlds)), 4)

    def sow(self) -> None:
        """Plant the oldest seed from the bag beside the others: its parent's L-system, a seed of its own."""
        game = self.game
        if not game.garden.seeds:
            game.say(text("messages.no_seeds"), 5)
            return
        if game.garden.full:
            game.say(text("messages.garden_full", count=MAX_GARDEN), 5)
            return
        parent = game.garden.seeds[0].parent_seed
        number = next((i + 1 for i, w in enumerate(game.garden.worlds) if w.seed == parent), 1)
        world = game.garden.plant_seed(game.rules, game.system)
        game.previous = copy.deepcopy(world.sim.state)
        self.sync_sliders()
        game.say(text("messages.sown", parent=number, count=len(game.garden.worlds)), 5)

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
        menu.widget("modeler").label = text("menu.modeler_done" if game.modeling.active else "menu.modeler")

    def set_speed(self, speed: float) -> None:
        """Time speed: 0 (pause), 1, 10 or 100."""
        self.game.loop.speed = speed
        self.sync_sliders()
