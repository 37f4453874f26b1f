"""The game's renderer: instanced records that join without steps, growth that updates only what grows,
wind that moves twigs and not the trunk, a sun that shows, nights that are blue, blossoms that are pink."""

import copy
import math

import numpy as np
import pytest

from arbor.engine.life.form.growth_view import GrowthView
from arbor.engine.life.form.interpret import Clocks
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import load_lsystem
from arbor.game.render.camera import project_points
from arbor.game.render.instanced import LEAF_KEPT, Detail
from arbor.game.screens.game import Game, GameConfig

SIZE = (640, 360)


@pytest.fixture(scope="module")
def grown(lsys_dir):
    world = World(load_lsystem(lsys_dir / "game_tree.lsys"), load_rules("assets/rules.toml", pace="demo"), seed=3)
    world.sim.state.sun_meter = world.sim.state.water_meter = 0.9
    world.tree.dead_linger = 0.0  # (a branch that dies falls at once: these tests draw its fall, not its linger)
    for step in range(6000):  # about 8 simulated days, and on until a branch has just been shed
        world.apply(Action.WATER, float(world.sim.state.water_meter < 0.6))
        world.step(0.5)
        if step >= 2000 and world.tree.fallen:
            break
    return world


def test_joint_rings_are_shared_so_branches_taper_without_steps(grown):
    view = GrowthView(grown.tree.lstring, grown.clocks(), grown.tree.geometry_constants)
    data, module = view.tubes.data, view.tubes.module
    row = {int(m): i for i, m in enumerate(module)}
    segs = grown.tree.geometry(grown.clocks()).turtle.segments
    cont = np.flatnonzero(segs.continues)
    child = np.array([row[int(segs.module[c])] for c in cont])
    parent = np.array([row[int(segs.module[segs.parent[c]])] for c in cont])
    assert len(cont) > 40  # (joints enough to judge: 48 on the tree the carbon budget pays for in 8 days)
    np.testing.assert_allclose(data[child, 0:9], data[parent, 9:18], atol=1e-6)  # centre, tangent, reference
    np.testing.assert_allclose(data[child, 18], data[parent, 19], atol=1e-7)  # radius: no width step
    tips = data[:, 24] > 0.5
    assert 0 < tips.sum() < len(data)  # cones only where a branch ends


def test_growing_parts_move_as_a_fresh_build_would(grown):
    clocks = grown.clocks()
    view = GrowthView(grown.tree.lstring, clocks, grown.tree.geometry_constants)
    later = Clocks(clocks.length_time + 0.8, clocks.girth_time, 0.0)
    view.update(later)
    fresh = GrowthView(grown.tree.lstring, later, grown.tree.geometry_constants)
    a, b = view.tubes.data[np.argsort(view.tubes.module)], fresh.tubes.data[np.argsort(fresh.tubes.module)]
    assert np.abs(a[:, 9:12] - b[:, 9:12]).max() < 0.01  # (parts 97 % grown catch up at the next build)
    assert view.young_row < len(view.tubes)  # only a block of rows moved
    old = np.argsort(view.tubes.module)[: view.young_row]
    assert len(old) > 0


@pytest.fixture
def game(gl_ctx, tmp_path, grown):
    clock = [100.0]
    g = Game(gl_ctx, SIZE, GameConfig(saves=tmp_path, seed=5, resume=False), clock=lambda: clock[0])
    g.garden.worlds[0] = copy.deepcopy(grown)  # tests change the tree: each gets its own
    g.world.tree.fallen.clear()  # (a branch shed just before would fall through the first frames)
    g.fake = clock
    g.fbo = gl_ctx.framebuffer(color_attachments=[gl_ctx.renderbuffer(SIZE)],
                               depth_attachment=gl_ctx.depth_renderbuffer(SIZE))
    return g


def frame(game) -> np.ndarray:
    game.draw(game.fbo)
    return np.frombuffer(game.fbo.read(components=3), np.uint8).reshape(SIZE[1], SIZE[0], 3)[::-1].astype(int)


