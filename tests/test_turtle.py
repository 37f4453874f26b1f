import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from arbor.engine.geometry.turtle import INITIAL_FRAME, TurtleConfig, interpret
from arbor.engine.lsystem.lstring import parse_lstring

AXES = {"+": (2, 1), "-": (2, -1), "&": (1, 1), "^": (1, -1), "/": (0, 1), "\\": (0, -1)}


def rot(axis, deg):
    a = math.radians(deg)
    c, s = math.cos(a), math.sin(a)
    m = np.eye(3)
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    m[i, i] = m[j, j] = c
    m[j, i], m[i, j] = s, -s
    return m


def reference_turtle(text, angle=90.0, step=1.0):
    """A plain stack-based turtle: the obvious sequential definition, used as the oracle."""
    ls = parse_lstring(text)
    frame, pos, stack, segs = INITIAL_FRAME.copy(), np.zeros(3), [], []
    for i in range(len(ls)):
        sym, params = ls.module(i)
        value = params[0] if params else None
        if sym in AXES:
            axis, sign = AXES[sym]
            frame = frame @ rot(axis, sign * (angle if value is None else value))
        elif sym == "|":
            frame = frame @ rot(2, 180)
        elif sym in "FGf":
            new = pos + frame[:, 0] * (step if value is None else value)
            if sym != "f":
                segs.append((pos, new, i))
            pos = new
        elif sym == "[":
            stack.append((frame, pos))
        elif sym == "]":
            frame, pos = stack.pop()
    return segs


@st.composite
def turtle_strings(draw):
    parts, depth = [], 0
    for _ in range(draw(st.integers(1, 60))):
        kind = draw(st.sampled_from("FFFf+-&^/\\|[]AX"))
        if kind == "[":
            depth += 1
        elif kind == "]":
            if depth == 0:
                continue
            depth -= 1
        if kind in "Ff+-&^/\\" and draw(st.booleans()):
            kind += f"({draw(st.floats(-180, 180, allow_nan=False)):.3f})"
        parts.append(kind)
    return "".join(parts) + "]" * depth


@given(turtle_strings())
@settings(max_examples=200, deadline=None)
def test_compiled_turtle_matches_sequential_reference(text):
    expected = reference_turtle(text, angle=30.0)
    segs = interpret(parse_lstring(text), TurtleConfig(angle=30.0)).segments
    assert len(segs) == len(expected)
    for k, (a, b, module) in enumerate(expected):
        assert segs.module[k] == module
        np.testing.assert_allclose(segs.start[k], a, atol=1e-9)
        np.testing.assert_allclose(segs.end[k], b, atol=1e-9)


def test_conventions_y_up_and_turns():
    segs = interpret(parse_lstring("F(2)+(90)F&(90)F"), TurtleConfig()).segments
    np.testing.assert_allclose(segs.end[0], [0, 2, 0], atol=1e-12)  # grows along +Y
    np.testing.assert_allclose(segs.end[1], [-1, 2, 0], atol=1e-12)  # '+' turns toward L = -X
    np.testing.assert_allclose(segs.end[2], [-1, 2, -1], atol=1e-12)  # '&' pitches away from U = +Z


def test_roll_to_horizontal():
    result = interpret(parse_lstring("&(30)/(50)$F"))
    left = result.segments.frame[0][:, 1]
    assert abs(left[1]) < 1e-9  # L is horizontal after '$'
    np.testing.assert_allclose(result.segments.frame[0].T @ result.segments.frame[0], np.eye(3), atol=1e-9)


def test_width_colour_order_and_module_index():
    segs = interpret(parse_lstring("!(2)F[!(1)'(3)+F]'F!F"), TurtleConfig(width_factor=0.5)).segments
    np.testing.assert_allclose(segs.radius, [1.0, 0.5, 1.0, 0.5])
    np.testing.assert_allclose(segs.colour, [0, 3, 1, 1])
    assert segs.order.tolist() == [0, 1, 0, 0]
    assert segs.module.tolist() == [1, 6, 9, 11]
    assert segs.parent.tolist() == [-1, 0, 0, 2]
    assert segs.continues.tolist() == [False, False, True, True]


def test_leaves_and_blossoms_are_instances():
    result = interpret(parse_lstring("F[+L(0.5)]FK"), TurtleConfig(leaves_at_tips=0))
    assert len(result.leaves) == 1 and len(result.blossoms) == 1
    np.testing.assert_allclose(result.leaves.position[0], [0, 1, 0], atol=1e-12)
    assert result.leaves.size[0] == 0.5 and result.leaves.module[0] == 3
    np.testing.assert_allclose(result.blossoms.position[0], [0, 2, 0])


def test_pipe_model_radii():
    segs = interpret(parse_lstring("F[+F[F][F]]F[-F]F"), TurtleConfig(width=0.2)).segments
    np.testing.assert_allclose(segs.radius / 0.1, [2, math.sqrt(2), 1, 1, math.sqrt(2), 1, 1])


def test_big_string_is_fine(lsys_dir):
    from arbor.engine.lsystem.derive import derive
    from arbor.engine.lsystem.lsys import load_lsystem

    system = load_lsystem(lsys_dir / "abop_2_8_tree.lsys")
    result = interpret(derive(system, 8), TurtleConfig.from_system(system))
    assert len(result.segments) == 13121
    lo, hi = result.bounds()
    assert lo[1] == pytest.approx(0.0) and hi[1] > 1000


def test_long_chains_of_roll_to_horizontal_stay_rigid():
    # '$' repeated on a long curving branch used to compound rounding into stretched segments
    text = "F(1)[&(50)" + "".join(f"/({k * 137.5})$^(3)F(0.7)" for k in range(60)) + "]"
    segs = interpret(parse_lstring(text), TurtleConfig(pipe_model=False)).segments
    lengths = np.linalg.norm(segs.end - segs.start, axis=1)
    np.testing.assert_allclose(lengths, [1.0] + [0.7] * 60, rtol=1e-9)
    frames = segs.frame
    np.testing.assert_allclose(np.einsum("nij,nik->njk", frames, frames), np.broadcast_to(np.eye(3), frames.shape),
                               atol=1e-9)
    assert np.abs(frames[1:, 1, 1]).max() < 1e-9  # L horizontal after every '$'


def test_tropism_bends_towards_the_vector_and_never_past_it():
    text = "F" + "T(20)F" * 8
    wind = interpret(parse_lstring(text), TurtleConfig(tropism=(1.0, 0.0, 0.0), pipe_model=False)).segments
    headings = wind.frame[:, :, 0]
    tilt = np.degrees(np.arccos(np.clip(headings @ np.array([1.0, 0.0, 0.0]), -1, 1)))
    np.testing.assert_allclose(tilt[:6], [90, 70, 50, 30, 10, 0], atol=1e-6)  # 20 degrees a step, then aligned
    assert tilt.max() <= 90 + 1e-9 and np.allclose(tilt[5:], 0.0, atol=1e-6)
    still = interpret(parse_lstring(text), TurtleConfig(pipe_model=False)).segments
    np.testing.assert_allclose(still.end[-1], [0, 9, 0], atol=1e-12)  # no tropism vector: T does nothing
