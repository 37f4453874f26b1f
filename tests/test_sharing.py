"""Settings -> Share and Garden -> Import in the game: a postcard written by one garden plants its tree in
another; a card the garden already holds, or a broken one, plants nothing and says why."""

from __future__ import annotations

import shutil
from pathlib import Path

from arbor.engine.life.world.actions import Action
from arbor.game.screens.game import Game, GameConfig

SIZE = (640, 360)


def _game(gl_ctx, folder: Path, seed: int) -> Game:
    return Game(gl_ctx, SIZE, GameConfig(saves=folder, seed=seed, resume=False), clock=lambda: 0.0)


def _grow(game: Game, seconds: float) -> None:
    world = game.world
    world.sim.state.sun_meter = world.sim.state.water_meter = 0.9
    for _ in range(int(seconds / 0.5)):
        world.apply(Action.WATER, float(world.sim.state.water_meter < 0.6))
        world.step(0.5)


def test_a_tree_shared_from_one_garden_is_planted_in_another(gl_ctx, tmp_path):
    mine = _game(gl_ctx, tmp_path / "mine", seed=4)
    _grow(mine, 600)
    mine.act(Action.SHARE, 1.0)
    cards = list((tmp_path / "mine" / "cards").glob("*.png"))
    assert len(cards) == 1 and "postcard of your tree" in mine.state.message
    friend = _game(gl_ctx, tmp_path / "friend", seed=9)
    (tmp_path / "friend" / "cards").mkdir(parents=True)
    shutil.copy(cards[0], tmp_path / "friend" / "cards" / "from_a_friend.png")
    (tmp_path / "friend" / "cards" / "broken.png").write_bytes(b"\x89PNG\r\n\x1a\n" + bytes(40))
    friend.act(Action.IMPORT, 1.0)
    assert len(friend.garden.worlds) == 2 and friend.garden.current == 1
    assert friend.world.tree.lstring.to_text() == mine.world.tree.lstring.to_text()
    assert "from_a_friend.png" in friend.state.message
    friend.act(Action.IMPORT, 1.0)  # nothing new: the same tree is not planted twice
    assert len(friend.garden.worlds) == 2
    assert "No new tree" in friend.state.message and "1 card(s)" in friend.state.message  # the broken one
