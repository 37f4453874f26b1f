"""The kiosk's attract loop: a short recording of gestures that shows visitors what they can do.

`python -m game.screens.attract` rewrites assets/attract/demo.jsonl (slow one-finger turns, a tap that opens
the menu, a tap that closes it). Any session can be recorded with `arbor --record FILE` instead.

:class:`AttractShow` plays it on a copy of the settings: whatever slider its gestures move (the sun's
height and speed, time speed) goes back before the frame goes on, and each run ends with the menu closed.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from arbor.engine.life.world.actions import Action
from arbor.game.input.events import DOWN, MOVE, UP, InputEvent, Player, Recorder
from arbor.game.paths import ASSETS

Game = Any  # the kiosk's game (game/screens/game.py; not imported here: the parts never import it)

OUT = ASSETS / "attract" / "demo.jsonl"


@dataclass(frozen=True)
class Settings:
    """What an attract run could move: the one sun's height and speed over the garden, and time speed."""

    orbit_height: float
    sun_speed: float
    speed: float

    @classmethod
    def of(cls, game: Game) -> Settings:
        """The game's settings now (the sun as the cared-for tree has it: one sun shines on the garden)."""
        s = game.world.sim.state
        return cls(s.orbit_height, s.sun_speed, game.state.loop.speed)

    def put_back(self, game: Game) -> bool:
        """Set the game's settings back to these (only what moved is touched); True when anything had."""
        garden, moved = game.garden, False
        for action, value, field in ((Action.ORBIT_HEIGHT, self.orbit_height, "orbit_height"),
                                     (Action.SUN_SPEED, self.sun_speed, "sun_speed")):
            if any(getattr(w.sim.state, field) != value for w in garden.worlds):
                garden.apply_sun(action, value)
                moved = True
        if game.state.loop.speed != self.speed:
            game.set_speed(self.speed)
            moved = True
        if moved:
            game.care.sync_sliders()
        return moved


class AttractShow:
    """The attract loop over a game, on a copy of its settings (see module docstring). ``runs`` counts
    the recording's runs played to their end and ``after_run`` holds the settings each left behind."""

    def __init__(self, events: list[InputEvent], now: float) -> None:
        self.player = Player(events, now, loop=True)
        self.runs = 0
        self.after_run: Settings | None = None

    def play(self, game: Game, now: float) -> None:
        """Feed the gestures due by ``now`` to ``game``, then put back every setting they moved."""
        kept, start = Settings.of(game), self.player.start
        for e in self.player.poll(now):
            game.handle_input(e)
        over = self.player.start != start  # the recording came round: one run is over
        if over or game.modeling.active or game.family.up:  # (the show is the garden, not the tools)
            self.tidy(game)
        kept.put_back(game)
        if over:
            self.runs += 1
            self.after_run = Settings.of(game)

    @staticmethod
    def tidy(game: Game) -> None:
        """Leave the game as a visitor should find it: no gesture held, the menu, the family page and the
        modeler closed."""
        game.gestures.cancel_all()
        if game.modeling.active:
            game.modeling.toggle()
        game.family.close()
        for action in game.menu.hide():  # (as a tap outside it does, letting go of a held button)
            game.act(*action)


def demo_events(size: tuple[int, int] = (1280, 720)) -> list[InputEvent]:
    """About 20 s of gestures for a screen of ``size``."""
    w, h = size
    out: list[InputEvent] = []
    t = 0.0
    for sweep in range(2):
        x0, y = w * 0.3, h * 0.6
        out.append(InputEvent(DOWN, t, "attract", 0, x0, y))
        for i in range(1, 121):
            t += 1 / 30
            out.append(InputEvent(MOVE, t, "attract", 0, x0 + i * w * 0.4 / 120 * (1 if sweep == 0 else -1), y))
        out.append(InputEvent(UP, t, "attract", 0, out[-1].x, y))
        t += 1.5
    for x, y in ((w * 0.55, h * 0.3), (w * 0.1, h * 0.9)):  # open the menu, then close it
        out.append(InputEvent(DOWN, t, "attract", 1, x, y))
        out.append(InputEvent(UP, t + 0.1, "attract", 1, x, y))
        t += 4.0
    return out


def main() -> None:
    """Write the demo recording."""
    recorder = Recorder(OUT)
    recorder.write(demo_events())
    recorder.close()


if __name__ == "__main__":
    main()