def test_wind_sways_twigs_not_the_trunk_and_zero_is_still(game, monkeypatch):
    from arbor.game.render import garden

    monkeypatch.setattr(garden, "LAYER_COST", float("inf"))  # (each frame drawn whole: see the test below)
    game.rules.wind.strength = 0.0
    a = frame(game)
    game.fake[0] += 1.7
    b = frame(game)
    assert np.abs(a - b).max() == 0  # still air: nothing moves
    game.rules.wind.strength = 2.0
    a = frame(game)
    game.fake[0] += 1.7
    b = frame(game)
    moved = np.abs(a - b).sum(axis=2) > 40
    assert moved.sum() > 500
    base = project_points(game.camera(), SIZE, np.array([[0.0, 0.3, 0.0]]))[0].astype(int)
    x, y = base
    assert not moved[y - 3:y + 3, x - 3:x + 3].any()  # the foot of the trunk stays put


def test_nights_are_blue_not_black_and_the_tree_stays_visible(game):
    game.world.sim.state.sun_angle = 4.7
    night = frame(game)
    sky = night[5:40, SIZE[0] - 100:SIZE[0] - 20].reshape(-1, 3).mean(axis=0)  # (the hint sits top centre)
    assert sky[2] > 60 and sky[2] > sky[0] + 20  # dark blue
    centre = project_points(game.camera(), SIZE, np.array([[0.0, float(game.renderer.hi[1]) * 0.6, 0.0]]))[0]
    x, y = centre.astype(int)
    crown = night[y - 30:y + 30, x - 30:x + 30].reshape(-1, 3)
    assert crown.mean() > 15  # not a black hole


def test_the_rising_sun_shows_in_the_default_view(game):
    sim = game.world.sim
    orbit = sim.sun_height() - math.sin(sim.state.sun_angle)  # (the season raises or lowers the orbit)
    sim.state.sun_angle = math.asin(0.1 - orbit)  # just after sunrise
    game.hud.draw = lambda camera: None  # the scene alone (the sun may rise behind the meters)
    shot = frame(game)
    sun = game.world.sim.sun_direction()
    camera = game.camera()
    px = project_points(camera, SIZE, (camera.eye + sun * camera.distance * 15)[None])[0]
    assert np.all(np.isfinite(px)) and 0 <= px[0] < SIZE[0] and 0 <= px[1] < SIZE[1]
    x, y = px.astype(int)
    assert shot[max(y - 2, 0):y + 3, max(x - 2, 0):x + 3].min(axis=(0, 1)).sum() > 600  # a bright disc


def test_blossoms_are_pink(game):
    import re

    from arbor.engine.lsystem.lstring import parse_lstring

    text = game.world.tree.lstring.to_text().replace("L(", "K(")  # every leaf becomes a blossom, K(birth)
    game.world.tree.lstring = parse_lstring(re.sub(r"K\(([-0-9.e]+),[-0-9.e]+,[-0-9.e]+\)", r"K(\1)", text))
    shot = frame(game)
    pink = (shot[:, :, 0] > 110) & (shot[:, :, 0] > shot[:, :, 1] + 20) & (shot[:, :, 2] > shot[:, :, 1] + 5)
    assert pink.sum() > 100  # pink petals, not grey-blue ones


