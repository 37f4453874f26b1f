"""Settings -> Restore: earlier autosaves shown, then brought back as they were saved (issue 47).

The first press lists the kept generations (engine/life/keep/generations.py), each with its age and its
cared-for tree as saved (alive or dead, its age, its water); a press within CONFIRM_SECONDS of the last
plays the next older one, as it was when it was saved: the time it lay in the backup is not lived (a
restored tree comes back as it was, not dead of ten minutes' thirst). A press after a pause lists them again.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path

from arbor.engine.life.keep.generations import generations
from arbor.game.screens.saves import SaveKeeper
from arbor.game.screens.state import GameState
from arbor.game.strings import duration, text

CONFIRM_SECONDS = 5.0  # a press of Restore within this long of the last brings one back; later, it lists them


def tree_line(index: int, s) -> str:
    """Tree ``index`` (from 0) in a few words: alive or dead, its age, its water (a restored garden's)."""
    life = text("messages.alive" if s.alive else "messages.dead")
    return text("messages.restored_tree", number=index + 1, life=life, age=duration(s.time), water=100 * s.water_meter)


class Restorer:
    """What Restore does (see module docstring); ``then()`` after a garden is brought back (the sliders)."""

    def __init__(self, state: GameState, keeper: SaveKeeper, wall_clock: Callable[[], float],
                 then: Callable[[], None]) -> None:
        self.state, self.keeper, self.wall_clock, self.then = state, keeper, wall_clock, then
        self.restored = 0  # the autosave generation Restore brought back last (0: none)
        self.pressed_at: float | None = None  # when Restore was last pressed (a press soon after acts)

    def press(self) -> None:
        """One press of Restore: list the kept autosaves, or (soon after a press) bring the next one back."""
        state = self.state
        kept = generations(self.keeper.autosave_path)
        if not kept:
            state.say(text("messages.no_generations"), 5)
            return
        now, last = state.clock(), self.pressed_at
        self.pressed_at = now
        if last is None or now - last > CONFIRM_SECONDS:
            state.say(self.preview(kept), CONFIRM_SECONDS + 5)
            return
        self.restored = self.restored % len(kept) + 1
        garden = self.keeper.load(kept[self.restored - 1], catch_up=False)
        if garden is not None:
            state.use(garden)
            self.then()
            state.say(text("messages.restored", when=self.age(self.keeper.saved_at), n=self.restored, count=len(kept),
                           tree=tree_line(state.garden.current, state.world.sim.state)), 10)

    def age(self, saved_at: float | None) -> str:
        """How long ago a save was written, in words ("?" when its clock cannot be read: None or NaN)."""
        if saved_at is None or not math.isfinite(saved_at):
            return "?"
        return duration(max(self.wall_clock() - saved_at, 0.0))

    def preview(self, kept: list[Path]) -> str:
        """One line: each kept autosave's age and its cared-for tree (alive or dead, age, water), and which
        one the next press of Restore brings back."""
        items = []
        for n, path in enumerate(kept, 1):
            saved = self.keeper.peek(path)
            if saved is None:
                items.append(text("messages.restore_unreadable", n=n))
                continue
            items.append(text("messages.restore_item", n=n, when=self.age(saved.saved_at),
                              tree=tree_line(saved.current, saved.state)))
        return text("messages.restore_preview", items="; ".join(items), next=self.restored % len(kept) + 1)
