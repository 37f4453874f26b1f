"""The compiled loops behind symbolic.SymbolRewriter's direct steps (imported on a plain system's first step).

A direct step writes each module's successor (its own symbol when no production rewrites it) one after
another. Successors are kept as little-endian 64-bit words padded with zeros, and the output is written a
whole word at a time: the bytes still pending from the previous successor (``fill`` of them, fewer than
8) are merged with the next successor's words by shifts, every word is stored whether or not it is full,
and the write position moves on by the whole words completed. No branch depends on the data, so the loop
costs a few cycles a module instead of a mispredicted jump per successor length. The block step
(expand_blocks) instead stores each block's expansion 32 bytes at a time at any byte position (unaligned
stores, _store_u64): no bytes carried from one block to the next, so blocks are written back to back.
"""

# numba caches these kernels on disk under this module's name (arbor.engine...) and reloads them while
# this file is unchanged: renaming the module needs a change here too, or the cache names a module gone.

from __future__ import annotations

import numba
import numpy as np
from llvmlite import ir
from numba import types
from numba.extending import intrinsic


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


@intrinsic
def _store_u64(typingctx, arr, idx, val):
    """Store the 64-bit ``val`` at byte ``idx`` of the uint8 array ``arr``, aligned or not (one move on
    the CPUs numba targets; the caller keeps idx + 8 inside the array)."""
    def codegen(context, builder, signature, args):
        ary = context.make_array(signature.args[0])(context, builder, args[0])
        store = builder.store(args[2], builder.bitcast(builder.gep(ary.data, [args[1]]),
                                                       ir.IntType(64).as_pointer()))
        store.align = 1
        return context.get_dummy_value()
    return types.void(arr, types.int64, types.uint64), codegen


BLOCK = 8  # modules a block: read as one 64-bit word
_GOLDEN = np.uint64(0x9E3779B97F4A7C15)


@numba.njit(cache=True, nogil=True, inline="always")
def _append(out, pos, fill, acc, src, start, nbytes):
    """Write ``nbytes`` bytes held in the words ``src[start:]`` after the ``fill`` bytes pending in
    ``acc`` at word ``pos`` of ``out``; the new (pos, fill, acc). Bytes past the end are overwritten by
    the next append (``acc`` keeps only the pending ones)."""
    one = np.uint64(1)
    up, down = np.uint64(8 * fill), np.uint64(63 - 8 * fill)
    carry = acc
    count = (nbytes + 7) >> 3
    for w in range(count):
        x = src[start + w]
        out[pos + w] = carry | (x << up)
        carry = (x >> one) >> down
    out[pos + count] = carry
    total = fill + nbytes
    pos += total >> 3
    fill = total & 7
    return pos, fill, out[pos] & ((one << np.uint64(8 * fill)) - one)


@numba.njit(cache=True, nogil=True)
def expand_blocks(sym: np.ndarray, lengths: np.ndarray, ruled: np.ndarray, words: np.ndarray, most: int,
                  budget: int) -> tuple[np.ndarray, int, int]:  # little-endian machines only
    """A whole direct step a block of BLOCK modules at a time: L-strings repeat their blocks, so each
    distinct block is expanded once (found again by its 64-bit word in a hash table) and then copied
    whole words at a time. A first pass finds every block's expansion and adds up the output length and
    the rewritten modules (``ruled[s]``); when that length fits ``budget``, a second pass writes the
    output, allocated to its length. Returns (output words, bytes written, rewritten modules); the
    output is empty when the step exceeds the budget, and the length is -1 when more than ``most``
    blocks are distinct (then the module-at-a-time loop is the faster one)."""
    whole = len(sym) // BLOCK
    width = words.shape[1]
    if whole == 0:  # shorter than a block: nothing to share (the module-at-a-time loops)
        total, rewritten = measure(sym, lengths, ruled)
        out = np.empty(8 * (total // 8 + width + 2), np.uint8)
        if total <= budget:
            expand(sym, lengths, words, out.view(np.uint64))
        return out, total, rewritten
    flat = words.ravel()
    keys = sym[:whole * BLOCK].view(np.uint64)
    bits = 4
    while (1 << bits) < 4 * most:
        bits += 1
    mask = (1 << bits) - 1
    slot_key = np.zeros(1 << bits, np.uint64)
    slot_id = np.full(1 << bits, -1, np.int64)
    block_len = np.empty(most, np.int64)  # each distinct block's bytes, from word block * stride
    block_ruled = np.empty(most, np.int64)  # and its rewritten modules
    stride = BLOCK * width + 1
    expanded = np.empty(most * stride + 4, np.uint64)  # the writing pass reads whole 4-word runs
    ids = np.empty(whole, np.int32)
    distinct, total, rewritten = 0, 0, 0
    for b in range(whole):
        key = keys[b]
        slot = np.int64((key * _GOLDEN) >> np.uint64(64 - bits))
        while slot_id[slot] >= 0 and slot_key[slot] != key:
            slot = (slot + 1) & mask
        block = slot_id[slot]
        if block < 0:
            if distinct == most:
                return np.empty(0, np.uint8), -1, 0
            block, distinct = distinct, distinct + 1
            slot_key[slot], slot_id[slot] = key, block
            p, f, a, r = block * stride, 0, np.uint64(0), 0
            for i in range(b * BLOCK, b * BLOCK + BLOCK):
                s = sym[i]
                p, f, a = _append(expanded, p, f, a, flat, s * width, lengths[s])
                r += ruled[s]
            block_len[block], block_ruled[block] = 8 * (p - block * stride) + f, r
        ids[b] = block
        total += block_len[block]
        rewritten += block_ruled[block]
    for i in range(whole * BLOCK, len(sym)):
        total += lengths[sym[i]]
        rewritten += ruled[sym[i]]
    if total > budget:
        return np.empty(0, np.uint8), total, rewritten
    out = np.empty(total + 8 * max(width, 4), np.uint8)
    at = 0  # the writing pass: each block's expansion stored 32 bytes at a time at any byte position
    for b in range(whole):  # (bytes past its end are garbage, overwritten by the next block's)
        w = ids[b] * stride
        n = block_len[ids[b]]
        for k in range(0, n, 32):
            _store_u64(out, at + k, expanded[w])
            _store_u64(out, at + k + 8, expanded[w + 1])
            _store_u64(out, at + k + 16, expanded[w + 2])
            _store_u64(out, at + k + 24, expanded[w + 3])
            w += 4
        at += n
    for i in range(whole * BLOCK, len(sym)):
        s = sym[i]
        for k in range(width):
            _store_u64(out, at + 8 * k, words[s, k])
        at += lengths[s]
    return out, total, rewritten
