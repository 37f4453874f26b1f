"""Issue 47: Restore brings the tree back as it was saved, and a start's catch-up says what it did."""

from arbor.engine.life.world.actions import Action
from arbor.game.screens.game import Game, GameConfig
from tests.conftest import FakeClock

WATER = 0.48  # the water meter of the tree worth keeping, when it was saved


def _game(gl_ctx, saves, clock, **config):
    return Game(gl_ctx, (640, 360), GameConfig(saves=saves, seed=5, **config), clock=clock,
                wall_clock=lambda: 1.7e9 + clock.t)


def _replace_a_grown_tree(gl_ctx, saves, clock):
    """A grown tree (its clock at 77 s, water at WATER) saved, then R, confirm, quit."""
    game = _game(gl_ctx, saves, clock)
    s = game.world.sim.state
    s.length_time, s.time, s.water_meter = 77.0, 77.0, WATER
    game.save()
    game.act(Action.REPLANT, 1.0)
    game.act(Action.REPLANT, 1.0)
    assert game.world.sim.state.length_time < 77.0
    game.quit()


def test_a_restored_tree_is_the_tree_as_it_was_saved(gl_ctx, tmp_path):
    """R, confirm, quit, ten minutes later restart, Restore: the tree is back alive with the water it had
    (before: the ten minutes were lived on load, at the demo pace five days of thirst: back dead)."""
    clock = FakeClock()
    _replace_a_grown_tree(gl_ctx, tmp_path, clock)
    clock.t += 600.0
    game = _game(gl_ctx, tmp_path, clock)
    assert game.world.sim.state.length_time < 77.0  # the sapling (it lived the ten minutes)
    game.act(Action.RESTORE, 1.0)  # the first press shows what each kept autosave holds
    preview = game.state.shown_message()
    assert game.world.sim.state.length_time < 77.0 and preview.startswith("Autosaves kept: 1) 10 min ago"), preview
    assert "tree 1 alive, 77 s old, water 48 %" in preview and "bring back 1" in preview, preview
    game.act(Action.RESTORE, 1.0)  # the second, within 5 s, brings it back
    s = game.world.sim.state
    assert s.length_time == 77.0, "Restore did not bring the replaced tree"
    assert s.alive and abs(s.water_meter - WATER) < 1e-6, (s.alive, s.water_meter)
    shown = game.state.shown_message()
    clock.t += 6.0  # a press after a pause shows the list again: it never restores at once
    game.act(Action.RESTORE, 1.0)
    assert game.state.shown_message().startswith("Autosaves kept") and game.world.sim.state.length_time == 77.0
    assert "10 min" in shown and "alive" in shown and "48 %" in shown and "77 s old" in shown, shown


def test_a_start_s_catch_up_is_told_after_the_title(gl_ctx, tmp_path):
    """The catch-up at a normal start says what it did, and the title over the garden does not swallow
    that line: it is said again when the title is taken down."""
    from arbor.game.input.events import KEY_DOWN, InputEvent

    clock = FakeClock()
    _game(gl_ctx, tmp_path, clock).quit()
    clock.t += 600.0
    game = _game(gl_ctx, tmp_path, clock, title=True)
    told = game.keeper.start_message
    assert "While you were away (10 min)" in told, told
    clock.t += 60.0  # the player reads the title for a minute
    assert game.state.shown_message() != told
    game.title.handle(InputEvent(KEY_DOWN, clock.t, key=32))
    assert game.state.shown_message() == told


def test_a_glance_at_a_save_is_what_reading_it_gives_without_growing_its_trees(tmp_path, monkeypatch):
    """Restore's preview glances at each kept autosave: the same time, cared-for tree and state as reading
    it, and no tree is built (a 30-year garden's preview costs its parse alone)."""
    import pytest

    from arbor.engine.life.keep import save
    from arbor.engine.life.keep.save import SavedGarden, peek_garden, read_garden, write_garden
    from arbor.engine.life.keep.save_check import SaveError
    from arbor.engine.life.rules.rules import load_rules
    from arbor.engine.life.world.garden import Garden
    from arbor.engine.life.world.world import World
    from arbor.engine.lsystem.lsys import load_lsystem
    from arbor.game.paths import ASSETS

    rules = load_rules(ASSETS / "rules.toml", pace="demo")
    system = load_lsystem(ASSETS / "lsystems" / "game_tree.lsys")
    worlds = [World(system, rules, seed=k) for k in (1, 2)]
    worlds[1].sim.state.water_meter, worlds[1].sim.state.time = 0.31, 500.0
    garden = Garden(worlds)
    garden.current = 1
    path = tmp_path / "garden.arbor"
    write_garden(SavedGarden.of(garden, "game_tree.lsys", saved_at=1.7e9), path)
    read = read_garden(path, rules)
    monkeypatch.setattr(save, "_load_tree", None)  # (a glance that built a tree would fail here)
    glance = peek_garden(path)
    assert (glance.saved_at, glance.current) == (read.saved_at, read.current) == (1.7e9, 1)
    assert glance.state == read.world.sim.state and glance.state.water_meter == pytest.approx(0.31)
    path.write_text(path.read_text().replace("current = 1", "current = 7"))
    with pytest.raises(SaveError, match="current"):  # (checked as reading checks it)
        peek_garden(path)
