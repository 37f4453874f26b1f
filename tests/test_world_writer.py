"""The world is the only writer of its own state (issue 42).

Every change a player, a tool, the kiosk, the lab or the garden makes enters a World as a command through
``World.apply``, which logs it with the steps between; a session's log replays to the same tree, modeler
edits included. Outside engine/life/world/ no code assigns to a world's fields or to a tree's L-string
(an AST check), and planting, loading and breeding build each World once.
"""

import ast
from pathlib import Path

import numpy as np

from arbor.engine.life.keep.save import SavedGarden, garden_text, read_garden_bytes
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world import world as world_module
from arbor.engine.life.world.commands import BeginEditing, Cut, RegionEdit, Stroke, Undo, Water
from arbor.engine.life.world.garden import Garden
from arbor.engine.life.world.log import MAX_ENTRIES, Log, Run, replay
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import load_lsystem
from arbor.engine.modeling.edits import load_edit_sets
from arbor.engine.modeling.regions import Sphere
from tests.test_modeler_tools import base_pixel, click, draw, press_bar, press_menu

ROOT = Path(__file__).resolve().parent.parent
OWNER = ROOT / "engine" / "life" / "world"  # the world's own package: the only place that writes it
WORLDISH = ("world", "worlds")  # names through which code reaches a world


def _chain(node: ast.AST) -> list[str]:
    """The names along an assignment target's base: ``self.state.world.tree`` -> [self, state, world, tree]."""
    names = []
    while isinstance(node, ast.Attribute | ast.Subscript):
        if isinstance(node, ast.Attribute):
            names.append(node.attr)
        node = node.value
    if isinstance(node, ast.Name):
        names.append(node.id)
    return names[::-1]


def _refers(value: ast.AST, worldish: set[str]) -> bool:
    """Whether ``value`` is a reference into a world (a plain chain like ``world.sim.state`` or
    ``garden.worlds[0]``), not a value computed from one."""
    return isinstance(value, ast.Name | ast.Attribute | ast.Subscript) and bool(set(_chain(value)) & worldish)


def _aliases(scope: ast.AST) -> set[str]:
    """Names that hold a world or a part of one in ``scope``: ``s = world.sim.state``, ``for w in
    garden.worlds``, ``tree = self.state.world.tree`` (and aliases of those)."""
    found: set[str] = set()
    for _ in range(3):  # (an alias of an alias)
        worldish = set(WORLDISH) | found
        for node in ast.walk(scope):
            pairs = []
            if isinstance(node, ast.Assign):
                for target in node.targets:
                    if isinstance(target, ast.Tuple) and isinstance(node.value, ast.Tuple):
                        pairs += list(zip(target.elts, node.value.elts, strict=False))
                    else:
                        pairs.append((target, node.value))
            elif isinstance(node, ast.For):
                pairs = [(node.target, node.iter)]
            found |= {t.id for t, v in pairs if isinstance(t, ast.Name) and _refers(v, worldish)}
    return found


def world_writes(path: Path) -> list[str]:
    """The assignments in ``path`` to a world's state (through a name like ``world``, or a name that holds
    a world or a part of one) or to any object's ``lstring`` but the object's own (``self.lstring``)."""
    found = []
    tree = ast.parse(path.read_text(encoding="utf-8"))
    for scope in [node for node in ast.walk(tree) if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef)]:
        worldish = set(WORLDISH) | _aliases(scope)
        for node in ast.walk(scope):
            targets = (node.targets if isinstance(node, ast.Assign)
                       else [node.target] if isinstance(node, ast.AugAssign | ast.AnnAssign) else [])
            for target in targets:
                for leaf in ast.walk(target):
                    if not isinstance(leaf, ast.Attribute) or not isinstance(leaf.ctx, ast.Store):
                        continue
                    base = _chain(leaf.value)
                    if (base[:1] != ["self"] and set(base[:1]) & worldish) or set(base) & set(WORLDISH) or \
                            (leaf.attr == "lstring" and base != ["self"]):
                        found.append(f"{path.relative_to(ROOT)}:{leaf.lineno}: {ast.unparse(leaf)} = ...")
    return sorted(set(found), key=lambda line: int(line.split(":")[1]))


