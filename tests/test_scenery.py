"""A garden that looks like a place (issue 47, looks): edging stones round each tree's foot, shrubs
beside it and stepping stones from tree to tree, cheap and the same at every start."""

from pathlib import Path

import numpy as np
import pytest

from arbor.game.render.scenery import EDGING, SHRUB_CARDS, SHRUBS, Spot, scale_of, scenery_view

SIZE = (1280, 720)


def test_stones_ring_each_tree_and_a_path_joins_them():
    spots = [Spot(0.0, 0.0, 1.0), Spot(-15.0, 3.0, 1.0), Spot(18.0, -16.0, 0.67)]
    view = scenery_view(spots)
    stones = view.stones.data
    assert len(view.leaves.data) == len(spots) * SHRUBS * SHRUB_CARDS
    foot = np.stack([stones[:, 0], stones[:, 2]], axis=1)
    near = [np.linalg.norm(foot - [s.x, s.z], axis=1) for s in spots]
    for spot, d in zip(spots, near, strict=True):
        ring = (d > 2.5 * spot.scale) & (d < 4.0 * spot.scale)
        assert ring.sum() >= EDGING and d.min() > 2.5 * spot.scale  # a ring, none on the trunk
    path = np.min(near, axis=0) > 4.2 * max(s.scale for s in spots)
    assert path.sum() >= 10  # (15 + 24 units of path: stones every 2.4 units)
    assert np.all(np.abs(stones[:, 1] - 0.35 * stones[:, 9] / 2) < 1e-6)  # (resting on the ground)
    again = scenery_view(spots)
    assert np.array_equal(again.stones.data, stones) and np.array_equal(again.leaves.data, view.leaves.data)


def test_a_lone_tree_has_a_path_out_and_its_scenery_grows_with_it():
    small, big = (scenery_view([Spot(0.0, 0.0, scale_of(height))]) for height in (3.0, 15.0))
    assert 0.0 < np.abs(small.stones.data[:, [0, 2]]).max() < 0.5 * np.abs(big.stones.data[:, [0, 2]]).max()
    assert scale_of(15.0) == 1.0 and scale_of(0.1) < scale_of(6.0) < 1.0 and scale_of(14.0) == scale_of(16.0)


@pytest.fixture(scope="module")
def frames(gl_ctx, tmp_path_factory):
    """The game's frame at its default zoom by day on a summer tree, with and without its scenery."""
    from arbor.game.render import scenery
    from arbor.game.screens import game_view
    from arbor.game.screens.game import Game, GameConfig
    from benchmarks.shots import _grow, summer_day

    kept, scenery.ON_SOFTWARE_GL = scenery.ON_SOFTWARE_GL, True  # (this machine's GL is llvmpipe)
    world = _grow(summer_day(), 3)
    world.sim.state.sun_angle = 1.1  # (by day)
    shots, triangles = [], []
    placed = game_view.GameView._scenery
    for shown in (False, True):
        game_view.GameView._scenery = placed if shown else (lambda self, here: [])
        try:
            game = Game(gl_ctx, SIZE, GameConfig(saves=Path(tmp_path_factory.mktemp("s")), seed=3, resume=False),
                        clock=lambda: 1000.0)
            game.garden.worlds[0] = world
            game.hud.draw = lambda camera: None
            fbo = gl_ctx.framebuffer(color_attachments=[gl_ctx.renderbuffer(SIZE)],
                                     depth_attachment=gl_ctx.depth_renderbuffer(SIZE))
            game.draw(fbo)
            shots.append(np.frombuffer(fbo.read(components=3), np.uint8).reshape(SIZE[1], SIZE[0], 3)[::-1].astype(int))
            triangles.append(game.triangles)
        finally:
            game_view.GameView._scenery = placed
    scenery.ON_SOFTWARE_GL = kept
    return shots, triangles


def test_a_software_gl_draws_the_scenery_into_the_backdrops_picture_not_every_frame(gl_ctx, tmp_path, monkeypatch):
    """The scenery's stones and shrubs cost a software GL nothing while the camera holds still: drawn with
    the grass into the backdrop's picture (drawn again only when the camera, the light or the trees move),
    and its box, the garden's ground, bounds neither the ground's shadow tests nor the smoothing."""
    from arbor.game.render import garden
    from arbor.game.screens.game import Game, GameConfig

    game = Game(gl_ctx, (320, 240), GameConfig(saves=tmp_path, seed=3, resume=False), clock=lambda: 1000.0)
    fbo = gl_ctx.framebuffer(color_attachments=[gl_ctx.renderbuffer((320, 240))],
                             depth_attachment=gl_ctx.depth_renderbuffer((320, 240)))
    game.draw(fbo)
    renderer = game.renderer
    scenery = [p for p in renderer.placed if p.version == garden.SCENERY]
    assert renderer.samples <= 1 and len(scenery) == 1
    assert len(garden.placed_boxes(renderer.placed)) == len(renderer.placed) - 1
    drawn = []
    draw = renderer.trees.draw
    monkeypatch.setattr(renderer.trees, "draw", lambda buffers, pass_, *rest: (
        drawn.append(buffers is scenery[0].buffers and pass_ == "lit"), draw(buffers, pass_, *rest)))
    for _ in range(8):  # (the camera holds still)
        game.draw(fbo)
    assert sum(drawn) <= 1 and len(drawn) >= 8  # (the tree itself drawn every frame)


def test_the_game_shows_stones_and_shrubs_round_the_tree_at_little_cost(frames):
    (bare, placed), (before, after) = frames
    grey = lambda shot: (np.ptp(shot, axis=2) < 25) & (shot.mean(axis=2) > 60)  # noqa: E731 (stone, not grass)
    ground = slice(SIZE[1] // 2, None)  # (below the horizon: not the clouds)
    assert grey(placed[ground]).sum() > grey(bare[ground]).sum() + 1500  # stones on the grass
    changed = np.abs(placed - bare).max(axis=2) > 30
    assert changed[ground].sum() > 8000  # and shrubs
    assert after - before < 0.05 * before  # (measured: 2,904 -> 2,976 triangles)
