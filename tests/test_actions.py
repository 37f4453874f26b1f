"""Player actions are values dispatched in one place, and the game's parts never reach for the game.

Actions are :class:`Action` values from the menu, the keys, the kiosk and replays to the one dispatcher
(game/screens/care.py) and on to the world; their names exist as text only at the edges (files,
scripts), converted by :meth:`Action.named`.
"""

import re
from pathlib import Path

import pytest

from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.commands import Water
from arbor.engine.life.world.log import Run, replay
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import load_lsystem
from tests.test_layers import imports_of

ROOT = Path(__file__).resolve().parent.parent
# an action compared with (or looked up among) strings: what a second, name-keyed dispatch looks like
STRING_DISPATCH = re.compile(r"""\baction\b\s*(?:[=!]=|(?:not\s+)?in\b)\s*[(\[{]?\s*["']|["']\s*[=!]=\s*action\b""")


def test_no_action_is_dispatched_by_its_name():
    found = [f"{path.relative_to(ROOT)}:{n}: {line.strip()}"
             for top in ("engine", "game") for path in sorted((ROOT / top).rglob("*.py"))
             for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1)
             if STRING_DISPATCH.search(line)]
    assert not found, "actions compared by name (dispatch them as Action values in care.py):\n" + "\n".join(found)


def test_the_game_parts_do_not_import_the_game():
    screens = ROOT / "game" / "screens"
    found = [f"{path.name}:{line}" for path in sorted(screens.glob("*.py")) if path.name != "game.py"
             for name, line in imports_of(path) if name == "game.screens.game" or name.startswith("game.screens.game.")]
    assert not found, "parts get the state and their services, not the Game: " + ", ".join(found)


def test_action_names_from_text_come_back_as_actions_and_unknown_ones_are_refused():
    assert all(Action.named(action.value) is action for action in Action)
    with pytest.raises(ValueError, match=r"unknown action 'waterr' \(known: water, orbit_height"):
        Action.named("waterr")


def test_a_world_applies_only_its_own_actions_and_logs_them_for_replay(lsys_dir):
    rules = load_rules(ROOT / "assets" / "rules.toml", pace="demo")
    system = load_lsystem(lsys_dir / "game_tree.lsys")
    world = World(system, rules, seed=4)
    with pytest.raises(ValueError, match="not an action of the world: 'save'"):
        world.apply(Action.SAVE, 1.0)
    for step in range(30):
        if step in (3, 12):
            world.apply(Action.WATER, float(step == 3))
        world.step(0.5)
    assert world.log.entries == [Run(0.5, 3), Water(True), Run(0.5, 9), Water(False), Run(0.5, 18)]
    again = replay(world.log)
    assert again.sim.state == world.sim.state
