"""The compiled turtle walk behind turtle.interpret: one pass over the string with a bracket stack."""

from __future__ import annotations

import math

import numba
import numpy as np

OPEN, CLOSE = 91, 93  # '[' and ']'
MOVE_F = ord("f")  # moves without drawing; 'F' and 'G' draw
IS_MOVE = np.zeros(256, np.bool_)
IS_MOVE[[ord("F"), ord("G"), MOVE_F]] = True
TURN_AXIS = np.full(256, -1, np.int64)  # local axis a turn symbol rotates about (0 H, 1 L, 2 U)
TURN_SIGN = np.zeros(256)
for _sym, _axis, _sign in (("+", 2, 1.0), ("-", 2, -1.0), ("&", 1, 1.0), ("^", 1, -1.0), ("/", 0, 1.0),
                           ("\\", 0, -1.0)):
    TURN_AXIS[ord(_sym)], TURN_SIGN[ord(_sym)] = _axis, _sign
AROUND, ROLL_LEVEL, TROPISM, WIDTH, COLOUR = ord("|"), ord("$"), ord("T"), ord("!"), ord("'")


@numba.njit(cache=True, nogil=True, inline="always")
def _rotate(f: np.ndarray, axis: int, degrees: float) -> None:
    """Turn the frame ``f`` (columns H, L, U) about its own axis ``axis`` by ``degrees``."""
    i, j = (axis + 1) % 3, (axis + 2) % 3
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    for r in range(3):
        a, b = f[r, i], f[r, j]
        f[r, i] = c * a + s * b
        f[r, j] = c * b - s * a


@numba.njit(cache=True, nogil=True)
def _roll_level(f: np.ndarray) -> None:
    """ABOP '$': roll about H so that L is horizontal, L = (V x H) / |V x H| with V = +Y."""
    hn = math.sqrt(f[0, 0] ** 2 + f[1, 0] ** 2 + f[2, 0] ** 2)
    hx, hy, hz = f[0, 0] / hn, f[1, 0] / hn, f[2, 0] / hn
    lx, ly, lz = hz, 0.0, -hx  # (0, 1, 0) x h
    ln = math.sqrt(lx * lx + lz * lz)
    if ln > 1e-9:
        lx, lz = lx / ln, lz / ln
    else:  # heading vertical: keep L
        ln = math.sqrt(f[0, 1] ** 2 + f[1, 1] ** 2 + f[2, 1] ** 2)
        lx, ly, lz = f[0, 1] / ln, f[1, 1] / ln, f[2, 1] / ln
    f[0, 0], f[1, 0], f[2, 0] = hx, hy, hz
    f[0, 1], f[1, 1], f[2, 1] = lx, ly, lz
    f[0, 2], f[1, 2], f[2, 2] = hy * lz - hz * ly, hz * lx - hx * lz, hx * ly - hy * lx


@numba.njit(cache=True, nogil=True)
def _bend(f: np.ndarray, target: np.ndarray, degrees: float) -> None:
    """ABOP tropism 'T(a)': turn the heading a degrees towards the unit vector ``target``, never past it
    (a rotation of the whole frame about H x target, Rodrigues' formula)."""
    hn = math.sqrt(f[0, 0] ** 2 + f[1, 0] ** 2 + f[2, 0] ** 2)
    hx, hy, hz = f[0, 0] / hn, f[1, 0] / hn, f[2, 0] / hn
    kx, ky, kz = hy * target[2] - hz * target[1], hz * target[0] - hx * target[2], hx * target[1] - hy * target[0]
    sin = math.sqrt(kx * kx + ky * ky + kz * kz)
    between = math.degrees(math.atan2(sin, hx * target[0] + hy * target[1] + hz * target[2]))
    turn = math.radians(min(max(degrees, -between), between))
    if sin > 1e-9:
        kx, ky, kz = kx / sin, ky / sin, kz / sin
    else:  # heading along the target (or against it): turn about L
        ln = math.sqrt(f[0, 1] ** 2 + f[1, 1] ** 2 + f[2, 1] ** 2)
        kx, ky, kz = f[0, 1] / ln, f[1, 1] / ln, f[2, 1] / ln
    c, s = math.cos(turn), math.sin(turn)
    for col in range(3):
        vx, vy, vz = f[0, col], f[1, col], f[2, col]
        dot = (kx * vx + ky * vy + kz * vz) * (1 - c)
        f[0, col] = vx * c + (ky * vz - kz * vy) * s + kx * dot
        f[1, col] = vy * c + (kz * vx - kx * vz) * s + ky * dot
        f[2, col] = vz * c + (kx * vy - ky * vx) * s + kz * dot


