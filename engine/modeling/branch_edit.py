"""Per-branch editing (issue 48; SpeedTree's and The Grove's per-branch handles): a branch picked on the
tree has its width, its angle or its length changed, the rest of it following rigidly.

A branch is the axis a picked piece lies on, from the axis' first piece (where it leaves its parent, or
the tree's base) and everything growing from it: modules ``[first, end)`` of the L-string, the first
piece's own turn, pitch and width modules included. Edits are module edits, so they save, undo and
export like strokes:

- width: every width ``!`` in the branch times a factor, and the first piece given ``!`` of its shown
  width times the factor (the game draws drawn wood at least as wide as its pipe model needs, so a
  thinner width stops at the pipe model's; grown wood keeps the width its growth gives it);
- angle: the branch turned about its base by a number of degrees away from its parent's axis (toward
  it when negative): a turn, a pitch and a roll before its first piece make its frame the turned one;
- length: every drawn piece in the branch times a factor (grown internodes keep the length their age
  gives them).

Drawn pieces keep their record of where they start, their heading and up (``F``'s parameters 2-10) true
to the edited tree (:func:`refreshed`), so a stroke later joined to them splits them where they are.
"""

from __future__ import annotations

import numpy as np

from arbor.engine.geometry.turtle import Segments, unit
from arbor.engine.geometry.turtle_kernel import TURN_SIGN
from arbor.engine.lsystem import brackets
from arbor.engine.lsystem.lstring import LString, concat, parse_lstring
from arbor.engine.lsystem.text import format_number
from arbor.engine.modeling.modeler import DRAWN, F_PARAMS, aimed

EDITS = ("width", "angle", "length")
WIDTH, ROLL = ord("!"), ord("/")
_PREFIX = np.frombuffer(b"+&!", np.uint8)  # a drawn piece's own modules before its F
LIMITS = {"width": (0.2, 5.0), "angle": (-90.0, 90.0), "length": (0.2, 3.0)}  # one edit's amount at most


def branch_of(segs: Segments, k: int) -> int:
    """The first segment of the axis segment ``k`` lies on (back along the pieces it continues)."""
    while segs.parent[k] >= 0 and segs.continues[k]:
        k = int(segs.parent[k])
    return k


def branch_span(ls: LString, segs: Segments, first: int) -> tuple[int, int]:
    """Modules ``[start, end)`` of the branch whose first segment is ``first``: its first piece's own
    turn, pitch and width modules, the piece and everything growing from it."""
    module = int(segs.module[first])
    start = module
    while start > 0 and ls.sym[start - 1] in _PREFIX and ls.nparams[start - 1] == 1:
        start -= 1
    return start, int(brackets.branch_ends(ls.sym, np.array([module]))[0])


def drawn_in(ls: LString, start: int, end: int) -> np.ndarray:
    """The drawn pieces (modules) in ``[start, end)``."""
    idx = np.arange(start, end)
    return idx[(ls.sym[idx] == DRAWN) & (ls.nparams[idx] == F_PARAMS)]


def edited(ls: LString, segs: Segments, first: int, edit: str, amount: float) -> LString:
    """``ls`` with the branch starting at segment ``first`` edited (see module docstring): ``amount`` is a
    factor for width and length, degrees for angle, clipped to LIMITS."""
    if edit not in EDITS:
        raise ValueError(f"not a branch edit: {edit!r}")
    lo, hi = LIMITS[edit]
    amount = float(np.clip(amount, lo, hi))
    start, end = branch_span(ls, segs, first)
    module = int(segs.module[first])
    index = np.arange(len(ls))
    if edit == "length":
        out = ls.select(np.ones(len(ls), bool))
        pieces = drawn_in(ls, start, end)
        out.params[out.offsets[pieces]] *= amount
        return out
    if edit == "width":
        out = ls.select(np.ones(len(ls), bool))
        widths = np.arange(start, end)
        widths = widths[(ls.sym[widths] == WIDTH) & (ls.nparams[widths] == 1)]
        out.params[out.offsets[widths]] *= amount
        if (ls.sym[start:module] == WIDTH).any():
            return out
        first_width = parse_lstring(f"!({format_number(2.0 * float(segs.radius[first]) * amount)})")
        return concat(out.select(index < module), first_width, out.select(index >= module))
    turned = parse_lstring(_turn(segs, first, amount))
    return concat(ls.select(index < module), turned, ls.select(index >= module))


def _turn(segs: Segments, first: int, degrees: float) -> str:
    """The modules that turn the turtle at segment ``first``'s start by ``degrees`` about the axis at
    right angles to both its parent's heading and its own (away from the parent's axis)."""
    frame = segs.frame[first]
    h = frame[:, 0]
    parent = segs.parent[first]
    above = segs.frame[parent][:, 0] if parent >= 0 else np.array([0.0, 1.0, 0.0])
    axis = np.cross(above, h)
    if np.linalg.norm(axis) < 1e-6:  # a branch along its parent's axis: turned about its own left
        axis = frame[:, 1]
    q = _rotation(unit(axis), np.radians(degrees))
    target = q @ frame
    text, aim = aimed(frame, target[:, 0])
    up_aim, up_target = aim[:, 2], target[:, 2]
    roll = np.degrees(np.arctan2(np.cross(up_target, up_aim) @ target[:, 0], up_aim @ up_target))
    if abs(roll) > 1e-9:
        text += f"/({format_number(float(-roll * TURN_SIGN[ROLL]))})"
    return text


def _rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    """Rodrigues' rotation by ``angle`` (radians) about the unit ``axis``."""
    k = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    return np.eye(3) + np.sin(angle) * k + (1.0 - np.cos(angle)) * k @ k


def refreshed(ls: LString, segs: Segments) -> LString:
    """``ls`` (whose segments are ``segs``) with every drawn piece's record of its start, heading and up
    (``F``'s parameters 2-10) as the turtle draws it."""
    out = ls.select(np.ones(len(ls), bool))
    drawn = np.flatnonzero((ls.sym[segs.module] == DRAWN) & (ls.nparams[segs.module] == F_PARAMS))
    at = out.offsets[segs.module[drawn]][:, None]
    out.params[at + np.arange(1, 4)] = segs.start[drawn]
    out.params[at + np.arange(4, 7)] = segs.frame[drawn][:, :, 0]
    out.params[at + np.arange(7, 10)] = segs.frame[drawn][:, :, 2]
    return out
