import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from arbor.engine.base.assets import assets_dir
from arbor.engine.geometry.turtle import TurtleConfig, interpret
from arbor.engine.lsystem.lstring import parse_lstring
from arbor.engine.lsystem.lsys import load_lsystem
from arbor.engine.modeling.modeler import Modeler, ModelerSettings, nearest_on_segments
from arbor.engine.modeling.strokes import ArcLengthSpline, Stroke, adaptive_sample, curvature, sample_steps


def line(a, b, n=200, seconds=1.0):
    u = np.linspace(0, 1, n)[:, None]
    return Stroke(np.asarray(a) + u * (np.asarray(b) - np.asarray(a)), np.linspace(0, seconds, n))


def spiral(n=500, height=5.0, radius=0.6, turns=2.5, seconds=3.0):
    u = np.linspace(0, 1, n)
    angle = 2 * np.pi * turns * u
    pts = np.stack([radius * np.sin(angle), height * u, radius * (np.cos(angle) - 1)], 1)
    return Stroke(pts, np.linspace(0, seconds, n))


def reconstruction_error(modeler, stroke):
    segs = interpret(modeler.lstring, TurtleConfig(pipe_model=False, leaves_at_tips=0)).segments
    trunk = segs.order == 0
    raw = stroke.points - stroke.points[0]
    from arbor.engine.geometry.turtle import Segments

    main = Segments(**{k: getattr(segs, k)[trunk] for k in segs.__dataclass_fields__})
    return max(nearest_on_segments(p, main)[2] for p in raw) / stroke.length


def test_seed004_steps_run_from_2_to_13():
    assert sample_steps(np.array([1e9, 100.0, 1.0, 0.01, 0.0])).tolist() == [2, 2, 3, 13, 13]
    straight = np.stack([np.zeros(100), np.linspace(0, 10, 100), np.zeros(100)], 1)
    assert np.diff(adaptive_sample(straight))[:-1].tolist() == [13] * 7  # smooth: big steps
    circle = np.stack([np.cos(np.linspace(0, 6, 100)), np.sin(np.linspace(0, 6, 100)), np.zeros(100)], 1) * 0.05
    assert np.diff(adaptive_sample(circle)).max() <= 3  # tight bend (kappa = 20): small steps
    assert curvature(circle)[50] == pytest.approx(20.0, rel=0.01)


def test_arc_length_spline_is_even():
    spline = ArcLengthSpline(np.array([[0, 0, 0], [1, 1, 0], [2, 0, 0], [3, 1, 0.5]], float))
    pts = spline.resample(0.1)
    steps = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    assert steps.max() / steps.min() < 1.02
    np.testing.assert_allclose(pts[[0, -1]], [[0, 0, 0], [3, 1, 0.5]], atol=1e-9)


def test_spiral_trunk_is_reproduced_within_1_percent():
    m, stroke = Modeler(), spiral()
    result = m.add_stroke(stroke)
    assert result.pieces == m.lstring.count("F") and result.pieces > 20
    assert reconstruction_error(m, stroke) < 0.01
    first = m.lstring.module(next(i for i in range(len(m.lstring)) if m.lstring.module(i)[0] == "F"))
    assert len(first[1]) == 11  # F(l, V, H, U, M)


@given(st.integers(0, 10_000))
@settings(max_examples=25, deadline=None)
def test_random_strokes_are_reproduced_within_1_percent(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(50, 400))
    steps = rng.normal(0, 1, (n, 3)) * 0.02 + np.array([0.0, 0.03, 0.0])
    pts = np.cumsum(steps, axis=0)
    pts = np.array([np.convolve(pts[:, c], np.ones(9) / 9, mode="valid") for c in range(3)]).T  # hand-like
    stroke = Stroke(pts, np.linspace(0, n / 100, len(pts)))
    m = Modeler()
    m.add_stroke(stroke)
    assert reconstruction_error(m, stroke) < 0.01


