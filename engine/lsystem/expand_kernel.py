"""The compiled loops behind symbolic.SymbolRewriter's direct steps (imported on a plain system's first step).

A direct step writes each module's successor (its own symbol when no production rewrites it) one after
another. Successors are kept as little-endian 64-bit words padded with zeros, and the output is written a
whole word at a time: the bytes still pending from the previous successor (``fill`` of them, fewer than
8) are merged with the next successor's words by shifts, every word is stored whether or not it is full,
and the write position moves on by the whole words completed. No branch depends on the data, so the loop
costs a few cycles a module instead of a mispredicted jump per successor length.
"""

# numba caches these kernels on disk under this module's name (arbor.engine...) and reloads them while
# this file is unchanged: renaming the module needs a change here too, or the cache names a module gone.

from __future__ import annotations

import numba
import numpy as np


@numba.njit(cache=True, nogil=True)
def measure(sym: np.ndarray, lengths: np.ndarray, ruled: np.ndarray) -> tuple[int, int]:
    """The output length (sum of ``lengths[s]``) and the number of rewritten modules (``ruled[s]``) of
    ``sym``; four running sums, so the additions overlap."""
    t0 = t1 = t2 = t3 = 0
    r0 = r1 = 0
    n = len(sym)
    m = n - n % 4
    for i in range(0, m, 4):
        a, b, c, d = sym[i], sym[i + 1], sym[i + 2], sym[i + 3]
        t0 += lengths[a]
        t1 += lengths[b]
        t2 += lengths[c]
        t3 += lengths[d]
        r0 += ruled[a] + ruled[b]
        r1 += ruled[c] + ruled[d]
    for i in range(m, n):
        t0 += lengths[sym[i]]
        r0 += ruled[sym[i]]
    return t0 + t1 + t2 + t3, r0 + r1


@numba.njit(cache=True, nogil=True)
def expand(sym: np.ndarray, lengths: np.ndarray, words: np.ndarray, out: np.ndarray) -> int:
    """Write the successors of ``sym`` (``words[s]``: W words each) into the words ``out`` (at least
    total // 8 + W + 1 of them); returns the bytes written. Successors of at most 16 bytes (W = 2) take
    a loop where the word that carries over is picked among three registers, so no store is read back."""
    if words.shape[1] == 2:
        return _expand_short(sym, lengths, words, out)
    return _expand_long(sym, lengths, words, out)


@numba.njit(cache=True, nogil=True, inline="always")
def _expand_short(sym: np.ndarray, lengths: np.ndarray, words: np.ndarray, out: np.ndarray) -> int:
    one = np.uint64(1)
    pos, fill, acc = 0, 0, np.uint64(0)
    for i in range(len(sym)):
        s = sym[i]
        w0, w1 = words[s, 0], words[s, 1]
        up, down = np.uint64(8 * fill), np.uint64(63 - 8 * fill)  # (x >> 1) >> down: no shift by 64
        c0 = acc | (w0 << up)
        c1 = ((w0 >> one) >> down) | (w1 << up)
        c2 = (w1 >> one) >> down
        out[pos] = c0
        out[pos + 1] = c1
        out[pos + 2] = c2
        total = fill + lengths[s]
        done = total >> 3
        pos += done
        fill = total & 7
        acc = (c0 if done == 0 else c1 if done == 1 else c2) & ((one << np.uint64(8 * fill)) - one)
    return 8 * pos + fill


@numba.njit(cache=True, nogil=True, inline="always")
def _expand_long(sym: np.ndarray, lengths: np.ndarray, words: np.ndarray, out: np.ndarray) -> int:
    one = np.uint64(1)
    width = words.shape[1]
    pos, fill, acc = 0, 0, np.uint64(0)
    for i in range(len(sym)):
        s = sym[i]
        up, down = np.uint64(8 * fill), np.uint64(63 - 8 * fill)
        carry = acc
        for w in range(width):
            x = words[s, w]
            out[pos + w] = carry | (x << up)
            carry = (x >> one) >> down
        out[pos + width] = carry
        total = fill + lengths[s]
        pos += total >> 3
        fill = total & 7
        acc = out[pos] & ((one << np.uint64(8 * fill)) - one)  # the carried word, read back
    return 8 * pos + fill
