"""The symbols tool's supertoroid regions in the real game: messy mouse outlines drawn in the view give a
region as wide as they are apart (at the default view and two others), and only a drag from the
centre handle or well inside moves a region, so a new one can be started right beside it."""

import numpy as np
import pytest

from arbor.engine.modeling.regions import Sphere, Supertoroid
from arbor.game.input.events import DOWN, MOUSE_ID, MOVE, UP, InputEvent
from arbor.game.render.camera import project_points
from arbor.game.tools.region import HANDLE_PIXELS

SIZE = (1280, 720)


@pytest.fixture
def game(modeler_game):
    return modeler_game(seed=5)


def mouse(game, kind, x, y):
    game.handle_input(InputEvent(kind, game.clock_box[0], "mouse", MOUSE_ID, float(x), float(y)))


def drag(game, pixels, dt=0.02):
    """A mouse drag through window ``pixels``."""
    mouse(game, DOWN, *pixels[0])
    for p in pixels[1:]:
        game.clock_box[0] += dt
        mouse(game, MOVE, *p)
    game.clock_box[0] += dt
    mouse(game, UP, *pixels[-1])


def symbols_tool(game):
    game.tap(100, 100)
    center = game.menu.reveal("symbols").rect.center
    mouse(game, DOWN, *center)
    mouse(game, UP, *center)
    if game.menu.visible:  # (a tool pressed in the modeler closes it itself)
        game.tap(1200, 700)
    assert game.modeling.symbols and not game.menu.visible


def hand_outline(rng, across, side, spacing, height, base=0.9, points=40, jitter=0.015):
    """A messy outline on the drawing plane (vertical, through the tree's axis, facing the camera whose
    right is ``across``): ``spacing`` / 2 to the ``side``, slightly leaning and wavering, with hand jitter
    of ``jitter`` of its height (a slow drift plus per-point noise). Returns (world points, offsets
    across the view)."""
    s = np.sort(rng.uniform(0.0, 1.0, points))
    wobble = np.convolve(rng.normal(0, 1, points + 8), np.ones(9) / 3, "valid")
    t = side * spacing / 2 + 0.08 * (s - 0.5) + jitter * height * (0.6 * wobble + 0.6 * rng.normal(0, 1, points))
    y = base + height * s + jitter * height * rng.normal(0, 1, points)
    return t[:, None] * across + y[:, None] * np.array([0.0, 1.0, 0.0]), t


def outlines(game, spacing, height, seed=0, jitter=0.015):
    """Draw two messy outlines with the mouse; returns the measured spacing of what was drawn."""
    camera = game.camera()
    across = camera.view()[0, :3]
    rng = np.random.default_rng(seed)
    gaps = []
    for side in (-1, 1):
        world, t = hand_outline(rng, across, side, spacing, height, jitter=jitter)
        drag(game, [tuple(p) for p in project_points(camera, SIZE, world)])
        gaps.append(t.mean())
    return gaps[1] - gaps[0]


@pytest.mark.parametrize("yaw", [None, 30.0, 140.0])  # the game's default view (255 deg) and two others
def test_mouse_outlines_give_a_region_as_wide_as_they_are_apart(game, yaw):
    if yaw is not None:
        game.control.yaw = yaw
    symbols_tool(game)
    spacing = outlines(game, 2.6, 2.6)
    region = game.modeling.region_tool.region
    assert isinstance(region, Supertoroid) and "two outlines" in game.hud_info().message
    width = 2 * region.a_x
    across = game.camera().view()[0, :3]
    t, y = np.meshgrid(np.linspace(-0.4, 0.4, 9) * spacing, np.linspace(1.4, 3.0, 9))
    between = t.reshape(-1, 1) * across + y.reshape(-1, 1) * [0.0, 1.0, 0.0]
    inside = region.contains(between).mean()
    print(f"\nview yaw {game.control.yaw:.0f} deg: mouse outlines {spacing:.2f} apart -> region {width:.2f} wide "
          f"({width / spacing - 1:+.1%}); {inside:.0%} of the points between them inside")
    assert width == pytest.approx(spacing, rel=0.15)
    assert inside > 0.95  # what was drawn between the outlines is inside