def test_width_is_inversely_proportional_to_speed():
    slow, fast = Modeler(), Modeler()
    slow.add_stroke(line([0, 0, 0], [0, 4, 0], seconds=2.0))  # 2 units/s
    fast.add_stroke(line([0, 0, 0], [0, 4, 0], seconds=1.0))  # 4 units/s
    w_slow = slow.segments().radius.mean()
    w_fast = fast.segments().radius.mean()
    assert w_slow == pytest.approx(2 * w_fast, rel=0.05)
    crazy = Modeler()
    crazy.add_stroke(line([0, 0, 0], [0, 3, 0], seconds=0.01))
    assert crazy.segments().radius.min() >= ModelerSettings().min_width / 2 - 1e-12  # clamped


def test_growth_points_follow_the_density_and_carry_attributes():
    m = Modeler(settings=ModelerSettings(density=(0.0, 0.0, 2.0, 2.0, 2.0)))
    result = m.add_stroke(line([0, 0, 0], [0, 10, 0], n=400, seconds=5.0))
    points = [m.lstring.module(i) for i in range(len(m.lstring)) if m.lstring.module(i)[0] == "A"]
    assert len(points) == result.growth_points
    assert 12.5 * 0.7 < len(points) < 12.5 * 1.3 + 1  # the integral of lambda(s): 10 x (0.25 x 1 + 0.5 x 2)
    heights = [p[1][2] for p in points]
    assert min(heights) > 2.4 and all(len(p[1]) == 5 for p in points)  # A(l, x, y, z, d)
    gaps = np.diff(sorted(heights))
    assert gaps.std() > 0.1 * gaps.mean()  # at random places (Wakabayashi & Durikovic algorithm 2), not a regular comb


def _growth_heights(settings: ModelerSettings, strokes: int = 40) -> np.ndarray:
    heights = []
    for seed in range(strokes):
        m = Modeler(settings=ModelerSettings(density=settings.density, seed=seed))
        m.add_stroke(line([0, 0, 0], [0, 10, 0], n=400, seconds=5.0))
        heights += [m.lstring.module(i)[1][2] for i in range(len(m.lstring)) if m.lstring.module(i)[0] == "A"]
    return np.array(heights)


def test_growth_point_density_is_a_curve_each_species_shapes():
    """lambda(s) from the species' LAM0..LAM4: the poplar's side shoots start low on a drawn trunk and
    are many, the broadleaf keeps a clear bole; along the axis the counts follow the curve."""
    curves = {}
    for name in ("game_tree", "game_poplar"):
        system = load_lsystem(assets_dir() / "lsystems" / f"{name}.lsys")
        curves[name] = ModelerSettings.for_species(system.constants)
    broad, poplar = (_growth_heights(curves[k]) for k in ("game_tree", "game_poplar"))
    print(f"growth points on 40 axes 10 units long: broadleaf {len(broad)} (lowest quarter {np.mean(broad < 2.5):.0%}),"
          f" poplar {len(poplar)} (lowest quarter {np.mean(poplar < 2.5):.0%})")
    assert curves["game_tree"].density != curves["game_poplar"].density
    assert len(poplar) > 1.2 * len(broad)
    assert np.mean(broad < 2.5) < 0.02 < 0.06 < np.mean(poplar < 2.5)  # a clear bole against shoots low down
    for species, heights in ((curves["game_tree"], broad), (curves["game_poplar"], poplar)):
        s = np.linspace(0, 1, 401)
        lam = species.density_at(s)
        for a, b in ((0.0, 0.5), (0.5, 1.0)):  # each half of the axis gets its share of the integral
            inside = (s >= a) & (s <= b)
            expected = 40 * 10 * np.trapezoid(lam[inside], s[inside])
            got = np.sum((heights >= 10 * a) & (heights < 10 * b))
            assert abs(got - expected) < 0.15 * expected + 5, (a, got, expected)


def test_a_density_out_of_range_is_one_clear_error():
    with pytest.raises(ValueError, match="growth-point density"):
        ModelerSettings(density=(0.0, -1.0))
    with pytest.raises(ValueError, match="growth-point density"):
        ModelerSettings(density=(0.0, float("nan")))


