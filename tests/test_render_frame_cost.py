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


def test_leaves_are_drawn_by_a_leaves_only_program_and_look_the_same(gl_ctx, tree_game):
    trees = tree_game.renderer.trees
    assert "u_kind" not in trees.programs[("card", "lit")]
    _frame(tree_game)
    fast = _frame(tree_game)
    kept = trees.programs[("card", "lit")]

    def forget_vaos():
        for placed in tree_game.renderer.placed:
            for part in placed.buffers.parts.values():
                part.vaos.clear()

    try:
        trees.programs[("card", "lit")] = trees.programs[("leaf", "lit")]
        forget_vaos()
        every = _frame(tree_game)
    finally:
        trees.programs[("card", "lit")] = kept
        forget_vaos()
    parts = tree_game.renderer.placed[0].buffers.parts
    assert sum(parts[name].count for name in ("leaf", "leaf_young") if name in parts) > 0  # (leaves on screen)
    assert (np.abs(fast - every).max(axis=2) > 2).sum() <= 5


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
    assert sum(parts[name].count for name in ("tube", "tube_young")) > 30  # (a tree with wood on screen)
    changed = np.abs(fast - every).max(axis=2) > 8
    assert changed.sum() <= 20, f"{changed.sum()} pixels differ"


def test_a_sun_moving_while_the_camera_holds_still_costs_a_frame_one_part_of_the_backdrop(tree_game, monkeypatch):
    """The kept backdrop (software GL) follows the sun a part a frame (sky, ground, grass, shadows) and
    within a few frames shows what a fresh drawing shows."""
    from arbor.game.render import garden

    renderer = tree_game.renderer
    if renderer.samples > 1:
        pytest.skip("multisampled: the backdrop is drawn every frame")
    monkeypatch.setattr(garden, "LAYER_COST", float("inf"))  # the trees drawn whole every frame (not a picture)
    drawn: list[str] = []
    for owner, name in ((renderer.backdrop, "draw_sky"), (renderer.backdrop, "draw_ground"),
                        (renderer.grass, "draw"), (renderer.backdrop, "draw_shadows")):
        kept = getattr(owner, name)
        monkeypatch.setattr(owner, name, lambda *a, kept=kept, name=name, **k: (drawn.append(name), kept(*a, **k))[1])
    sim = tree_game.world.sim
    state = sim.state
    state.sun_angle = _angle_at_height(sim, 0.1)  # a low sun, where 0.05 rad changes the sky's colours (a high
    tree_game.state.remember()  # one's day light is full and its disc may be out of view: nothing to redraw)
    _frame(tree_game)
    state.sun_angle += 0.05
    tree_game.state.remember()
    parts = []
    for _ in range(8):
        drawn.clear()
        shot = _frame(tree_game)
        parts.append(len(drawn))
    assert max(parts) <= 1 and sum(parts) >= 2, parts  # (one part a frame, and it did follow the sun)
    assert not tree_game.renderer.stage.busy
    tree_game.renderer.stage.forget()
    fresh = _frame(tree_game)
    assert (np.abs(shot - fresh).max(axis=2) > 2).sum() <= 20


def test_a_look_changes_its_version_only_by_a_level_and_a_part_drawn_again_keeps_the_rest():
    from arbor.game.render.sky_look import LookKey

    key = LookKey()
    look, rects = np.array([10.0, 20.0, 30.0]), np.array([[0, 0, 10, 10], [50, 50, 60, 60], [0, 0, 100, 100]], float)
    first = key.of(look)
    key.draw(look, rects)
    assert key.of(look + 0.6) == first  # (under a level: the picture is kept)
    moved = look + np.array([0.0, 3.0, 0.0])
    assert key.of(moved) == first + 1
    assert key.dirty(moved, rects, (100, 100)) == (48, 48, 14, 14)  # (the changed value's pixels, a rim)
    key.draw(moved, rects, (48, 48, 14, 14), (100, 100))
    assert not key.differs(moved)
    assert key.drawn[0] == 10.0  # (outside the part drawn again: as it was drawn)


def test_a_sky_changing_every_frame_keeps_neither_the_ground_nor_the_shadows_from_being_drawn(gl_ctx):
    from arbor.game.render.kept import KeptBackdrop, Looks, Parts

    kept, drawn = KeptBackdrop(gl_ctx), []
    parts = Parts(*(lambda depth, name=name: drawn.append(name) for name in ("sky", "ground", "cover")),
                  lambda into: drawn.append("shadows"))
    looks = Looks(("a view",), (0,), 0, 0, 0)
    kept.full((16, 16), looks, (0,), parts)
    drawn.clear()
    for frame in range(1, 9):  # (the sky new every frame, the ground's light changed once)
        kept.step(looks._replace(sky=(frame,), ground=1), (0,), parts)
    assert len(drawn) == 8 and {"sky", "ground", "cover", "shadows"} <= set(drawn), drawn
    kept.release()


def _angle_at_height(sim, height: float) -> float:
    """A sun angle at which ``sim``'s sun stands ``height`` high (the sine of its elevation), rising."""
    def at(angle: float) -> float:
        sim.state.sun_angle = angle
        return float(sim.sun_direction()[1])
    angles = np.linspace(0.0, 2 * np.pi, 721)
    return float(min((a for a in angles if at(a + 0.01) > at(a)), key=lambda a: abs(at(a) - height)))


def test_a_falling_branch_casts_no_shadow_and_does_not_redraw_the_shadow_map_every_frame(tree_game, monkeypatch):
    from arbor.engine.geometry.instances import TUBE_FLOATS, LeafInstances, TubeInstances
    from arbor.game.render.falling import StaticView
    from arbor.game.render.garden import FALLING, Placed
    from arbor.game.render.instanced import TreeBuffers

    def piece() -> StaticView:  # new records every frame, as a falling branch has
        data = np.zeros((1, TUBE_FLOATS), np.float32)
        data[0, 0:3], data[0, 3:6], data[0, 6:9] = (3.0, 5.0, 0.0), (0.0, 1.0, 0.0), (1.0, 0.0, 0.0)
        data[0, 9:12], data[0, 12:15], data[0, 15:18] = (3.0, 9.0, 0.0), (0.0, 1.0, 0.0), (1.0, 0.0, 0.0)
        data[0, 18:20], data[0, 20:22] = (0.3, 0.3), (0.0, 1.0)
        return StaticView(TubeInstances(data, np.zeros(1, np.int64)), LeafInstances.empty(), LeafInstances.empty(),
                          np.array([2.7, 5.0, -0.3]), np.array([3.3, 9.0, 0.3]))

    view = tree_game.view

    def falling(here):
        buffers = TreeBuffers()
        view.renderer.trees.sync(buffers, piece())
        view.falls.append(buffers)
        return [Placed(buffers, np.zeros(3), FALLING)]

    monkeypatch.setattr(view, "_falling", falling)
    _frame(tree_game)
    _frame(tree_game)
    maps = tree_game.renderer.shadows.version
    for _ in range(5):
        _frame(tree_game)
    assert tree_game.renderer.shadows.version == maps  # (it was redrawn at each of them)
