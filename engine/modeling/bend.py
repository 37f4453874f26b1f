"""Bend down (Onishi et al. 2003 section 5.2's gravitropism edit) in world terms: every branch piece that starts
inside a region turns toward the ground by a few degrees, whatever its turtle frame.

A turn module pair ``+(a)&(b)`` is put before each such piece: the rotation, computed in the piece's own
frame, that takes its heading toward -y by an angle in proportion to its length (a piece already
pointing down stays). Turtle turns are relative, so everything that grows from the piece turns with it.
The drawn pieces' stored start V and frame H, U (Onishi et al. 2003's F parameters) are then rewritten from the
bent tree, so they stay exactly where the turtle draws them.
"""

from __future__ import annotations

import numpy as np

from arbor.engine.geometry.turtle import TurtleConfig, interpret
from arbor.engine.lsystem.lstring import LString, concat, parse_lstring
from arbor.engine.lsystem.text import format_number

DOWN = np.array([0.0, -1.0, 0.0])
WOOD = (ord("F"), ord("I"))
STORED = 11  # F(length, x, y, z, hx, hy, hz, ux, uy, uz, variation): a drawn piece


def bend_region(ls: LString, view: LString, region, degrees: float = 12.0,
                cfg: TurtleConfig | None = None) -> tuple[LString, int]:
    """Bend the pieces of ``ls`` that start inside ``region`` toward the ground by ``degrees`` per unit
    of their length (a long branch bends as much as many short pieces of the same length).
    ``view`` is ``ls`` as drawn (same modules; a grown internode's length from its age). Returns the new
    string and how many pieces were bent."""
    cfg = cfg or TurtleConfig(pipe_model=False, leaves_at_tips=0)
    segs = interpret(view, cfg).segments
    wood = np.isin(view.sym[segs.module], WOOD)
    heading = segs.frame[:, :, 0]
    room = np.degrees(np.arccos(np.clip(heading @ DOWN, -1.0, 1.0)))  # angle left to straight down
    bend = wood & region.contains(segs.start) & (room > 0.5)
    picks = np.flatnonzero(bend)
    if not len(picks):
        return ls, 0
    frames = segs.frame[picks]
    length = np.linalg.norm(segs.end[picks] - segs.start[picks], axis=1)
    angle = np.radians(np.minimum(degrees * length, room[picks]))
    target = _toward_down(frames[:, :, 0], angle)
    local = np.einsum("kij,ki->kj", frames, target)  # the new heading in each piece's (H, L, U)
    turn = np.degrees(np.arctan2(local[:, 1], local[:, 0]))
    pitch = np.degrees(np.arctan2(-local[:, 2], np.hypot(local[:, 0], local[:, 1])))
    at = segs.module[picks]
    order = np.argsort(at, kind="stable")
    index = np.arange(len(ls))
    parts, last = [], 0
    for k in order:
        parts += [ls.select((index >= last) & (index < at[k])),
                  parse_lstring(f"+({format_number(float(turn[k]))})&({format_number(float(pitch[k]))})")]
        last = int(at[k])
    parts.append(ls.select(index >= last))
    return refresh_stored_frames(concat(*parts), cfg), len(picks)


def _toward_down(heading: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """Each heading turned ``angle`` (radians) toward -y, about the horizontal axis across it."""
    axis = np.cross(heading, DOWN)
    norm = np.linalg.norm(axis, axis=1, keepdims=True)
    axis = np.where(norm > 1e-9, axis / np.maximum(norm, 1e-12), np.array([1.0, 0.0, 0.0]))
    c, s = np.cos(angle)[:, None], np.sin(angle)[:, None]
    return heading * c + np.cross(axis, heading) * s + axis * (axis * heading).sum(axis=1, keepdims=True) * (1 - c)


def refresh_stored_frames(ls: LString, cfg: TurtleConfig | None = None) -> LString:
    """Write every drawn piece's start V and frame H, U (its parameters 2-10) from where the turtle
    draws it now."""
    drawn = np.flatnonzero((ls.sym == ord("F")) & (ls.nparams == STORED))
    if not len(drawn):
        return ls
    segs = interpret(ls, cfg or TurtleConfig(pipe_model=False, leaves_at_tips=0)).segments
    row = np.full(len(ls), -1)
    row[segs.module] = np.arange(len(segs))
    drawn = drawn[row[drawn] >= 0]
    params = ls.params.copy()
    off = ls.offsets[drawn]
    r = row[drawn]
    for k in range(3):
        params[off + 1 + k] = segs.start[r, k]
        params[off + 4 + k] = segs.frame[r, k, 0]
        params[off + 7 + k] = segs.frame[r, k, 2]
    return LString(ls.sym, ls.nparams, ls.offsets, params)
