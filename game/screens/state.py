"""What a running game is at a moment, apart from its screens: the garden and the tree cared for, the
fixed-step loop (time speed), the camera's gestures, the message line, the sim state frames are drawn
from, the roots' view, the devices seen and the 3D cursor.

The game's parts (care, coach, family, HUD, input, view, picking, saves) each get this state and the
few services they use, never the whole game; they change it through its methods.
"""

from __future__ import annotations

import copy
from collections.abc import Callable

from arbor.engine.life.form.interpret import Clocks
from arbor.engine.life.plant.sim import sun_angle_at
from arbor.engine.life.rules.rules import Rules, first_day
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.commands import SunAt
from arbor.engine.life.world.garden import Garden
from arbor.engine.life.world.guardian import NEEDS, Gardener, Guardian, Need, needs_of
from arbor.engine.life.world.world import World
from arbor.game.input.gestures import CameraControl
from arbor.game.loop import FixedStepLoop
from arbor.game.strings import text

FIRST_HOUR = 10.0  # the hour of the sun's day a player arriving in the dark is shown (a new game, a visitor)
LOW_SUN = 0.3  # orbit radii: a sun lower than this is too dark a welcome
SPROUT_SECONDS = 24.0  # real seconds a new game's seedling takes to rise from its seed to the planted sapling


