"""The compiled turtle walk behind turtle.interpret: one pass over the string with a bracket stack."""

# numba caches these kernels on disk under this module's name (arbor.engine...) and reloads them while
# this file is unchanged: renaming the module needs a change here too, or the cache names a module gone.

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


# The kernels copy rows element by element, never ``a[i] = b`` or ``a[:n] = b`` between arrays: numba's
# array-to-array assignment (broadcasting, with its error messages built from strings) took most of a cold
# start's compile of walk: 7.7 s of CPU, 3.0 s with the loops (load 8; benchmarks.startup's cold figure).


@numba.njit(cache=True, nogil=True)
def _grown(stack: np.ndarray) -> np.ndarray:
    bigger = np.empty((2 * stack.shape[0], stack.shape[1]), stack.dtype)
    for i in range(stack.shape[0]):
        for j in range(stack.shape[1]):
            bigger[i, j] = stack[i, j]
    return bigger


@numba.njit(cache=True, nogil=True)
def walk(sym, nparams, offsets, params, defaults, initial, tropism, record, n_draw):
    """Interpret the string in one pass (see turtle.interpret for the symbols).

    ``defaults``: angle, step, initial width, bare-'!' factor, whether 'T' bends (1.0) or not;
    ``record``: modules whose incoming state (position, frame) is wanted (leaves, buds, picking).
    Returns per drawn module: start, end, frame, width, colour, bracket depth and the drawn segment it
    grows from; per module: the nearest move strictly before it on its path; per recorded module (in
    string order): its index, position and frame; and (0, -1), or a bracket fault and where: (1, i)
    for a ']' at i with no '[', (2, i) for the '[' at i never closed.
    """
    angle, step, width, factor, bends = defaults[0], defaults[1], defaults[2], defaults[3], defaults[4] > 0
    n = len(sym)
    k = 0
    for i in range(n):
        k += record[i]
    start, end = np.empty((n_draw, 3)), np.empty((n_draw, 3))
    frames, widths, colours = np.empty((n_draw, 3, 3)), np.empty(n_draw), np.empty(n_draw)
    parent, depth, nearest = np.empty(n_draw, np.int64), np.empty(n_draw, np.int64), np.empty(n, np.int64)
    rec_module, rec_pos, rec_frame = np.empty(k, np.int64), np.empty((k, 3)), np.empty((k, 3, 3))
    saved, saved_at = np.empty((16, 14)), np.empty((16, 3), np.int64)  # the state at each open '['
    f, pos, fault = initial.copy(), np.zeros(3), np.zeros(2, np.int64)
    fault[1] = -1
    colour, last_move, last_draw, top, seg, rec = 0.0, -1, -1, 0, 0, 0
    for i in range(n):
        s = sym[i]
        nearest[i] = last_move
        if record[i]:
            rec_module[rec] = i
            for r in range(3):
                rec_pos[rec, r] = pos[r]
                for c in range(3):
                    rec_frame[rec, r, c] = f[r, c]
            rec += 1
        has = nparams[i] > 0
        value = params[offsets[i]] if has else 0.0
        if IS_MOVE[s]:
            length = value if has else step
            if s != MOVE_F:
                for r in range(3):
                    start[seg, r] = pos[r]
                    for c in range(3):
                        frames[seg, r, c] = f[r, c]
                widths[seg], colours[seg], parent[seg], depth[seg] = width, colour, last_draw, top
            for r in range(3):
                pos[r] += f[r, 0] * length
            if s != MOVE_F:
                for r in range(3):
                    end[seg, r] = pos[r]
                last_draw = seg
                seg += 1
            last_move = i
        elif TURN_AXIS[s] >= 0:
            _rotate(f, TURN_AXIS[s], TURN_SIGN[s] * (value if has else angle))
        elif s == OPEN:
            if top == len(saved):
                saved, saved_at = _grown(saved), _grown(saved_at)
            for r in range(3):
                for c in range(3):
                    saved[top, 3 * r + c] = f[r, c]
                saved[top, 9 + r] = pos[r]
            saved[top, 12], saved[top, 13] = width, colour
            saved_at[top, 0], saved_at[top, 1], saved_at[top, 2] = last_move, last_draw, i
            top += 1
        elif s == CLOSE:
            if top == 0:
                fault[0], fault[1] = 1, i
                break
            top -= 1
            for r in range(3):
                for c in range(3):
                    f[r, c] = saved[top, 3 * r + c]
                pos[r] = saved[top, 9 + r]
            width, colour = saved[top, 12], saved[top, 13]
            last_move, last_draw = saved_at[top, 0], saved_at[top, 1]
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
    if fault[0] == 0 and top > 0:
        fault[0], fault[1] = 2, saved_at[top - 1, 2]
    return start, end, frames, widths, colours, depth, parent, nearest, rec_module, rec_pos, rec_frame, fault


@numba.njit(cache=True, nogil=True)
def tip_leaves(frame, end, module, tips, k):
    """Positions and frames of ``k`` leaves at each tip segment (see turtle._tip_leaves): leaf j is
    rolled (module * 37 deg + j/k of a turn) about the twig and pitched 40 deg away from it."""
    cp, sp = math.cos(math.radians(40.0)), math.sin(math.radians(40.0))
    position, out = np.empty((len(tips) * k, 3)), np.empty((len(tips) * k, 3, 3))
    step_c, step_s = np.empty(k), np.empty(k)
    for j in range(k):
        step_c[j], step_s[j] = math.cos(2 * math.pi * j / k), math.sin(2 * math.pi * j / k)
    row = 0
    for t in tips:
        offset = math.radians(module[t] * 37 % 360)
        co, so = math.cos(offset), math.sin(offset)
        for j in range(k):  # roll = offset + j/k of a turn, by the angle-sum formulas
            c, s = co * step_c[j] - so * step_s[j], so * step_c[j] + co * step_s[j]
            for r in range(3):
                h, lft, up = frame[t, r, 0], frame[t, r, 1], frame[t, r, 2]
                side = c * lft + s * up
                out[row, r, 0] = cp * h + sp * side
                out[row, r, 1] = s * lft - c * up
                out[row, r, 2] = cp * side - sp * h
                position[row, r] = end[t, r]
            row += 1
    return position, out
