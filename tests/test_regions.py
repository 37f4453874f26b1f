import numpy as np
import pytest

from arbor.engine.geometry.turtle import TurtleConfig, interpret, module_positions
from arbor.engine.lsystem.derive import Deriver
from arbor.engine.lsystem.lstring import parse_lstring
from arbor.engine.lsystem.lsys import parse_lsystem
from arbor.engine.modeling.regions import Sphere, Supertoroid, fit_supertoroid, prune, seed_in_region


def test_sphere_inside():
    ball = Sphere((0.0, 2.0, 0.0), 1.0)
    assert ball.contains(np.array([[0, 2, 0], [0.5, 2.5, 0], [0, 3.1, 0]], float)).tolist() == [True, True, False]


def test_supertoroid_surface_and_inside_agree():
    shape = Supertoroid(a_x=2.0, a_y=1.5, a_z=1.0, alpha_y=4.0, n=0.7, e=1.0, slope_x=0.3)
    u, v = np.meshgrid(np.linspace(-1.4, 1.4, 30), np.linspace(-np.pi / 2, np.pi / 2, 30))
    surface = shape.surface(u.ravel(), v.ravel()) * 1.0
    center = np.array([0.0, 4.0, 0.0])
    assert shape.contains(center + 0.97 * (surface - center)).mean() > 0.97  # just inside the surface
    assert not shape.contains(center + 1.05 * (surface - center)).any()  # just outside it
    torus = Supertoroid(a_x=1.0, a_y=0.5, a_z=1.0, alpha_y=0.0, alpha_x=2.0, alpha_z=2.0)
    assert not torus.contains(np.array([[0.0, 0.0, 0.0]]))[0] and torus.contains(np.array([[2.0, 0.0, 0.0]]))[0]


def test_fit_to_two_outline_strokes_recovers_the_shape():
    truth = Supertoroid(a_x=2.0, a_y=2.0, a_z=2.0, alpha_y=5.0, n=0.8, b_x=0.5, slope_x=0.25)
    u = np.linspace(-np.pi / 2 + 0.05, np.pi / 2 - 0.05, 60)
    left = truth.surface(u, np.full_like(u, np.pi))  # v = pi: the x < axis outline (signed cos)
    right = truth.surface(u, np.zeros_like(u))
    fit = fit_supertoroid(left, right)
    assert fit.alpha_y == pytest.approx(5.0, abs=0.05) and fit.a_x == pytest.approx(2.0, rel=0.03)
    assert fit.slope_x == pytest.approx(0.25, abs=0.02) and fit.n == pytest.approx(0.8, abs=0.1)
    pts = np.random.default_rng(0).uniform([-3, 2.5, -3], [4, 7.5, 3], (3000, 3))
    agree = (fit.contains(pts) == truth.contains(pts)).mean()
    assert agree > 0.97


def test_rules_apply_only_inside_the_region():
    system = parse_lsystem("w: F(1)\np1: A -> AB")
    ls = parse_lstring("F(1)[+(90)F(1)A]F(1)[-(90)F(1)A]F(1)A")
    positions = module_positions(ls)
    region = Sphere((1.0, 2.0, 0.0), 0.5)  # around the tip of the '-' branch (towards +x)
    grown, _ = Deriver(system).step(ls, None, only=region.contains(positions))
    assert grown.to_text() == "F(1)[+(90)F(1)A]F(1)[-(90)F(1)AB]F(1)A"  # only the A inside the sphere changed


def test_empty_region_gets_a_new_axis_there():
    ls = parse_lstring("F(2)F(2)")
    seeded = seed_in_region(ls, "F(1)F(1)", np.array([3.0, 1.0, -2.0]))
    segs = interpret(seeded, TurtleConfig(pipe_model=False)).segments
    new = segs.order == 1
    np.testing.assert_allclose(segs.start[new][0], [3.0, 1.0, -2.0], atol=1e-5)
    np.testing.assert_allclose(segs.end[new][-1], [3.0, 3.0, -2.0], atol=1e-4)  # growing straight up
    assert interpret(seeded).segments.end[~new].max(axis=0)[1] == pytest.approx(4.0)  # the tree is untouched


def test_prune_removes_the_subtree_a_touch_picked():
    ls = parse_lstring("F(1)[+F(1)[-F(1)L]F(1)L]F(1)L")
    from arbor.engine.geometry.mesh import wood_mesh

    mesh = wood_mesh(interpret(ls, TurtleConfig(leaves_at_tips=0)).segments, n_surf=4)
    touched = int(mesh.face_module[np.flatnonzero(mesh.face_module == 3)[0]])  # a triangle of the branch
    assert prune(ls, touched).to_text() == "F(1)[+]F(1)L"
    assert prune(ls, 0).to_text() == ""  # pruning the trunk's base removes everything after it


@pytest.mark.parametrize("e, a_z", [(0.5, 1.0), (1.0, 1.4), (1.8, 1.2)])
def test_fit_takes_depth_and_exponent_from_outlines_drawn_in_3d(e, a_z):
    truth = Supertoroid(a_x=2.0, a_y=2.0, a_z=a_z, alpha_y=5.0, n=0.8, e=e, b_x=0.3)
    rng = np.random.default_rng(2)
    u = np.linspace(-np.pi / 2 + 0.1, np.pi / 2 - 0.1, 60)
    wander = 0.7 + 0.6 * np.sin(3 * u)  # a tracker's outlines wander around the crown in depth
    left = truth.surface(u, np.pi - wander) + rng.normal(0, 0.01, (60, 3))
    right = truth.surface(u, -wander) + rng.normal(0, 0.01, (60, 3))
    fit = fit_supertoroid(left, right)
    assert fit.e == pytest.approx(e, abs=0.15) and fit.a_z == pytest.approx(a_z, rel=0.1)
    pts = rng.uniform([-3, 2.5, -2], [4, 7.5, 2], (4000, 3))
    assert (fit.contains(pts) == truth.contains(pts)).mean() > 0.97
    flat = fit_supertoroid(left * [1, 1, 0], right * [1, 1, 0])  # drawn on a plane: no depth to read
    assert flat.a_z == flat.a_x and flat.e == 1.0


