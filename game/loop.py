"""Fixed-timestep game loop (Glenn Fiedler, "Fix Your Timestep!").

Real frame time, scaled by the time speed (pause, 1x, 10x, 100x), fills an accumulator that is drained
in fixed simulation steps; what is left over gives the interpolation factor between the last two
simulation states for rendering. A slow frame is clamped so catching up can never spiral.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

SPEEDS = (0.0, 1.0, 10.0, 100.0)


@dataclass
class FixedStepLoop:
    """Accumulator that turns variable frame times into a whole number of fixed steps."""

    dt: float = 0.1  # simulation step, seconds of game time
    speed: float = 1.0  # game seconds per real second (0 = paused)
    max_frame: float = 0.25  # real seconds of one frame counted at most (spiral-of-death clamp)
    max_steps: int = 400  # steps run in one frame at most
    accumulator: float = 0.0
    steps: int = 0  # total steps run so far (input events are logged against this)
    dropped: float = 0.0  # game seconds thrown away by the clamps (reported, for honesty)

    def advance(self, frame_seconds: float, step: Callable[[float], None]) -> float:
        """Run the steps this frame owes; returns alpha in [0, 1) for render interpolation."""
        real = min(max(frame_seconds, 0.0), self.max_frame)
        self.dropped += max(frame_seconds - self.max_frame, 0.0) * self.speed
        self.accumulator += real * self.speed
        ran = 0
        while self.accumulator >= self.dt - 1e-9 and ran < self.max_steps:
            step(self.dt)
            self.accumulator -= self.dt
            self.steps += 1
            ran += 1
        if self.accumulator >= self.dt:  # still behind after max_steps: drop the backlog
            self.dropped += self.accumulator - self.accumulator % self.dt
            self.accumulator %= self.dt
        return self.accumulator / self.dt
