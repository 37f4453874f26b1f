"""Blossom as flowers seen at the game's default zoom in spring (issue 47, looks): each blossom record is
drawn as a cluster of flowers (blossom.png) out of the leaves, not a pink dot among them."""

from pathlib import Path

import numpy as np
import pytest
from PIL import Image
from scipy import ndimage

from arbor.game.render.textures import TEXTURES

SIZE = (1280, 720)


@pytest.fixture(scope="module")
def spring(gl_ctx, tmp_path_factory):
    """The game's first frame at its default zoom on the shots' tree in its first spring (demo pace), by day."""
    from arbor.game.screens.game import Game, GameConfig
    from benchmarks.shots import SPRING, _grow

    clock = [1000.0]
    game = Game(gl_ctx, SIZE, GameConfig(saves=Path(tmp_path_factory.mktemp("saves")), seed=3, resume=False),
                clock=lambda: clock[0])
    world = _grow(SPRING, 3)
    world.sim.state.sun_angle = 1.1  # (the sun high, a little to the side: by day)
    game.garden.worlds[0] = world
    game.hud.draw = lambda camera: None  # (the scene alone)
    fbo = gl_ctx.framebuffer(color_attachments=[gl_ctx.renderbuffer(SIZE)],
                             depth_attachment=gl_ctx.depth_renderbuffer(SIZE))
    game.draw(fbo)
    shot = np.frombuffer(fbo.read(components=3), np.uint8).reshape(SIZE[1], SIZE[0], 3)[::-1].astype(int)
    return game, shot


def test_the_blossom_card_is_a_cluster_of_flowers():
    card = np.asarray(Image.open(TEXTURES / "blossom.png").convert("RGBA")).astype(int)
    yellow = (card[..., 3] > 127) & (card[..., 0] > 200) & (card[..., 2] < 120)  # the flowers' centres
    _, centres = ndimage.label(yellow)
    assert centres >= 4  # (one flower had one)


def test_blossoms_show_as_flowers_at_the_default_zoom_in_spring(spring):
    game, shot = spring
    assert len(game.world.tree.geometry(game.world.clocks()).turtle.leaves) > 0  # (leaves out, blossom among them)
    pink = (shot[..., 0] > shot[..., 1] + 25) & (shot[..., 2] > shot[..., 1])
    labels, _ = ndimage.label(pink)
    sizes = np.bincount(labels.ravel())[1:]
    blossoms = game.renderer.placed[0].buffers.parts["blossom"].count
    # per blossom the tree carries (the plant model sets how many): measured 155 pink pixels each (2,017 for
    # 13) and 6 clusters of 100 or more; drawn as before, single 9-pixel flowers: 16 each (194), none
    assert blossoms >= 4 and pink.sum() > 60 * blossoms, (blossoms, pink.sum())
    assert (sizes >= 100).sum() >= 2, sorted(sizes)[-8:]