def test_regions_move_and_resize():
    from arbor.engine.modeling.regions import moved_region, scaled_region

    ball = moved_region(Sphere((0.0, 2.0, 0.0), 1.0), (1.0, 0.5, 0.0))
    assert ball.center == (1.0, 2.5, 0.0) and scaled_region(ball, 2.0).radius == 2.0
    crown = Supertoroid(a_x=2.0, a_y=1.0, a_z=2.0, alpha_y=4.0)
    bigger = scaled_region(moved_region(crown, (0.0, 1.0, 0.0)), 1.5)
    assert bigger.center == (0.0, 5.0, 0.0) and bigger.a_x == 3.0 and bigger.contains(np.array([[2.8, 5.0, 0.0]]))[0]


def hand_outline(rng, across, side, spacing, height=3.0, base=1.0, points=40, jitter=0.015):
    """A messy mouse outline on the vertical plane through the axis facing a camera whose right is
    ``across``: a slightly leaning, wavering line ``spacing`` / 2 to the ``side`` (-1 left, +1 right),
    with hand jitter of ``jitter`` of the outline's height (a wobble plus per-point noise)."""
    s = np.sort(rng.uniform(0.0, 1.0, points))
    wobble = np.convolve(rng.normal(0, 1, points + 8), np.ones(9) / 3, "valid")  # slow hand drift
    t = side * spacing / 2 + 0.1 * (s - 0.5) + jitter * height * (0.6 * wobble + 0.6 * rng.normal(0, 1, points))
    y = base + height * s + jitter * height * rng.normal(0, 1, points)
    return t[:, None] * np.asarray(across) + y[:, None] * np.array([0.0, 1.0, 0.0])


def right_of(yaw):
    """An OrbitCamera's right for ``yaw`` degrees (game/render/camera.py: eye at (sin, ., cos) * distance)."""
    t = np.radians(yaw)
    return np.array([np.cos(t), 0.0, -np.sin(t)])


@pytest.mark.parametrize("yaw", [255.0, 30.0, 140.0])  # the game's default view and two others
def test_outlines_drawn_in_a_view_give_a_region_as_wide_as_their_spacing(yaw):
    rng = np.random.default_rng(int(yaw))
    across, spacing = right_of(yaw), 2.6
    left, right = hand_outline(rng, across, -1, spacing), hand_outline(rng, across, 1, spacing)
    region = fit_supertoroid(left, right, across=across)
    width = 2 * region.a_x
    print(f"yaw {yaw:.0f}: outlines {spacing} apart -> region {width:.2f} wide ({width / spacing - 1:+.1%})")
    assert width == pytest.approx(spacing, rel=0.15)
    t, y = np.meshgrid(np.linspace(-0.4, 0.4, 9) * spacing, np.linspace(1.5, 3.5, 9))
    between = t.reshape(-1, 1) * across + y.reshape(-1, 1) * [0.0, 1.0, 0.0]
    assert region.contains(between).mean() > 0.95  # what was drawn between the outlines is inside
    beside = np.array([k * 0.75 * spacing * across + [0.0, 2.5, 0.0] for k in (-1, 1)])
    assert not region.contains(beside).any()  # and what is clearly beside them is not
    deep = np.array([0.5 * region.a_z * np.cross(across, [0.0, 1.0, 0.0]) + [0.0, 2.5, 0.0]])
    assert region.a_z == pytest.approx(region.a_x) and region.contains(deep)[0]  # round: as deep as wide


def test_a_turned_supertoroid_moves_and_scales_like_the_view_it_was_drawn_in():
    from arbor.engine.modeling.regions import moved_region, scaled_region

    plain = Supertoroid(a_x=2.0, a_y=1.5, a_z=0.8, alpha_y=4.0, n=0.7, b_x=0.5, slope_x=0.3)
    turned = Supertoroid(a_x=2.0, a_y=1.5, a_z=0.8, alpha_y=4.0, n=0.7, b_x=0.5, slope_x=0.3, yaw=90.0)
    u, v = np.meshgrid(np.linspace(-1.4, 1.4, 20), np.linspace(-np.pi, np.pi, 20))
    turn = np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]])  # x -> -z, z -> x: 90 deg about y
    centre = np.array([0.5, 0.0, 0.0])
    expect = (plain.surface(u, v) - centre) @ turn.T + centre
    np.testing.assert_allclose(turned.surface(u, v), expect, atol=1e-9)
    pts = np.random.default_rng(4).uniform([-3, 2, -3], [4, 6, 3], (3000, 3))
    assert (turned.contains(pts) == plain.contains((pts - centre) @ turn + centre)).all()
    assert turned.contains(np.array([[0.5, 4.0, -1.9]]))[0] and not turned.contains(np.array([[2.4, 4.0, 0.0]]))[0]
    moved = scaled_region(moved_region(turned, (1.0, 0.5, 0.0)), 1.5)
    assert moved.yaw == 90.0 and moved.center == (1.5, 4.5, 0.0) and moved.contains(np.array([[1.5, 4.5, -2.8]]))[0]