def test_coarser_levels_draw_fewer_triangles_within_budget(game, monkeypatch):
    counts = []
    for lod in range(4):
        level = lambda buffers, *a, lod=lod: Detail.of(buffers, lod, 0.0, LEAF_KEPT[lod])  # noqa: E731
        monkeypatch.setattr(game.renderer, "_detail", level)
        frame(game)
        counts.append(game.triangles)
    assert counts == sorted(counts, reverse=True) and counts[3] < 0.6 * counts[0] and counts[1] < counts[0]
    monkeypatch.undo()
    buffers = game.renderer.placed[0].buffers
    game.renderer.vertex_budget = Detail.of(buffers, 2, 0.0, LEAF_KEPT[2]).vertices(buffers) - 1
    frame(game)
    assert game.renderer.last_details[0].lod == 3  # too much to shade: a coarser level, whatever the size
    whole = Detail.of(buffers, 3, 0.0, LEAF_KEPT[3])
    young = Detail(3).vertices(buffers)  # the growing parts (always drawn whole)
    game.renderer.vertex_budget = young + (whole.vertices(buffers) - young) // 3
    frame(game)
    detail = game.renderer.last_details[0]
    assert detail.vertices(buffers) <= game.renderer.vertex_budget  # still too much: the thinnest twigs
    assert detail.tubes < whole.tubes and detail.leaf_share < LEAF_KEPT[3]  # and a share of the leaves go


def test_a_frame_updates_records_without_rebuilding(game, monkeypatch):
    frame(game)
    builds = []
    original = GrowthView.__init__

    def counting(self, *args, **kwargs):
        builds.append(1)
        original(self, *args, **kwargs)

    monkeypatch.setattr(GrowthView, "__init__", counting)
    game.world.last_light = float("inf")
    for _ in range(5):
        game.fake[0] += 0.05
        game.update(0.05)  # time passes, the tree grows, no rewrite in these steps
        frame(game)
    assert len(builds) <= 1  # at most one rewrite in a quarter second: every other frame only moved records


def test_a_branch_shed_just_now_falls_then_is_gone(game, grown):
    from arbor.game.render.falling import FALL_SECONDS

    game.world.tree.fallen = copy.deepcopy(grown.tree.fallen)
    assert game.world.tree.fallen, "the grown tree has shed a branch lately"
    game.world.tree.last_rewrite_T = max(f.at for f in game.world.tree.fallen)  # shed at the last rewrite
    frame(game)
    assert len(game.view.falls) >= 1 and any(p.version == -1 for p in game.renderer.placed)
    game.fake[0] += FALL_SECONDS + 0.5
    frame(game)
    assert not game.view.falls


def test_branches_fall_in_a_picture_drawn_over_frames(game, grown, monkeypatch):
    """Falling branches are new buffers every frame (the old ones freed): a picture drawn over several
    frames keeps going while they fall, draws them as they are when each step runs, and copes with
    one landing mid-picture."""
    from arbor.game.render.falling import FALL_SECONDS

    monkeypatch.setattr("arbor.game.render.garden.draw_scale", lambda *a: 0.5)
    game.world.tree.fallen = copy.deepcopy(grown.tree.fallen)
    game.world.tree.last_rewrite_T = max(f.at for f in game.world.tree.fallen)
    frame(game)
    pictures, shown = game.renderer.pictures, game.renderer.pictures.version
    while game.view.falls:
        game.fake[0] += FALL_SECONDS / 12  # they land part-way through a picture
        frame(game)
    assert pictures.version >= shown + 1  # pictures kept coming while they fell
    landed = pictures.version
    for _ in range(8):
        frame(game)
    assert pictures.version > landed


def test_the_sky_and_ground_picture_follows_the_camera_and_the_sun(game):
    """On a software GL the backdrop is drawn once and copied while nothing it shows changes: after
    turning the camera or tilting it the frame must equal a fresh drawing at once; after moving the sun
    (the camera holding still: drawn a part a frame, see kept.py) within a few frames."""
    game.rules.wind.strength = 0.0
    frame(game)
    for change, frames in ((lambda: setattr(game.control, "yaw", game.control.yaw + 25.0), 1),
                           (lambda: setattr(game.control, "tilt", game.control.tilt + 8.0), 1),
                           (lambda: setattr(game.world.sim.state, "sun_angle", game.world.sim.state.sun_angle + 0.3),
                            6)):
        change()
        for _ in range(frames):
            kept = frame(game)
        game.renderer.stage.forget()  # what a fresh drawing shows
        fresh = frame(game)
        assert np.abs(kept - fresh).max() <= 2
    assert game.renderer.samples > 1 or game.renderer.stage.kept.shown is not None  # (the copy was in use)