def test_nothing_outside_the_world_package_writes_a_world_or_a_tree_s_lstring():
    files = [p for top in ("engine", "game") for p in sorted((ROOT / top).rglob("*.py")) if OWNER not in p.parents]
    found = [line for path in files for line in world_writes(path)]
    assert not found, "send the world a command (engine/life/world/commands.py) instead:\n" + "\n".join(found)


def test_the_writer_check_catches_the_writes_it_is_for(tmp_path):
    bad = tmp_path / "tool.py"
    bad.write_text("def f(mode, tree, w, garden):\n    mode.state.world.tree.lstring = 1\n    tree.lstring = 2\n"
                   "    w.worlds[0].position = (0, 0)\n    self.lstring = 3\n"
                   "    s = garden.world.sim.state\n    s.water_meter = 1.0\n"
                   "    for v in garden.worlds:\n        v.rules.light.interval = 2\n", encoding="utf-8")
    bad = bad.rename(ROOT / "tests" / f"_probe_{tmp_path.name}.py")
    try:
        assert [line.split(": ", 1)[1] for line in world_writes(bad)] == [
            "mode.state.world.tree.lstring = ...", "tree.lstring = ...", "w.worlds[0].position = ...",
            "s.water_meter = ...", "v.rules.light.interval = ..."]
    finally:
        bad.unlink()


def _lsys(name: str = "game_tree"):
    return load_lsystem(ROOT / "assets" / "lsystems" / f"{name}.lsys")


