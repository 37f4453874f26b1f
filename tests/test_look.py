"""The look of the game's scene (issue 29): light through a leaf, relief on the bark, the branch collar
and root flare, fruit big enough to see, stars and moon at night."""

import numpy as np
import pytest

from arbor.engine.geometry.instances import LEAF_FLOATS, TUBE_FLOATS, LeafInstances, TubeInstances
from arbor.game.render.camera import OrbitCamera
from arbor.game.render.falling import StaticView
from arbor.game.render.garden import GardenRenderer, Placed
from arbor.game.render.instanced import TreeBuffers
from arbor.game.render.species import GAME_TREE, SpeciesLook, look_of

SIZE = (320, 240)


def drawer(gl_ctx, renderer: GardenRenderer):
    """draw(view, camera, sun) -> the frame's pixels (rows top first), one static tree at the origin."""
    fbo = gl_ctx.framebuffer(color_attachments=[gl_ctx.renderbuffer(SIZE)],
                             depth_attachment=gl_ctx.depth_renderbuffer(SIZE))

    def draw(view: StaticView, camera: OrbitCamera, sun: np.ndarray, look: SpeciesLook = GAME_TREE) -> np.ndarray:
        buffers = TreeBuffers()
        renderer.trees.sync(buffers, view)
        renderer.place([Placed(buffers, np.zeros(3), look=look)], view.lo, view.hi)
        renderer.render(fbo, camera, np.asarray(sun, float), SIZE)
        buffers.release()
        return np.frombuffer(fbo.read(components=3), np.uint8).reshape(SIZE[1], SIZE[0], 3)[::-1].astype(float)

    return draw


@pytest.fixture(scope="module")
def scene(gl_ctx):
    renderer = GardenRenderer(gl_ctx)
    yield renderer, drawer(gl_ctx, renderer)
    renderer.release()


def leaf_view(normal) -> StaticView:
    """One upright leaf card 4 units long at height 3 facing ``normal``."""
    data = np.zeros((1, LEAF_FLOATS), np.float32)
    data[0, 0:3], data[0, 3:6], data[0, 6:9] = (0.0, 3.0, 0.0), (0.0, 1.0, 0.0), normal
    data[0, 9], data[0, 10], data[0, 12] = 4.0, 2.0, 0.5
    return StaticView(TubeInstances.empty(), LeafInstances(data), LeafInstances.empty(),
                      np.array([-2.0, 0.0, -2.0]), np.array([2.0, 7.0, 2.0]))


def card_pixels(image: np.ndarray, sky: np.ndarray) -> np.ndarray:
    """The pixels where the card is (those that differ from the picture without it)."""
    return image[np.abs(image - sky).sum(axis=2) > 30]


def test_a_leaf_against_the_sun_is_brighter_than_an_opaque_card(scene):
    renderer, draw = scene
    camera = OrbitCamera(yaw=0.0, pitch=0.0, distance=9.0, target=np.array([0.0, 5.0, 0.0]))
    to_eye = (camera.eye - camera.target) / np.linalg.norm(camera.eye - camera.target)
    behind = -to_eye + np.array([0.0, 0.35, 0.0])  # the sun low behind the leaf, the viewer looking into it
    view = leaf_view(to_eye)
    empty = StaticView(TubeInstances.empty(), LeafInstances.empty(), LeafInstances.empty(), view.lo, view.hi)
    sky = draw(empty, camera, behind)
    renderer.translucency = 0.0
    opaque = card_pixels(draw(view, camera, behind), sky)
    renderer.translucency = 1.0
    lit = card_pixels(draw(view, camera, behind), sky)
    assert len(opaque) > 500 and len(lit) > 500  # (the card is drawn)
    assert lit.mean(axis=0)[1] > 1.5 * opaque.mean(axis=0)[1]  # green light through the leaf
    front = to_eye + np.array([0.0, 0.35, 0.0])  # sun behind the viewer: nothing comes through
    sky = draw(empty, camera, front)
    renderer.translucency = 0.0
    opaque = card_pixels(draw(view, camera, front), sky)
    renderer.translucency = 1.0
    lit = card_pixels(draw(view, camera, front), sky)
    assert abs(lit.mean() - opaque.mean()) < 2.0


