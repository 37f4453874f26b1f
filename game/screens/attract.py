"""The kiosk's attract loop: a short recording of gestures that shows visitors what they can do.

`python -m game.screens.attract` rewrites assets/attract/demo.jsonl (slow one-finger turns, a tap that opens
the menu, a tap that closes it). Any session can be recorded with `arbor --record FILE` instead.
"""

from __future__ import annotations

from arbor.game.input.events import DOWN, MOVE, UP, InputEvent, Recorder
from arbor.game.paths import ASSETS

OUT = ASSETS / "attract" / "demo.jsonl"


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