def test_branch_snaps_to_the_nearest_point_and_is_bracketed():
    m = Modeler()
    m.add_stroke(line([0, 0, 0], [0, 4, 0], seconds=4.0))
    trunk_text = m.lstring.to_text()
    result = m.add_stroke(line([0.2, 2.03, 0.1], [2.0, 3.5, 0.0], seconds=1.0))
    assert result.snapped_to is not None
    np.testing.assert_allclose(result.snap_point, [0, 2.03, 0], atol=1e-6)
    segs = m.segments()
    branch = segs.order == 1
    np.testing.assert_allclose(segs.start[branch][0], [0, 2.03, 0], atol=1e-6)
    assert m.lstring.count("[") >= 1 and len(m.lstring) > len(parse_lstring(trunk_text))
    trunk_len = np.linalg.norm(segs.end[segs.order == 0] - segs.start[segs.order == 0], axis=1).sum()
    assert trunk_len == pytest.approx(4.0, abs=1e-6)  # the split F keeps the trunk's length


def test_stroke_through_a_trunk_is_bent_around_it():
    m = Modeler(settings=ModelerSettings(density=0.0))
    m.add_stroke(line([0, 0, 0], [0, 4, 0], seconds=8.0))  # thick (slow) trunk
    m.add_stroke(line([0.0, 0.8, 0.0], [-2.0, 1.5, 0.15], seconds=1.0))  # a side branch
    result = m.add_stroke(line([-2.0, 1.5, 0.15], [2.0, 1.5, 0.15], seconds=2.0))  # from its tip, across
    assert result.snapped_to is not None and result.bypassed > 0
    segs = m.segments()
    trunk, new = segs.order == 0, segs.order == 2
    pts = np.concatenate([segs.start[new], segs.end[new]])
    from arbor.engine.geometry.turtle import Segments
    from arbor.engine.modeling.modeler import _segment_distances

    main = Segments(**{k: getattr(segs, k)[trunk] for k in segs.__dataclass_fields__})
    dist, _ = _segment_distances(pts, main)
    clearance = dist - main.radius[None, :] - segs.radius[new].max()
    assert clearance.min() > 0


def test_undo_redo():
    m = Modeler()
    m.add_stroke(line([0, 0, 0], [0, 3, 0]))
    one = m.lstring.to_text()
    m.add_stroke(line([0.05, 1.5, 0], [1, 2, 0]))
    two = m.lstring.to_text()
    assert m.undo() and m.lstring.to_text() == one
    assert m.undo() and len(m.lstring) == 0 and not m.undo()
    assert m.redo() and m.redo() and m.lstring.to_text() == two and not m.redo()


def test_bypass_goes_to_the_emptier_side_when_axes_meet():
    m = Modeler(settings=ModelerSettings(density=0.0))
    m.add_stroke(line([0, 0, 0], [0, 4, 0], seconds=8.0))
    for k in range(3):  # branches crowd the +x side of the trunk
        m.add_stroke(line([0.02, 1.0 + k, 0.0], [1.5, 1.8 + k, 0.0], seconds=1.0))
    m.add_stroke(line([0.0, 2.0, 0.0], [0.0, 3.5, -2.0], seconds=1.0))  # a branch towards -z
    result = m.add_stroke(line([0.0, 3.5, -2.0], [0.0, 3.5, 2.0], seconds=2.0))  # from its tip through the axis
    assert result.bypassed > 0 and result.snapped_to is not None
    segs = m.segments()
    crossing = (segs.order == 2) & (np.abs(segs.start[:, 2]) < 0.3)
    assert crossing.any() and segs.start[crossing, 0].max() < 0  # went round on the empty (-x) side


def test_undo_history_is_bounded():
    modeler = Modeler(lstring=parse_lstring("F"))
    for i in range(modeler.UNDO_LIMIT + 30):
        modeler.commit(parse_lstring(f"F({i})"))
    assert len(modeler.undo_stack) == modeler.UNDO_LIMIT
    while modeler.undo():
        pass
    assert modeler.lstring.equals(parse_lstring("F(29)"))  # the 30 oldest steps were let go