def region_pixels(game):
    """The region's centre and its rim across and up the view, in window pixels."""
    camera, region = game.camera(), game.modeling.region_tool.region
    across = camera.view()[0, :3]
    c = np.asarray(region.center, float)
    up = np.array([0.0, region.a_y, 0.0])
    centre, side, top = project_points(camera, SIZE, np.stack([c, c + region.a_x * across, c + up]))
    return centre, side[0] - centre[0], centre[1] - top[1]


def tall_region(game):
    """The symbols tool with a tall region (twice as high as wide) from messy mouse outlines."""
    symbols_tool(game)
    outlines(game, 1.2, 2.8)
    _, across, up = region_pixels(game)
    assert isinstance(game.modeling.region_tool.region, Supertoroid) and up > 1.8 * across > 100
    return game.modeling.region_tool


def test_a_drag_well_inside_a_region_moves_it_and_one_from_its_rim_resizes_it(game):
    tool = tall_region(game)
    first = tool.region
    (cx, cy), across, up = region_pixels(game)
    drag(game, [(cx, cy - 0.45 * up), (cx + 20, cy - 0.45 * up), (cx + 60, cy - 0.45 * up)])  # well inside: moves
    moved = tool.region
    assert moved.a_x == first.a_x and moved.center[1] == pytest.approx(first.center[1], abs=0.05)
    assert np.linalg.norm(np.subtract(moved.center, first.center)) > 0.2
    (cx, cy), across, up = region_pixels(game)
    drag(game, [(cx + 0.85 * across, cy), (cx + 1.1 * across, cy), (cx + 1.4 * across, cy)])  # the rim: resizes
    bigger = tool.region
    assert bigger.a_x > 1.3 * moved.a_x and bigger.center == pytest.approx(moved.center)


def test_a_drag_beside_a_region_starts_a_new_one(game):
    tool = tall_region(game)
    (cx, cy), across, _ = region_pixels(game)
    start = (cx + across + 40, cy)  # 40 px beside its rim (old code: within 1.15x its height, so it moved)
    drag(game, [start, (start[0] + 10, start[1] - 20), (start[0] + 20, start[1] - 40)])
    assert isinstance(tool.region, Sphere)  # a new region, placed where the drag went
    placed = project_points(game.camera(), SIZE, np.array([tool.region.center]))[0]
    assert np.hypot(*(placed - (start[0] + 20, start[1] - 40))) < 3


def test_the_centre_handle_moves_a_region_too_thin_to_grab_inside(game):
    symbols_tool(game)
    outlines(game, 0.18, 2.4, jitter=0.004)  # a thin region: a couple of handles across
    tool = game.modeling.region_tool
    first = tool.region
    (cx, cy), across, _ = region_pixels(game)
    assert isinstance(first, Supertoroid) and 0.6 * across < 0.8 * HANDLE_PIXELS < across
    drag(game, [(cx + 0.8 * HANDLE_PIXELS, cy), (cx + 30, cy - 10), (cx + 60, cy - 20)])  # on the handle: moves
    assert tool.region.a_x == first.a_x and tool.region.center != first.center


def test_no_sphere_follows_an_outline_being_drawn(game):
    symbols_tool(game)
    camera = game.camera()
    world, _ = hand_outline(np.random.default_rng(3), camera.view()[0, :3], -1, 2.0, 2.4)
    pixels = project_points(camera, SIZE, world)
    mouse(game, DOWN, *pixels[0])
    for p in pixels[1:]:
        game.clock_box[0] += 0.02
        mouse(game, MOVE, *p)
    assert game.modeling.region_tool.region is None  # the outline shows, not a sphere left at its start
    mouse(game, UP, *pixels[-1])
    assert game.modeling.region_tool.region is None and "outline" in game.hud_info().message
