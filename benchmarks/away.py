"""Time away: how long loading a garden takes when the player was gone 3 or 14 days (home pace).

Run: python -m benchmarks.away
A tree is grown at the home pace by a player who waters twice a day (benchmarks.home_pace) for 11
days (into summer), saved, and loaded as if the save were 3 and 14 days old: the load (parse + catch-up) is timed
and the summary the player would read is printed. The issue's goal: under 1 s for 14 days.
"""

from __future__ import annotations

import contextlib
import io
import tempfile
import time
from pathlib import Path

from arbor.engine.life.keep.away import away_seconds, live_away
from arbor.engine.life.keep.save import SavedGarden, read_garden, write_garden
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.garden import Garden
from benchmarks.home_pace import ASSETS, play

DAYS = 11  # grown into summer: the time away covers summer and autumn (and winter, for 14 days)


def main() -> None:
    """Grow, save, and load after 3 and 14 days away."""
    with contextlib.redirect_stdout(io.StringIO()):
        garden = play(DAYS)
    world = garden.world
    print(f"tree after {DAYS} days: {len(world.tree.lstring):,} modules, height {world.tree.height / 10:.2f} m")
    rules = load_rules(ASSETS / "rules.toml", pace="home")
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "autosave.arbor"
        for days in (3, 14, 30):
            write_garden(SavedGarden(garden.worlds, 0, 0.0, garden.seeds), path)
            start = time.perf_counter()
            saved = read_garden(path, rules)
            away, saved_at = Garden(saved.worlds, saved.current), saved.saved_at
            seconds = away_seconds(days * 86400.0, saved_at, rules.away.cap_days)
            summary = live_away(away, seconds)
            ms = (time.perf_counter() - start) * 1e3
            print(f"away {days:2d} days: load + catch-up {ms:6.0f} ms; lived {summary.days:.1f} days; "
                  f"grew {summary.grown:.2f} m, shed {summary.shed}, blossoms {summary.blossoms}, "
                  f"fruit {summary.fruit}, thirsty {summary.thirsty}, died {summary.died}; seasons {summary.seasons}")


if __name__ == "__main__":
    main()