def test_commands_of_an_edit_session_replay_to_the_same_lstring():
    rules = load_rules(ROOT / "assets" / "rules.toml", pace="demo")
    world = World(_lsys(), rules, seed=5, replanted=True)
    for _ in range(400):
        world.step(0.5)
    world.apply(Water(True))
    world.apply(BeginEditing())
    top = world.drawn_segments(world.tree.lstring).end[:, 1].max()
    jitter = np.random.default_rng(1).normal(0, 0.01, (40, 3))
    trunk = np.linspace([0, 0, 0], [0.2, top * 1.5, 0], 40) + jitter
    assert world.apply(Stroke(trunk, np.linspace(0, 1, 40))).pieces > 0
    branch = np.linspace([0.1, top, 0], [1.5, top * 1.4, 0.3], 30)
    assert world.apply(Stroke(branch, np.linspace(0, 0.6, 30))).pieces > 0
    segs = world.drawn_segments(world.tree.lstring)
    assert world.apply(Cut(int(segs.module[len(segs) // 2]))) > 0
    grow = load_edit_sets(ROOT / "assets" / "edits")["grow"]
    assert world.apply(RegionEdit("grow", Sphere((0.0, top, 0.0), top * 0.6), grow)).changed != 0
    assert world.apply(Undo())
    for _ in range(200):  # time runs on: the region confines growth, the edits grow on
        world.step(0.5)
    again = replay(world.log)
    assert again.tree.lstring.to_text() == world.tree.lstring.to_text()
    assert again.sim.state == world.sim.state


def test_a_modeler_session_in_the_real_game_replays_from_the_world_s_log(modeler_game):
    game = modeler_game(seed=3)
    press_menu(game, "modeler")
    x0, y0 = base_pixel(game)
    draw(game, [(x0 + 3 * np.sin(i), y0 - 12 * i) for i in range(30)])  # a jittery trunk from the foot
    draw(game, [(x0 + 8 * i, y0 - 200 - 4 * i + (i % 2)) for i in range(25)])  # a branch off it
    press_bar(game, "crown")
    a = np.linspace(0, 2 * np.pi, 48)
    draw(game, [(x0 + 110 * np.cos(t), y0 - 330 + 90 * np.sin(t)) for t in a])  # a lobe
    assert len(game.modeling.crown_tool.state().lobes) == 1
    press_bar(game, "prune")  # a tap on a branch cuts it
    segs = game.world.drawn_segments(game.world.tree.lstring)
    tips = [k for k in range(len(segs)) if segs.parent[k] >= 0 and game.hud.project(game.camera(), segs.end[k])]
    x, y = game.hud.project(game.camera(), (segs.start[tips[-1]] + segs.end[tips[-1]]) / 2)
    click(game, x, y)
    said = game.hud_info().message  # ('Cut 1 branch piece.' or 'Cut 3 branch pieces.', never '1 branch pieces')
    assert said.startswith("Cut ") and ("1 branch piece." if said.startswith("Cut 1 ") else "pieces.") in said
    press_bar(game, "symbols")  # a region over the trunk, then Grow in it
    draw(game, [(x0, y0 - 100), (x0, y0 - 160), (x0, y0 - 200)])
    while game.modeling.edit != "grow":
        game.act(game_action("edit"), 1.0)
    click(game, x0, y0 - 160)
    game.act(game_action("undo"), 1.0)
    game.act(game_action("redo"), 1.0)
    edits = [type(c).__name__ for c in game.world.log.commands]
    assert {"BeginEditing", "Stroke", "Crown", "Cut", "RegionEdit", "Undo", "Redo"} <= set(edits), edits
    again = replay(game.world.log)
    assert again.tree.lstring.to_text() == game.world.tree.lstring.to_text()


def game_action(name: str):
    from arbor.engine.life.world.actions import Action
    return Action.named(name)


def test_the_log_is_bounded_and_still_replays():
    rules = load_rules(ROOT / "assets" / "rules.toml", pace="demo")
    world = World(_lsys(), rules, seed=2)
    for k in range(3 * MAX_ENTRIES):
        world.apply(Water(k % 2 == 0))
        world.step(0.5)
    assert len(world.log.entries) <= MAX_ENTRIES
    assert isinstance(world.log.entries[0], Water | Run)
    assert replay(world.log).sim.state == world.sim.state


def test_steps_of_one_length_are_one_log_entry():
    log = Log()
    for dt in (0.5, 0.5, 0.5, 2.0, 2.0):
        log.ran(dt)
    assert log.entries == [Run(0.5, 3), Run(2.0, 2)]


def counting_plants(monkeypatch) -> list[int]:
    """Every sapling a World plants, counted (World._plant)."""
    planted = []
    real = World._plant

    def count(self, seed):
        planted.append(seed)
        return real(self, seed)
    monkeypatch.setattr(world_module.World, "_plant", count)
    return planted


def test_planting_and_breeding_plant_each_tree_once(monkeypatch):
    rules = load_rules(ROOT / "assets" / "rules.toml", pace="demo")
    garden = Garden([World(_lsys(), rules, seed=1)])
    planted = counting_plants(monkeypatch)
    garden.plant(_lsys(), rules)
    assert len(planted) == 1
    garden.breed(garden.worlds[0], garden.worlds[1], 77, rules)
    assert len(planted) == 2


def test_loading_builds_each_world_once_and_plants_nothing(monkeypatch, tmp_path):
    rules = load_rules(ROOT / "assets" / "rules.toml", pace="demo")
    garden = Garden([World(_lsys(), rules, seed=1)])
    for _ in range(100):
        garden.step(0.5)
    text = garden_text(SavedGarden(garden.worlds))
    planted = counting_plants(monkeypatch)
    built = []
    real_init = World.__post_init__

    def count(self, *args):
        built.append(self.seed)
        real_init(self, *args)
    monkeypatch.setattr(world_module.World, "__post_init__", count)
    loaded = read_garden_bytes(text.encode(), tmp_path / "g.arbor", rules)
    assert planted == [] and built == [1]
    assert loaded.worlds[0].tree.lstring.to_text() == garden.world.tree.lstring.to_text()