def test_a_coarse_level_draws_a_prefix_of_the_grown_leaves_and_the_same_picture(game, monkeypatch):
    """The grown leaves go to the GPU sorted by the hash a level keeps them by: drawing only the first
    ones must show exactly what drawing all of them and letting the shader drop the rest shows."""
    game.rules.wind.strength = 0.0
    frame(game)
    buffers = game.renderer.placed[0].buffers
    prefix = Detail.of(buffers, 2, 0.0, 0.5)
    assert 0 < prefix.leaves < 0.7 * buffers.parts["leaf"].count
    monkeypatch.setattr(game.renderer, "_detail", lambda *a: prefix)
    short = frame(game)
    everything = Detail(2, prefix.tubes, buffers.parts["leaf"].count, 0.5, prefix.leaf_grow)
    monkeypatch.setattr(game.renderer, "_detail", lambda *a: everything)
    assert np.abs(frame(game) - short).max() == 0


def test_big_leafy_trees_are_drawn_at_a_lower_resolution_and_laid_over_the_frame(game, monkeypatch):
    game.rules.wind.strength = 0.0
    full = frame(game)
    tree = np.abs(full - frame_without_trees(game)).sum(axis=2) > 30
    monkeypatch.setattr("arbor.game.render.garden.draw_scale", lambda *a: 0.5)
    half = frame(game)
    assert game.renderer.last_scale == 0.5 and game.renderer.pictures.front.size == (SIZE[0] // 2, SIZE[1] // 2)
    assert tree.sum() > 2000
    assert np.abs(half - full)[tree].mean() < 40  # the same tree, softer
    assert np.abs(half - full)[~tree].mean() < 3  # and nothing else changed


def test_a_picture_drawn_over_several_frames_is_the_picture_drawn_at_once(game, monkeypatch):
    """With the camera still, a layered frame draws only a step of the next picture (a share of the
    leaves, the wood, or the shadow map) and shows the last whole one: the result must not differ."""
    game.rules.wind.strength = 0.0
    monkeypatch.setattr("arbor.game.render.garden.draw_scale", lambda *a: 0.5)
    pictures = game.renderer.pictures
    at_once = frame(game)  # the first picture is drawn whole
    first = pictures.shown
    assert sum(into for _, into in first.steps) == 1  # one step drew the trees
    for _ in range(6):
        over_frames = frame(game)
    assert pictures.shown is not first and sum(into for _, into in pictures.shown.steps) == 3
    assert np.abs(over_frames - at_once).max() <= 2


def test_the_trees_follow_the_camera_at_once(game, monkeypatch):
    """A picture drawn for one camera is not shown for another: when the camera turns, that frame
    draws the trees whole for it."""
    game.rules.wind.strength = 0.0
    monkeypatch.setattr("arbor.game.render.garden.draw_scale", lambda *a: 0.5)
    for _ in range(4):
        frame(game)
    game.control.yaw += 20.0  # degrees
    turned = frame(game)
    game.renderer.pictures.release()  # forget every picture: the next frame is drawn from scratch
    fresh = frame(game)
    assert np.abs(turned - fresh).max() <= 2


def test_a_shadow_map_in_use_is_always_whole(gl_ctx):
    """The shadow map is redrawn into a second map, piece by piece, and swapped in at the end."""
    from arbor.game.render.instanced import WHOLE, Piece
    from arbor.game.render.shadows import SHADOW_FRAMES, ShadowMaps

    maps = ShadowMaps(gl_ctx)
    sun, versions = np.array([0.0, 1.0, 0.0]), (1,)
    assert maps.due(sun, versions)
    front, drawn = maps.texture, []
    steps = maps.steps(sun, versions, drawn.append, [Piece(frozenset({"leaf"})), WHOLE])
    steps[0]()
    assert maps.texture is front and maps.key is None and drawn == [Piece(frozenset({"leaf"}))]
    steps[1]()
    assert maps.texture is not front and drawn[-1] == WHOLE and not maps.due(sun, versions)
    assert maps.due(np.array([0.0, 0.9, 0.436]), versions) and maps.due(sun, (2,))
    maps.age = SHADOW_FRAMES
    assert maps.due(sun, versions)


def frame_without_trees(game) -> np.ndarray:
    drawn = game.renderer.trees.draw
    game.renderer.trees.draw = lambda *a, **k: None
    try:
        return frame(game)
    finally:
        game.renderer.trees.draw = drawn


def test_growing_twigs_thinner_than_the_grown_ones_drawn_are_left_out_too(game, monkeypatch):
    """A coarse level leaves out grown twigs under a thickness; growing ones that thin must go as well,
    or they would float where their parents are not drawn."""
    game.rules.wind.strength = 0.0
    frame(game)
    buffers = game.renderer.placed[0].buffers
    assert buffers.parts["tube_young"].count > 0
    monkeypatch.setattr(game.renderer, "_detail", lambda *a: Detail(3, 0, 0, 0.3, 1.0, 0.0))
    with_young = frame(game)
    monkeypatch.setattr(game.renderer, "_detail", lambda *a: Detail(3, 0, 0, 0.3, 1.0, 1e9))
    assert (np.abs(frame(game) - with_young).sum(axis=2) > 30).sum() > 20


def test_a_nearer_tree_gets_finer_detail_and_a_far_one_coarser(game):
    """The level of detail follows the tree's height on screen (not the vertex budget, set out of reach
    here): the finest level close up, the coarsest far away, never coarser as the camera comes nearer."""
    frame(game)  # the trees placed
    game.renderer.vertex_budget = 10**9
    camera = game.camera()
    lods = []
    for factor in (0.25, 0.6, 1.0, 2.5, 6.0):
        near = copy.deepcopy(camera)
        near.distance = camera.distance * factor
        game.renderer.render(game.fbo, near, game.world.sim.sun_direction(), SIZE)
        lods.append(game.renderer.last_details[0].lod)
    assert lods[0] == 0 and lods[-1] == 3
    assert lods == sorted(lods)


def test_a_heavy_tree_is_drawn_over_frames_at_full_resolution_and_looks_as_drawn_at_once(game, monkeypatch):
    """On a software GL a tree costly to draw (LAYER_COST) is drawn as a layer's picture a share a frame, at
    the frame's resolution, smoothed (FXAA) once per picture: the frames must show what drawing it whole in
    every frame shows."""
    from arbor.game.render import garden

    if game.renderer.samples > 1:
        pytest.skip("multisampled: trees are drawn whole every frame")
    game.rules.wind.strength = 0.0
    monkeypatch.setattr(garden, "LAYER_COST", 10**12)
    frame(game)
    at_once = frame(game)
    assert not game.renderer.last_layered and game.renderer.last_scale == 1.0
    monkeypatch.setattr(garden, "LAYER_COST", 0)
    pictures = game.renderer.pictures
    shown = pictures.version
    for _ in range(8):
        over_frames = frame(game)
    assert game.renderer.last_layered and pictures.front.size == SIZE  # a picture at full resolution
    assert pictures.version >= shown + 2 and sum(into for _, into in pictures.shown.steps) >= 3  # drawn in steps
    assert np.abs(over_frames - at_once).max() <= 2
    monkeypatch.setattr(garden, "STEP_COST", 1)  # the most shares of leaves and of wood
    for _ in range(16):
        over_frames = frame(game)
    assert game.renderer.leaf_steps == garden.LEAF_STEPS[1] and game.renderer.wood_steps == garden.WOOD_STEPS
    assert sum(into for _, into in pictures.shown.steps) == garden.LEAF_STEPS[1] + garden.WOOD_STEPS
    assert np.abs(over_frames - at_once).max() <= 2


def _form(shape: np.ndarray) -> np.ndarray:
    """A silhouette's form: the 8-pixel squares it covers at least a fifth of."""
    h, w = shape.shape[0] // 8 * 8, shape.shape[1] // 8 * 8
    return shape[:h, :w].reshape(h // 8, 8, w // 8, 8).mean(axis=(1, 3)) > 0.2


def test_a_coarse_level_covers_the_crown_as_the_finest_does(game, monkeypatch):
    """A coarse level draws a share of the leaves, grown to cover for the rest, and leaves out sub-pixel
    twigs: the tree's silhouette must stay the finest level's (its area from 0.85x to 1.6x, and its form, the
    8-pixel squares it covers, mostly the same)."""
    from arbor.game.render import garden

    game.rules.wind.strength = 0.0
    monkeypatch.setattr(garden, "LAYER_COST", float("inf"))  # (each frame drawn whole: its own level)
    frame(game)
    background = frame_without_trees(game)
    buffers = game.renderer.placed[0].buffers
    shapes = []
    for lod in range(4):
        level = Detail.of(buffers, lod, 0.0, LEAF_KEPT[lod])
        monkeypatch.setattr(game.renderer, "_detail", lambda *a, level=level: level)
        shapes.append(np.abs(frame(game) - background).sum(axis=2) > 30)
    full, full_form = shapes[0], _form(shapes[0])
    assert full.sum() > 3000  # (a crown on screen)
    for lod, shape in enumerate(shapes[1:], start=1):
        form = _form(shape)
        # (measured: area 0.94-1.36x as the trees and their look changed, form 0.57-0.84; with the leaves not
        # grown to cover, area 0.42x at level 3. The narrower sapling of issue 44's crowns: form 0.83, 0.68 and,
        # at level 3, a few big leaves for a hundred, 0.49)
        least = 0.45 if lod == 3 else 0.5
        assert 0.85 < shape.sum() / full.sum() < 1.6 and (form & full_form).sum() / (form | full_form).sum() > least


def test_a_tree_drawn_over_frames_sways_a_picture_later(game, monkeypatch):
    """A tree drawn as a picture over frames shows the wind (and growth) once the next picture is done: a
    few frames late, never frozen."""
    from arbor.game.render import garden

    monkeypatch.setattr(garden, "LAYER_COST", 0)
    game.rules.wind.strength = 2.0
    frame(game)
    pictures = game.renderer.pictures
    shown, shots = pictures.version, []
    for _ in range(10):
        game.fake[0] += 0.25
        shots.append(frame(game))
    assert game.renderer.last_layered and pictures.version >= shown + 2
    assert (np.abs(shots[0] - shots[-1]).sum(axis=2) > 40).sum() > 300  # the twigs moved


def test_a_coarse_level_keeps_its_thickest_segments_round_and_draws_every_other(game, monkeypatch):
    """At a coarse level the thickest grown segments (``fine``) are drawn with level 0's sides and the rest
    from the next record on at the level's: all of the wood is there, and the fine ones are level 0's."""
    from arbor.game.render import garden

    game.rules.wind.strength = 0.0
    monkeypatch.setattr(garden, "LAYER_COST", float("inf"))
    frame(game)
    background = frame_without_trees(game)
    n = game.renderer.placed[0].buffers.parts["tube"].count

    def wood(lod: int, fine: int) -> np.ndarray:
        monkeypatch.setattr(game.renderer, "_detail", lambda *a: Detail(lod, n, 0, 0.3, 1.0, 0.0, fine))
        return frame(game)

    finest, coarse, half, every = wood(0, 0), wood(3, 0), wood(3, n // 2), wood(3, n)
    shape = np.abs(finest - background).sum(axis=2) > 30
    half_shape = np.abs(half - background).sum(axis=2) > 30
    differs = lambda a, b: (np.abs(a - b).sum(axis=2) > 30).sum()  # noqa: E731
    records = game.renderer.placed[0].buffers.parts["tube"].records
    trunk = (records[0, 0:3] + records[0, 9:12]) / 2  # the thickest segment's middle
    x, y = project_points(game.camera(), SIZE, trunk[None])[0].astype(int)
    near = (slice(y - 4, y + 5), slice(x - 4, x + 5))
    assert differs(coarse[near], finest[near]) > 0  # (a 3-sided trunk shows)
    assert differs(every[near], finest[near]) == 0 and differs(half[near], finest[near]) == 0  # round
    assert shape.sum() > 500 and (half_shape & shape).sum() > 0.95 * shape.sum()  # and no segment missing
    assert differs(half, coarse) > 0


def test_a_jump_in_how_the_trees_are_coloured_shows_at_once_in_a_picture_over_frames(game, monkeypatch):
    """A picture over frames shows a slow change of colour a picture late, but a jump (every leaf fallen at
    once, as after time away) is drawn whole in the very frame."""
    from arbor.game.render import garden

    game.rules.wind.strength = 0.0
    monkeypatch.setattr(garden, "LAYER_COST", 0)
    for _ in range(6):
        leafy = frame(game)
    monkeypatch.setattr(game.view, "_season_look", lambda: setattr(game.renderer, "leaf_keep", 0.0))
    bare = frame(game)
    assert game.renderer.last_layered and np.abs(bare - leafy).max() > 30
    monkeypatch.setattr(garden, "LAYER_COST", float("inf"))
    assert np.abs(bare - frame(game)).max() <= 2  # what drawing it whole shows


def test_a_costly_tree_on_the_move_is_drawn_whole_and_over_frames_again_once_still(game, monkeypatch):
    """While the camera moves a costly tree is drawn whole every frame (no picture could be reused); held
    still again it is drawn over frames, and shows the picture it showed before."""
    from arbor.game.render import garden

    game.rules.wind.strength = 0.0
    game.hud.draw = lambda camera: None  # (the scene alone: a drag ends the coach's hint)
    monkeypatch.setattr(garden, "LAYER_COST", 0)
    frame(game)
    still = frame(game)
    for _ in range(3):
        game.control.yaw += 2.0  # degrees a frame: a drag
        frame(game)
        assert not game.renderer.last_layered
    game.control.yaw -= 6.0
    for _ in range(12):
        back = frame(game)
    assert game.renderer.last_layered and game.renderer.pictures.front.size == SIZE
    assert np.abs(back - still).max() <= 2


def test_a_turning_camera_draws_the_backdrop_into_the_frame_as_the_kept_picture_shows_it(game, monkeypatch):
    """On a software GL a frame whose camera moved draws sky, ground, grass and the trees' shadows straight
    into the frame, not into the kept pictures it would copy (game/render/stage.py): the same picture as the
    kept one once the camera holds still, the shadows in it."""
    from arbor.engine.life.plant.sim import sun_angle_at
    from arbor.game.render import garden

    if game.renderer.samples > 1:
        pytest.skip("a multisampled GL draws its backdrop into the frame every frame")
    monkeypatch.setattr(garden, "LAYER_COST", float("inf"))  # (the trees drawn whole, both ways)
    game.rules.wind.strength = 0.0
    game.world.sim.state.sun_angle = sun_angle_at(13 * 3600)  # (shadows on the ground)
    stage = game.renderer.stage
    frame(game)
    game.control.yaw += 10.0
    moving = frame(game)
    assert stage.kept.shown is None  # (no kept picture drawn for a frame whose camera moved)
    still = frame(game)
    assert stage.kept.shown is not None  # (the camera held still: the kept picture, copied)
    assert np.abs(moving - still).max() <= 2
    game.control.yaw -= 10.0
    frame(game)
    monkeypatch.setattr(stage.backdrop, "draw_shadows", lambda *a: None)
    game.control.yaw += 10.0
    unshaded = frame(game)
    assert (unshaded.sum(axis=2) > moving.sum(axis=2) + 20).sum() > 200  # the shadows were in the moving frame