@numba.njit(cache=True, nogil=True)
def walk(sym, nparams, offsets, params, defaults, initial, tropism, record, n_draw, max_depth):
    """Interpret the string in one pass (see turtle.interpret for the symbols).

    ``defaults``: angle, step, initial width, bare-'!' factor, whether 'T' bends (1.0) or not;
    ``record``: modules whose incoming state (position, frame) is wanted (leaves, buds, picking).
    Returns per drawn module: start, end, frame, width, colour, parent drawn segment on the path; per
    module: the nearest move strictly before it on its path; per recorded module: position, frame.
    """
    angle, step, width, factor, bends = defaults[0], defaults[1], defaults[2], defaults[3], defaults[4] > 0
    n = len(sym)
    k = 0
    for i in range(n):
        k += record[i]
    start, end = np.empty((n_draw, 3)), np.empty((n_draw, 3))
    frames, widths, colours = np.empty((n_draw, 3, 3)), np.empty(n_draw), np.empty(n_draw)
    parent, nearest = np.empty(n_draw, np.int64), np.empty(n, np.int64)
    rec_pos, rec_frame = np.empty((k, 3)), np.empty((k, 3, 3))
    s_frame, s_pos = np.empty((max_depth + 1, 3, 3)), np.empty((max_depth + 1, 3))
    s_scalar, s_index = np.empty((max_depth + 1, 2)), np.empty((max_depth + 1, 2), np.int64)
    f, pos = initial.copy(), np.zeros(3)
    colour, last_move, last_draw, top, seg, rec = 0.0, -1, -1, 0, 0, 0
    for i in range(n):
        s = sym[i]
        nearest[i] = last_move
        if record[i]:
            rec_pos[rec] = pos
            rec_frame[rec] = f
            rec += 1
        has = nparams[i] > 0
        value = params[offsets[i]] if has else 0.0
        if IS_MOVE[s]:
            length = value if has else step
            if s != MOVE_F:
                start[seg] = pos
                frames[seg] = f
                widths[seg], colours[seg], parent[seg] = width, colour, last_draw
            for r in range(3):
                pos[r] += f[r, 0] * length
            if s != MOVE_F:
                end[seg] = pos
                last_draw = seg
                seg += 1
            last_move = i
        elif TURN_AXIS[s] >= 0:
            _rotate(f, TURN_AXIS[s], TURN_SIGN[s] * (value if has else angle))
        elif s == OPEN:
            s_frame[top], s_pos[top] = f, pos
            s_scalar[top, 0], s_scalar[top, 1] = width, colour
            s_index[top, 0], s_index[top, 1] = last_move, last_draw
            top += 1
        elif s == CLOSE:
            top -= 1
            f[:], pos[:] = s_frame[top], s_pos[top]
            width, colour = s_scalar[top, 0], s_scalar[top, 1]
            last_move, last_draw = s_index[top, 0], s_index[top, 1]
        elif s == AROUND:
            _rotate(f, 2, 180.0)
        elif s == ROLL_LEVEL:
            _roll_level(f)
        elif s == TROPISM and bends:
            _bend(f, tropism, value)
        elif s == WIDTH:
            width = value if has else width * factor
        elif s == COLOUR:
            colour = value if has else colour + 1.0
    return start, end, frames, widths, colours, parent, nearest, rec_pos, rec_frame


@numba.njit(cache=True, nogil=True)
def tip_leaves(frame, end, module, tips, k):
    """Positions and frames of ``k`` leaves at each tip segment (see turtle._tip_leaves): leaf j is
    rolled (module * 37 deg + j/k of a turn) about the twig and pitched 40 deg away from it."""
    cp, sp = math.cos(math.radians(40.0)), math.sin(math.radians(40.0))
    position, out = np.empty((len(tips) * k, 3)), np.empty((len(tips) * k, 3, 3))
    row = 0
    for t in tips:
        offset = math.radians(module[t] * 37 % 360)
        for j in range(k):
            roll = offset + 2 * math.pi * j / k
            c, s = math.cos(roll), math.sin(roll)
            for r in range(3):
                h, lft, up = frame[t, r, 0], frame[t, r, 1], frame[t, r, 2]
                side = c * lft + s * up
                out[row, r, 0] = cp * h + sp * side
                out[row, r, 1] = s * lft - c * up
                out[row, r, 2] = cp * side - sp * h
                position[row, r] = end[t, r]
            row += 1
    return position, out