class GameState:
    """The garden, speed, camera gestures, messages and the drawn-from sim state (see module docstring).

    The garden comes from the save keeper, which needs the state to speak: :meth:`use` hands it over
    before anything reads :attr:`garden`.
    """

    garden: Garden

    def __init__(self, loop: FixedStepLoop, control: CameraControl, clock: Callable[[], float],
                 rules: Rules | None = None) -> None:
        self.loop, self.control, self.clock = loop, control, clock
        self.rules = rules or Rules()
        self.guardian = Guardian(self.rules)  # watches every tree while time flies (engine/life/world)
        self.gardener = Gardener(self.guardian)  # "the gardener cares while you skip" (at 10x and 100x)
        self.gardening: Callable[[], bool] = lambda: False  # the player's setting for it (Settings)
        self.halted: Need | None = None  # the need the guardian stopped fast-forward for (until "go on")
        self.halt_line = ""  # what the guardian's stop said (shown only while its need holds)
        self.resume_speed = 1.0  # the speed "go on" returns to
        self.autopilot = False  # the kiosk with nobody there: the garden is tended every step
        # the cans the player holds: id of the world -> "float" (stops at the top of the soil: a hold begun
        # below it, every hold on the kiosk; "floated" once it did), "open" (pours on); see hold_can
        self.valves: dict[int, str] = {}
        self.valve_always = False  # the kiosk: a held can never floods a tree
        self.on_halt: list[Callable[[], None]] = []  # told when the guardian stops fast-forward (menu labels)
        self.message, self.message_until = "", 0.0
        self.alpha = 1.0  # how far the frame is between the last two sim states
        self.cutaway = False  # the roots' view: the ground turns to soil and the roots show
        self.cursor3d: tuple[float, float, float] | None = None
        self.devices: dict[str, str] = {}  # input devices seen -> their kind
        self.sprouts = False  # whether new saplings are drawn rising from their seeds (GameConfig.sprout)
        self.sprout_from: float | None = None  # when a new game's seed was sown (its seedling is unfolding)
        self.sprouting: World | None = None  # the tree whose seedling unfolds (another tree cared for ends it)

    @property
    def world(self) -> World:
        """The tree the player is caring for."""
        return self.garden.world

    def use(self, garden: Garden) -> None:
        """Play ``garden`` from now on (at start, after a load)."""
        self.garden = garden
        self.remember()

    def remember(self) -> None:
        """Draw from the cared-for tree's state as it is now (after a jump: a new tree, another tree
        cared for), not from a state of another tree."""
        self.previous = copy.deepcopy(self.world.sim.state)

    def daylight(self) -> bool:
        """A player arriving (a new game, the kiosk's next visitor) meets daylight: when the sun is low,
        the one sun over the garden is moved to FIRST_HOUR of its day. True when it was moved."""
        if self.world.sim.sun_height() >= LOW_SUN:
            return False
        angle = sun_angle_at(FIRST_HOUR * 3600.0)
        for world in self.garden.worlds:
            world.apply(SunAt(angle))
        self.remember()
        return True

    def care_for(self, index: int) -> None:
        """Care for tree ``index`` of the garden."""
        self.garden.current = index
        self.remember()

    def advance(self, real_seconds: float) -> None:
        """Live one frame's worth of fixed steps (at the loop's speed)."""
        self.alpha = self.loop.advance(real_seconds, self._step)

    def hold_can(self, world: World, held: bool) -> None:
        """The player holds the watering can over ``world`` (or lets go). A forgiving can: a hold begun below
        :meth:`can_top` floats (it stops there by itself and says why, and pours again once the meter falls
        below comfortable, so a can held on and on keeps the tree well and never drowns it); a new hold on
        a full soil pours on (too much water is the player's choice), except on the kiosk."""
        if held:
            floats = self.valve_always or world.sim.state.water_meter < self.can_top()
            self.valves[id(world)] = "float" if floats else "open"
        else:
            self.valves.pop(id(world), None)
        world.apply(Action.WATER, 1.0 if held else 0.0)

    def can_top(self) -> float:
        """The water meter at which a floating can stops: one step's pour below the drowning line."""
        return self.rules.water.drown_level - self.rules.water.fill_rate * self.loop.dt

    def _float_cans(self) -> None:
        """After a step: every floating can the player holds stops at the top (the first time saying why)
        and pours again below comfortable."""
        top, comfort = self.can_top(), self.rules.health.comfort
        for world in self.garden.worlds:
            mode, s = self.valves.get(id(world)), world.sim.state
            if mode not in ("float", "floated") or not s.alive:
                continue
            if s.watering and s.water_meter >= top:
                world.apply(Action.WATER, 0.0)
                if mode == "float":
                    self.say(text("messages.soil_full"), 5)
                self.valves[id(world)] = "floated"
            elif not s.watering and s.water_meter < comfort:
                world.apply(Action.WATER, 1.0)

    def first_day_left(self) -> float:
        """Game seconds left of a new garden's faster first day (the pace's ``first_day_speed``): while every
        tree of the garden is in its first day of the sun; 0 at a pace without one."""
        if self.rules.first_day_speed <= 1.0:
            return 0.0
        oldest = max(world.sim.state.time for world in self.garden.worlds)
        return max(first_day(self.rules) - oldest, 0.0)

    def first_day_factor(self) -> float:
        """How many times as fast the garden lives than the loop's speed: the pace's ``first_day_speed``
        during a new garden's first day, 1 after it and while any can pours (the can fills per real second)."""
        if self.first_day_left() <= 0 or any(world.sim.state.watering for world in self.garden.worlds):
            return 1.0
        return self.rules.first_day_speed

    def time_speed(self) -> float:
        """Game seconds per real second now (0 when paused): the loop's speed x :meth:`first_day_factor`."""
        return self.loop.speed * self.first_day_factor()

    def _step(self, dt: float) -> None:
        """One fixed step of the whole garden (the frame interpolates from the state before it): ``dt`` x
        :meth:`first_day_factor` of game time; the step that ends a faster first day says so."""
        self.previous = copy.copy(self.world.sim.state)
        factor = self.first_day_factor()
        self.garden.step(dt * factor)
        if self.valves:
            self._float_cans()
        if factor > 1.0 and self.first_day_left() <= 0:
            self.say(text("messages.first_day_over"), 10)
        if self.autopilot:
            self.guardian.autopilot(self.garden)
            return
        if self.loop.speed > 1.0 and self.gardening():  # (tended: stops only for a player's decision)
            need = self.gardener.care(self.garden)
            if need is not None:
                self.halt(need)
            return
        self.gardener.season = None  # (a season seen at 1x is no stop when the gardener takes over again)
        self.guardian.care(self.garden)
        if self.loop.speed > 1.0:
            need = self.guardian.watch(self.garden)
            if need is not None:
                self.halt(need)

    def halt(self, need: Need) -> None:
        """The guardian's stop: back to 1x at once (the rest of this frame's steps are not run), and a
        line that says which tree needs what and how to go on."""
        self.halted, self.resume_speed = need, self.loop.speed
        self.loop.speed = 1.0
        self.loop.accumulator = self.loop.dt  # (the step in progress is this frame's last)
        season = text(f"seasons.{self.world.sim.season().name}")
        self.halt_line = text(f"guardian.{need.what}", number=need.index + 1, speed=f"{self.resume_speed:g}",
                              season=season)
        self.say(self.halt_line, 30)
        for listener in self.on_halt:
            listener()

    def go_on(self) -> None:
        """The player's answer to a stop: every tree is tended (the can pours where it is needed) and time
        flies on at the speed it had."""
        self.guardian.tend(self.garden)
        self.loop.speed = self.resume_speed
        self.halted = None
        self.message_until = 0.0

    def sow(self) -> None:
        """A new game (or the kiosk's next visitor): the planted sapling is first drawn as the seed it grew
        from, and rises and unfolds its leaves over SPROUT_SECONDS of real time (the sim is not changed),
        when the game :attr:`sprouts`."""
        if self.sprouts:
            self.sprout_from, self.sprouting = self.clock(), self.world

    def clocks(self) -> Clocks:
        """Growth clocks to draw: interpolated between the last two sim states (replayed from the seed
        while a new game's seedling unfolds)."""
        clocks = self.world.clocks(self.previous, self.alpha)
        if self.sprout_from is not None:
            f = (self.clock() - self.sprout_from) / SPROUT_SECONDS
            if f >= 1.0 or f < 0.0 or self.sprouting is not self.world:
                self.sprout_from = self.sprouting = None
            else:
                ease = f * f * (3.0 - 2.0 * f)
                clocks.length_time *= ease
                clocks.girth_time *= ease
        return clocks

    def say(self, text: str, seconds: float = 3.0) -> None:
        """Show a message at the bottom of the screen for a while."""
        self.message, self.message_until = text, self.clock() + seconds

    def shown_message(self) -> str:
        """The message on screen now ('' once it timed out, and a guardian's stop line once its need is
        gone: no thirst warning over a tree watered past the need line, nor after a speed chosen by hand)."""
        if self.clock() >= self.message_until:
            return ""
        if self.halt_line and self.message == self.halt_line and not self.halt_holds():
            return ""
        return self.message

    def halt_holds(self) -> bool:
        """Whether the guardian's stop still stands and the tree it named still has the need it named (a
        gardener's stop for a decision stands until it is answered)."""
        need, worlds = self.halted, self.garden.worlds
        if need is None or need.index >= len(worlds):
            return False
        return need.what not in NEEDS or need.what in needs_of(worlds[need.index], self.rules)
