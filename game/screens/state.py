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
from arbor.engine.life.world.garden import Garden
from arbor.engine.life.world.world import World
from arbor.game.input.gestures import CameraControl
from arbor.game.loop import FixedStepLoop


class GameState:
    """The garden, speed, camera gestures, messages and the drawn-from sim state (see module docstring).

    The garden comes from the save keeper, which needs the state to speak: :meth:`use` hands it over
    before anything reads :attr:`garden`.
    """

    garden: Garden

    def __init__(self, loop: FixedStepLoop, control: CameraControl, clock: Callable[[], float]) -> None:
        self.loop, self.control, self.clock = loop, control, clock
        self.message, self.message_until = "", 0.0
        self.alpha = 1.0  # how far the frame is between the last two sim states
        self.cutaway = False  # the roots' view: the ground turns to soil and the roots show
        self.cursor3d: tuple[float, float, float] | None = None
        self.devices: dict[str, str] = {}  # input devices seen -> their kind

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

    def care_for(self, index: int) -> None:
        """Care for tree ``index`` of the garden."""
        self.garden.current = index
        self.remember()

    def advance(self, real_seconds: float) -> None:
        """Live one frame's worth of fixed steps (at the loop's speed)."""
        self.alpha = self.loop.advance(real_seconds, self._step)

    def _step(self, dt: float) -> None:
        """One fixed step of the whole garden (the frame interpolates from the state before it)."""
        self.previous = copy.copy(self.world.sim.state)
        self.garden.step(dt)

    def clocks(self) -> Clocks:
        """Growth clocks to draw: interpolated between the last two sim states."""
        return self.world.clocks(self.previous, self.alpha)

    def say(self, text: str, seconds: float = 3.0) -> None:
        """Show a message at the bottom of the screen for a while."""
        self.message, self.message_until = text, self.clock() + seconds

    def shown_message(self) -> str:
        """The message on screen now ('' once it timed out)."""
        return self.message if self.clock() < self.message_until else ""
