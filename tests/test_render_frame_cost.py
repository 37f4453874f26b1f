"""What keeps a frame cheap on a software GL (issue 29) without changing the picture: the wood drawn by a
program of its own (no leaves' alpha test, so the depth test runs before shading) without the tubes'
inner sides."""

from pathlib import Path

import numpy as np
import pytest

from arbor.game.render.backdrop import program

SIZE = (480, 320)


@pytest.fixture(scope="module")
def tree_game(gl_ctx, tmp_path_factory):
    """The real game, headless, caring for a tree grown a few days (wood to draw), the HUD left out."""
    from arbor.game.screens.game import Game, GameConfig
    from benchmarks.game import grown_tree

    clock = [1000.0]
    game = Game(gl_ctx, SIZE, GameConfig(saves=Path(tmp_path_factory.mktemp("saves")), seed=5, resume=False),
                clock=lambda: clock[0])
    game.garden.worlds[0] = grown_tree(10)
    game.state.remember()
    game.hud.draw = lambda camera: None
    game.fbo = gl_ctx.framebuffer(color_attachments=[gl_ctx.renderbuffer(SIZE)],
                                  depth_attachment=gl_ctx.depth_renderbuffer(SIZE))
    game.rules.wind.strength = 0.0
    return game


def _frame(game) -> np.ndarray:
    game.draw(game.fbo)
    return np.frombuffer(game.fbo.read(components=3), np.uint8).reshape(SIZE[1], SIZE[0], 3).astype(int)


def test_a_constant_replaces_the_uniform(gl_ctx):
    wood = program(gl_ctx, "tube.vert", "tree.frag", ("wind.glsl",), {"u_kind": 0})
    every = program(gl_ctx, "tube.vert", "tree.frag", ("wind.glsl",))
    assert "u_kind" in every and "u_kind" not in wood
    with pytest.raises(ValueError):
        program(gl_ctx, "tube.vert", "tree.frag", ("wind.glsl",), {"u_no_such_thing": 0})


def test_the_wood_program_and_culling_draw_the_same_picture(gl_ctx, tree_game):
    trees = tree_game.renderer.trees
    _frame(tree_game)
    fast = _frame(tree_game)
    kept = trees.programs[("tube", "lit")]

    def forget_vaos():
        for placed in tree_game.renderer.placed:
            for part in placed.buffers.parts.values():
                part.vaos.clear()

    try:
        trees.programs[("tube", "lit")] = program(gl_ctx, "tube.vert", "tree.frag", ("wind.glsl",))
        trees.cull_wood = False
        forget_vaos()
        every = _frame(tree_game)
    finally:
        trees.programs[("tube", "lit")], trees.cull_wood = kept, True
        forget_vaos()
    parts = tree_game.renderer.placed[0].buffers.parts
    assert sum(parts[name].count for name in ("tube", "tube_young")) > 100  # (a tree with wood on screen)
    changed = np.abs(fast - every).max(axis=2) > 8
    assert changed.sum() <= 20, f"{changed.sum()} pixels differ"