def trunk_view(radius: float = 2.0) -> StaticView:
    """One straight vertical segment 20 units tall (one growth step of bark along it)."""
    data = np.zeros((1, TUBE_FLOATS), np.float32)
    data[0, 0:3], data[0, 3:6], data[0, 6:9] = (0.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 0.0, 0.0)
    data[0, 9:12], data[0, 12:15], data[0, 15:18] = (0.0, 20.0, 0.0), (0.0, 1.0, 0.0), (1.0, 0.0, 0.0)
    data[0, 18:20], data[0, 20:22] = radius, (0.0, 1.0)
    return StaticView(TubeInstances(data, np.zeros(1, np.int64)), LeafInstances.empty(), LeafInstances.empty(),
                      np.array([-radius, 0.0, -radius]), np.array([radius, 20.0, radius]))


def test_the_bark_normal_map_changes_shading_across_a_branch(scene):
    renderer, draw = scene
    camera = OrbitCamera(yaw=0.0, pitch=0.0, distance=9.0, target=np.array([0.0, 10.0, 0.0]))
    side = np.cross(camera.eye - camera.target, [0.0, 1.0, 0.0])
    sun = side / np.linalg.norm(side) + (camera.eye - camera.target) / 9.0 * 0.4 + np.array([0.0, 0.3, 0.0])
    renderer.relief = 0.0
    smooth = draw(trunk_view(), camera, sun).sum(axis=2)
    renderer.relief = 1.0
    relief = draw(trunk_view(), camera, sun).sum(axis=2)
    band = slice(SIZE[1] // 2 - 40, SIZE[1] // 2 + 40)  # rows of the trunk, the middle of the picture
    middle = slice(SIZE[0] // 2 - 30, SIZE[0] // 2 + 30)  # across the trunk's middle
    difference = np.abs(relief[band, middle] - smooth[band, middle])
    assert difference.mean() > 12  # furrows and ridges shade differently from a smooth tube
    # along a smooth tube's line (one normal) the shading is the texture's alone; relief adds to it
    assert relief[band, SIZE[0] // 2].std() > 1.3 * smooth[band, SIZE[0] // 2].std()


def test_two_species_differ_in_bark_and_leaf_colour(scene):
    _, draw = scene
    poplar = look_of("game_poplar")
    assert look_of("game_tree") == GAME_TREE and look_of("a_save_from_the_future") == GAME_TREE
    camera = OrbitCamera(yaw=0.0, pitch=0.0, distance=9.0, target=np.array([0.0, 10.0, 0.0]))
    sun = (camera.eye - camera.target) / 9.0 + np.array([0.3, 0.6, 0.0])  # (lit from the front)
    band = (slice(SIZE[1] // 2 - 40, SIZE[1] // 2 + 40), slice(SIZE[0] // 2 - 20, SIZE[0] // 2 + 20))
    tree_bark, poplar_bark = (draw(trunk_view(), camera, sun, look)[band].reshape(-1, 3).mean(axis=0)
                              for look in (GAME_TREE, poplar))
    assert poplar_bark.mean() > 1.2 * tree_bark.mean()  # the poplar's pale bark
    camera = OrbitCamera(yaw=0.0, pitch=0.0, distance=9.0, target=np.array([0.0, 5.0, 0.0]))
    to_eye = (camera.eye - camera.target) / np.linalg.norm(camera.eye - camera.target)
    view = leaf_view(to_eye)
    empty = StaticView(TubeInstances.empty(), LeafInstances.empty(), LeafInstances.empty(), view.lo, view.hi)
    sky = draw(empty, camera, to_eye + np.array([0.0, 0.5, 0.0]))
    tree_leaf, poplar_leaf = (card_pixels(draw(view, camera, to_eye + np.array([0.0, 0.5, 0.0]), look), sky)
                              for look in (GAME_TREE, poplar))
    assert len(tree_leaf) > 500 and len(poplar_leaf) > 500
    tree_green, poplar_green = tree_leaf.mean(axis=0), poplar_leaf.mean(axis=0)
    assert poplar_green.mean() > 1.1 * tree_green.mean()  # a lighter green ...
    assert poplar_green[0] / poplar_green[1] > 1.1 * tree_green[0] / tree_green[1]  # ... more yellow
    assert abs(len(poplar_leaf) - len(tree_leaf)) > 0.1 * len(tree_leaf)  # other leaves on the card


def twig_view(radius: float, tip=(1.6, 14.0, 2.0)) -> StaticView:
    """One thin straight twig from the ground to ``tip``."""
    data = np.zeros((1, TUBE_FLOATS), np.float32)
    axis = np.asarray(tip) / np.linalg.norm(tip)
    side = np.cross(axis, [0.0, 0.0, 1.0])
    side /= np.linalg.norm(side)
    data[0, 0:3], data[0, 3:6], data[0, 6:9] = (0.0, 0.0, 0.0), axis, side
    data[0, 9:12], data[0, 12:15], data[0, 15:18] = tip, axis, side
    data[0, 18:20], data[0, 20:22] = radius, (0.0, 1.0)
    return StaticView(TubeInstances(data, np.zeros(1, np.int64)), LeafInstances.empty(), LeafInstances.empty(),
                      np.minimum(tip, 0.0) - 0.1, np.maximum(tip, 0.0) + 0.1)


@pytest.mark.parametrize("distance", [12.0, 30.0, 70.0, 140.0])
def test_a_twig_thinner_than_a_pixel_is_an_unbroken_line_at_every_level_of_detail(scene, distance):
    renderer, draw = scene
    renderer.fxaa = False  # (the geometry alone: the edge smoothing would hide gaps)
    camera = OrbitCamera(yaw=0.0, pitch=0.0, distance=distance, target=np.array([0.8, 7.0, 1.0]))
    pixel = 2 * distance * np.tan(np.radians(camera.fov_y) / 2) / SIZE[1]  # (scene units at the twig)
    sun = np.array([0.3, 0.8, 0.5])
    twig = twig_view(0.45 * pixel)  # (drawn: the levels leave out only twigs under 0.35 px)
    background = draw(StaticView(TubeInstances.empty(), LeafInstances.empty(), LeafInstances.empty(), twig.lo,
                                 twig.hi), camera, sun)
    image = draw(twig, camera, sun)
    renderer.fxaa = renderer.samples <= 1
    rows = np.nonzero(np.abs(image - background).sum(axis=2) > 12)[0]
    lod = renderer.last_details[0].lod
    span = np.arange(rows.min() + 1, rows.max())
    assert len(span) > 8, lod
    assert np.isin(span, rows).all(), f"rows without a twig pixel at level {lod}"


def test_a_software_gl_smooths_the_edges_of_the_trees_and_leaves_the_sky_alone(scene):
    renderer, draw = scene
    if renderer.samples > 1:
        pytest.skip("multisampled: no edge smoothing pass")
    camera = OrbitCamera(yaw=0.0, pitch=0.0, distance=30.0, target=np.array([0.8, 7.0, 1.0]))
    pixel = 2 * 30.0 * np.tan(np.radians(camera.fov_y) / 2) / SIZE[1]
    twig, sun = twig_view(1.5 * pixel), np.array([0.3, 0.8, 0.5])
    renderer.fxaa = False
    jagged = draw(twig, camera, sun)
    renderer.fxaa = True
    smooth = draw(twig, camera, sun)
    sky = draw(StaticView(TubeInstances.empty(), LeafInstances.empty(), LeafInstances.empty(), twig.lo, twig.hi),
               camera, sun)
    on_twig = np.abs(jagged - sky).sum(axis=2) > 12
    changed = np.abs(smooth - jagged).sum(axis=2) > 6
    assert not changed[~on_twig].any()  # the sky and ground are not touched
    assert changed[on_twig].mean() > 0.2  # the twig's stair steps are ...
    step = on_twig & changed
    toward = np.abs(smooth[step] - sky[step]).sum(axis=1) < np.abs(jagged[step] - sky[step]).sum(axis=1)
    assert toward.mean() > 0.75  # ... blended toward what lies beside them


def test_shadow_edges_on_the_ground_are_soft(scene):
    renderer, draw = scene
    camera = OrbitCamera(yaw=0.0, pitch=60.0, distance=40.0, target=np.array([10.0, 0.0, 0.0]))
    sun = np.array([-1.0, 1.2, 0.3])
    widths = {}
    for soft in (0.0, 1.0):
        renderer.soft_shadows = soft
        luma = draw(trunk_view(), camera, sun)[50:130, 90:230].mean(axis=2)  # (the ground round the shadow)
        lit, dark = np.percentile(luma, 95), np.percentile(luma, 2)
        assert lit - dark > 20  # (a shadow is there)
        widths[soft] = ((luma > dark + 0.15 * (lit - dark)) & (luma < lit - 0.15 * (lit - dark))).sum()
    renderer.soft_shadows = 1.0
    assert widths[1.0] > 1.5 * widths[0.0]  # more pixels between shade and sun: a soft edge


def test_a_branch_swells_where_it_leaves_its_parent_and_the_trunk_flares_at_its_foot():
    from arbor.engine.geometry.instances import tube_instances
    from arbor.engine.geometry.mesh import wood_rings
    from arbor.engine.geometry.turtle import TurtleConfig, interpret
    from arbor.engine.lsystem.lstring import parse_lstring

    segs = interpret(parse_lstring("!(1)FF[+!(0.5)FF]F"), TurtleConfig(leaves_at_tips=0, pipe_model=False)).segments
    data = tube_instances(segs).data
    ring = wood_rings(segs)
    own = ring.rings.radius[ring.start_ring]  # each segment's start ring as the mesher has it
    lateral = (segs.parent >= 0) & ~segs.continues
    assert lateral.sum() == 1 and (segs.parent < 0).sum() == 1
    assert np.all(data[lateral, 18] > 1.2 * own[lateral])  # the collar: wider than the branch there
    assert np.all(data[segs.parent < 0, 18] > 1.4 * own[segs.parent < 0])  # the root flare
    along = segs.continues & (segs.parent >= 0) & ((segs.order > 0) | (segs.start[:, 1] > 5 * own))
    assert along.sum() >= 1  # (off the trunk's flared foot)
    np.testing.assert_allclose(data[along, 18], own[along])  # elsewhere the rings are the branch's own


def test_an_older_thicker_trunk_flares_wider_and_higher_and_its_rings_still_join():
    """The root flare ages with the trunk: a sapling's is a collar at the ground, an old tree's spreads up
    its foot over several segments, the same on both sides of every joint (no steps)."""
    from arbor.engine.base.units import METRE
    from arbor.engine.geometry.instances import FLARE, tube_instances
    from arbor.engine.geometry.turtle import TurtleConfig, interpret
    from arbor.engine.lsystem.lstring import parse_lstring

    def trunk(radius_m: float) -> np.ndarray:
        text = f"!({2 * radius_m * METRE})" + "F(1)" * 12  # (a width) a trunk of 10 cm segments
        segs = interpret(parse_lstring(text), TurtleConfig(leaves_at_tips=0, pipe_model=False)).segments
        data = tube_instances(segs).data
        np.testing.assert_allclose(data[1:, 18], data[:-1, 19])  # a joint's two rings alike
        return data[:, 18] / (radius_m * METRE)  # each start ring against the trunk's own radius

    young, old = trunk(0.01), trunk(0.2)
    assert young[0] == pytest.approx(FLARE[0], rel=0.02) and old[0] == pytest.approx(FLARE[1], rel=0.02)
    assert young[1] < 1.01 and old[1] > 1.3 and old[2] > 1.1  # 10 and 20 cm up: only the old one still flares
    assert old[-1] < 1.01  # and not up the whole trunk


def test_fruit_is_drawn_at_least_six_pixels_across_however_small(scene):
    _, draw = scene
    fruit = np.zeros((1, LEAF_FLOATS), np.float32)
    fruit[0, 0:3], fruit[0, 9], fruit[0, 10], fruit[0, 12] = (0.0, 3.0, 0.0), 0.01, 1.0, 0.5  # a ripe speck
    view = StaticView(TubeInstances.empty(), LeafInstances.empty(), LeafInstances.empty(),
                      np.array([-2.0, 0.0, -2.0]), np.array([2.0, 6.0, 2.0]), fruits=LeafInstances(fruit))
    camera = OrbitCamera(yaw=0.0, pitch=0.0, distance=60.0, target=np.array([0.0, 3.0, 0.0]))
    image = draw(view, camera, np.array([0.3, 0.8, 0.5]))
    red = (image[..., 0] > image[..., 1] + 40) & (image[..., 0] > image[..., 2] + 40)
    rows, cols = np.nonzero(red)
    assert len(rows) > 0
    assert cols.max() - cols.min() + 1 >= 6 and rows.max() - rows.min() + 1 >= 6  # (a 1 mm speck 60 units away)


def test_a_blossom_is_a_flower_turned_to_the_eye_and_big_enough_to_see_even_when_its_card_is_edge_on(scene):
    _, draw = scene
    blossom = np.zeros((1, LEAF_FLOATS), np.float32)
    blossom[0, 0:3], blossom[0, 3:6], blossom[0, 6:9] = (0.0, 3.0, 0.0), (0.0, 1.0, 0.0), (1.0, 0.0, 0.0)
    blossom[0, 9], blossom[0, 10], blossom[0, 12] = 0.05, 0.05, 0.5  # a small flower on a card seen edge-on
    view = StaticView(TubeInstances.empty(), LeafInstances.empty(), LeafInstances(blossom),
                      np.array([-2.0, 0.0, -2.0]), np.array([2.0, 6.0, 2.0]))
    camera = OrbitCamera(yaw=0.0, pitch=0.0, distance=60.0, target=np.array([0.0, 3.0, 0.0]))
    image = draw(view, camera, np.array([0.3, 0.8, 0.5]))
    pink = (image[..., 0] > image[..., 1] + 25) & (image[..., 2] > image[..., 1])
    rows, cols = np.nonzero(pink)
    assert len(rows) >= 20  # (petals, not a line: the card edge-on showed none)
    assert cols.max() - cols.min() + 1 >= 6 and rows.max() - rows.min() + 1 >= 6  # (a flower in a 9-px card)


def test_the_night_sky_has_stars_and_a_moon_and_the_day_sky_has_neither(scene):
    renderer, draw = scene
    camera = OrbitCamera(yaw=0.0, pitch=0.0, distance=9.0, target=np.array([0.0, 3.0, 0.0]))
    forward = (camera.target - camera.eye) * np.array([1.0, 0.0, 1.0])
    moon = forward / np.linalg.norm(forward) + np.array([0.0, 0.25, 0.0])  # ahead, up in the sky; the sun opposite
    empty = leaf_view((0.0, 0.0, 1.0))
    empty.leaves = LeafInstances.empty()
    night = draw(empty, camera, -moon).sum(axis=2)
    sky = night[: SIZE[1] // 3]
    background = np.median(sky)
    y, x = np.unravel_index(np.argmax(sky), sky.shape)
    rows, cols = np.indices(sky.shape)
    near = (rows - y) ** 2 + (cols - x) ** 2 <= 4**2
    assert sky[near].mean() > background + 150  # the brightest thing is a disc (the moon), not a point
    far = (rows - y) ** 2 + (cols - x) ** 2 > 30**2  # away from the moon and its glow
    assert (sky[far] > background + 60).sum() >= 5  # stars stand out of the dark sky
    clouds, renderer.backdrop.cloud_places = renderer.backdrop.cloud_places, np.zeros((0, 3))  # (clear sky)
    day = draw(empty, camera, -moon * np.array([1.0, -1.0, 1.0])).sum(axis=2)[: SIZE[1] // 3]  # sun behind us
    renderer.backdrop.cloud_places = clouds
    assert (day > np.median(day, axis=1, keepdims=True) + 40).sum() == 0  # a clear day sky: no points in it


def test_grass_sways_in_the_wind_and_stands_still_in_still_air(gl_ctx, scene):
    renderer = GardenRenderer(gl_ctx, samples=4)  # a GPU's path (a software GL keeps its grass still)
    draw = drawer(gl_ctx, renderer)

    camera = OrbitCamera(yaw=0.0, pitch=20.0, distance=30.0, target=np.array([0.0, 5.0, 0.0]))
    sun = np.array([0.3, 0.8, 0.5])
    lower = slice(SIZE[1] * 2 // 3, SIZE[1])  # the ground in front of the trunk
    pictures = {}
    for wind in (0.0, 2.0):
        renderer.wind = np.array([wind, 0.0, 0.0])
        for t in (10.0, 11.3):
            renderer.time = t
            pictures[wind, t] = draw(trunk_view(), camera, sun)[lower]
    renderer.release()
    assert np.array_equal(pictures[0.0, 10.0], pictures[0.0, 11.3])
    moved = np.abs(pictures[2.0, 10.0] - pictures[2.0, 11.3]).sum(axis=2) > 40
    assert moved.sum() > 50  # blades moved
    assert np.abs(pictures[0.0, 10.0] - pictures[2.0, 10.0]).sum(axis=2).max() > 40


def test_clouds_drift_across_the_sky(scene):
    renderer, draw = scene
    camera = OrbitCamera(yaw=0.0, pitch=-5.0, distance=30.0, target=np.array([0.0, 5.0, 0.0]))
    sun = np.array([0.3, 0.8, 0.5])
    skies = []
    for t in (0.0, 0.0, 120.0):
        renderer.time = t
        skies.append(draw(trunk_view(), camera, sun)[: SIZE[1] // 3])
    renderer.time = 0.0
    assert np.array_equal(skies[0], skies[1])
    assert (np.abs(skies[0] - skies[2]).sum(axis=2) > 30).sum() > 100  # two minutes on, the clouds are elsewhere


def test_a_software_gl_keeps_its_grass_in_the_ground_picture(scene):
    renderer, draw = scene
    assert renderer.samples == 1  # (llvmpipe here)
    camera = OrbitCamera(yaw=0.0, pitch=20.0, distance=30.0, target=np.array([0.0, 5.0, 0.0]))
    sun = np.array([0.3, 0.8, 0.5])
    lower = slice(SIZE[1] * 2 // 3, SIZE[1])
    grassy = draw(trunk_view(), camera, sun)[lower]
    blades, renderer.grass.draw = renderer.grass.draw, lambda uniforms, shadowed=True: None
    renderer.grass.version += 1  # (the picture is drawn again, without the grass)
    bare = draw(trunk_view(), camera, sun)[lower]
    renderer.grass.draw = blades
    renderer.grass.version += 1
    assert (np.abs(grassy - bare).sum(axis=2) > 30).sum() > 200  # blades drawn on the ground


def test_a_camera_close_over_a_seedling_sees_no_black_gap_past_the_ground(gl_ctx, tmp_path):
    from arbor.game.screens.game import Game, GameConfig

    size, t = (1280, 720), [0.0]
    game = Game(gl_ctx, size, GameConfig(saves=tmp_path, seed=5, resume=False, title=False, sprout=True),
                clock=lambda: t[0])
    fbo = gl_ctx.framebuffer(color_attachments=[gl_ctx.renderbuffer(size)],
                             depth_attachment=gl_ctx.depth_renderbuffer(size))
    for _ in range(3):
        t[0] += 0.1
        game.update(0.1)
        game.draw(fbo)
    pixels = np.frombuffer(fbo.read(components=3), np.uint8).reshape(size[1], size[0], 3)[::-1].astype(int)
    beside_hud = pixels[250:520, 800:]  # sky, the far edge of the ground, the ground (no HUD text here)
    assert (beside_hud.sum(axis=2) < 40).sum() < 20  # no band of the cleared framebuffer where the disc ends


def test_the_ground_speckle_is_soft_blotches_that_tile_not_a_grid_of_squares():
    from arbor.game.render.backdrop import ground_speckle

    speckle = ground_speckle().astype(float)
    steps = np.abs(np.diff(speckle, axis=1))  # from a texel to the next
    seam = np.abs(speckle[:, 0] - speckle[:, -1]).mean()  # across the tile's edge
    assert speckle.std() > 50  # (as strong a speckle as the random cells it is made of)
    # no jumps between neighbours (cells blown up to squares jump by 140 levels or more at one step in 20)
    assert np.percentile(steps, 95) < 80 and steps.max() < 130
    assert seam < 1.2 * steps.mean()  # and no seam where the tile repeats


def test_a_rock_is_lumpy_stone_with_no_grain_like_bark(scene):
    from arbor.game.render.roots import rocks_view

    _, draw = scene
    view = rocks_view([(0.0, 3.0, 0.0, 2.5)])
    camera = OrbitCamera(yaw=0.0, pitch=0.0, distance=9.0, target=np.array([0.0, 3.0, 0.0]))
    empty = StaticView(TubeInstances.empty(), LeafInstances.empty(), LeafInstances.empty(), view.lo, view.hi)
    sun = np.array([0.4, 0.8, 0.45])
    image = draw(view, camera, sun)
    rock = np.abs(image - draw(empty, camera, sun)).sum(axis=2) > 30
    rows, cols = np.nonzero(rock)
    cy, cx = rows.mean(), cols.mean()
    angle = np.arctan2(rows - cy, cols - cx)
    reach = [np.hypot(rows - cy, cols - cx)[np.abs(angle - a) < 0.1].max() for a in np.linspace(-3.0, 3.0, 24)]
    assert max(reach) > 1.08 * min(reach)  # a lumpy outline, not a disc
    grey = image.sum(axis=2)
    inside = rock[1:-1, 1:-1] & rock[2:, 1:-1] & rock[1:-1, 2:]
    across = np.abs(grey[1:-1, 2:] - grey[1:-1, 1:-1])[inside].mean()  # (from a pixel to the next, each way)
    down = np.abs(grey[2:, 1:-1] - grey[1:-1, 1:-1])[inside].mean()
    assert across > 2.0 and down > 2.0  # a rough surface
    assert max(across, down) < 1.5 * min(across, down)  # the same every way (bark's furrows run one way)
