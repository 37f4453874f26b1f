"""Older garden-*.arbor files (one tree each, from before gardens were one file) are never deleted unread
(issue 45: with 6 trees in the autosave, the game folded in only what fit and unlinked them all at the
next save): those that do not fit are kept in a folder of their own, and the player is told."""

from __future__ import annotations

from arbor.engine.life.keep.save import SavedGarden, read_garden, write_garden
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import load_lsystem
from arbor.game.paths import ASSETS
from arbor.game.screens.game import Game, GameConfig
from arbor.game.screens.saves import LEGACY_FOLDER
from tests.conftest import FakeClock

SIZE = (1280, 720)


def test_older_tree_files_beyond_the_garden_are_kept_not_deleted(gl_ctx, tmp_path):
    system = load_lsystem(ASSETS / "lsystems" / "game_tree.lsys")
    rules = load_rules(ASSETS / "rules.toml", pace="demo")
    saves = tmp_path / "saves"
    saves.mkdir()
    write_garden(SavedGarden([World(system, rules, seed=s) for s in range(5)]), saves / "autosave.arbor")
    for s in (11, 12, 13):
        write_garden(SavedGarden([World(system, rules, seed=s)]), saves / f"garden-{s}.arbor")
    game = Game(gl_ctx, SIZE, GameConfig(saves=saves, seed=1), clock=FakeClock(), wall_clock=lambda: 1.7e9)
    assert len(game.state.garden.worlds) == 6  # one folded in: the garden is full
    assert "2 older tree files did not fit" in game.hud_info().message
    game.quit()  # (saves: the folded file goes, it is in the autosave now)
    assert len(read_garden(saves / "autosave.arbor").worlds) == 6 and not (saves / "garden-11.arbor").exists()
    kept = sorted(p.name for p in (saves / LEGACY_FOLDER).iterdir())
    assert kept == ["garden-12.arbor", "garden-13.arbor"]
    assert read_garden(saves / LEGACY_FOLDER / "garden-13.arbor").worlds  # whole, as they were
