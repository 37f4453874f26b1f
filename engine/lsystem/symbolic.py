"""Symbols-only rewriting: when no module has parameters, a derivation step is a few byte passes.

Plain deterministic systems (one unconditional, context-free production per symbol) go faster still: a
compiled loop (expand_kernel) writes the successors 64-bit words at a time, after a pass that measures
the output; while the string repeats its blocks of 8 modules (as L-strings do), that pass also finds
each distinct block, expanded once, and the writing pass copies each block's expansion whole.

Otherwise every production alternative gets a placeholder byte that can never be a module symbol
(control codes and bytes above 126). A step marks each rewritten module with its alternative's
placeholder (the vectorised matcher decides, with contexts, conditions and random choices exactly as in
the general path) and then replaces each placeholder by its successor with ``bytes.replace``. Successors
hold only real symbols, so the replacements cannot see each other's output: the step stays parallel, as
an L-system step must be.
"""

from __future__ import annotations

import sys

import numpy as np

from arbor.engine.lsystem.lsys import Alternative, LSystem

PLACEHOLDERS = bytes(range(1, 33)) + bytes(range(127, 256))  # never valid module symbols
MOST_BLOCKS = 4096  # distinct blocks of modules a direct step expands once each, at most


class SymbolRewriter:
    """Placeholders and successor bytes for a parameter-free L-system (see module docstring)."""

    def __init__(self, system: LSystem) -> None:
        alts = [a for p in system.productions for a in p.alternatives]
        self.placeholder: dict[int, int] = {id(a): PLACEHOLDERS[i] for i, a in enumerate(alts)}
        self.successor: dict[bytes, bytes] = {
            bytes([PLACEHOLDERS[i]]): a.symbols.tobytes() for i, a in enumerate(alts)}
        self.direct_map, self.lengths = self._direct(system)
        self.ruled = np.zeros(256, bool) if self.direct_map is None else (
            np.frombuffer(self.direct_map, np.uint8) != np.arange(256))
        self.out_lengths = np.where(self.ruled, self.lengths, 1)  # copied symbols write themselves
        self.ruled_counts = self.ruled.astype(np.int64)  # 1 where a module counts as rewritten
        self.words = self._words(system) if self.direct_map is not None else None
        self.blocks = sys.byteorder == "little"  # its strings repeat their blocks (see rewrite_direct)

    @staticmethod
    def usable(system: LSystem) -> bool:
        """True when the system can never create or read a parameter (and its alternatives fit the
        placeholders): then a string without parameters stays without them."""
        prods = system.productions
        alts = [a for p in prods for a in p.alternatives]
        no_formals = all(not pat.formals for p in prods for pat in (p.pred, *p.left, *p.right))
        return no_formals and len(alts) <= len(PLACEHOLDERS) and not any(a.nparams.any() for a in alts)

    def _direct(self, system: LSystem) -> tuple[bytes | None, np.ndarray]:
        """For systems where the symbol alone decides the successor (one unconditional, context-free,
        single-alternative production per symbol): the translate table and each symbol's output
        length (0 for symbols no production rewrites)."""
        prods = system.productions
        lengths = np.zeros(256, dtype=np.int64)
        symbols = [p.pred.symbol for p in prods]
        if len(set(symbols)) != len(symbols) or any(
                p.left or p.right or p.condition is not None or len(p.alternatives) != 1 for p in prods):
            return None, lengths
        table = bytearray(range(256))
        for p in prods:
            alt = p.alternatives[0]
            table[p.pred.symbol] = self.placeholder[id(alt)]
            lengths[p.pred.symbol] = len(alt.symbols)
        return bytes(table), lengths

    def _words(self, system: LSystem) -> np.ndarray:
        """Each symbol's output as little-endian 64-bit words padded with zeros (see expand_kernel)."""
        width = max(2, -(-int(self.out_lengths.max()) // 8))
        table = np.zeros((256, 8 * width), np.uint8)
        table[:, 0] = np.arange(256)
        for p in system.productions:
            succ = p.alternatives[0].symbols
            table[p.pred.symbol] = 0
            table[p.pred.symbol, :len(succ)] = succ
        return table.view("<u8").astype(np.uint64)

    def rewrite_direct(self, sym: np.ndarray, budget: int) -> tuple[np.ndarray | None, int, int]:
        """One step of a direct system over the whole string: (the new symbols, or None when more than
        ``budget`` modules long; the output length; the rewritten modules). A block of modules at a
        time while the string repeats its blocks (L-strings do: the lengths come from the same pass),
        else a module at a time after a pass that measures (then for good: a system's strings keep their
        kind from step to step)."""
        from arbor.engine.lsystem.expand_kernel import BLOCK, expand, expand_blocks, measure

        assert self.words is not None
        sym = np.ascontiguousarray(sym, np.uint8)
        ruled = self.ruled_counts
        if self.blocks:
            out, total, rewritten = expand_blocks(sym, self.out_lengths, ruled, self.words,
                                                  min(MOST_BLOCKS, len(sym) // 64 + 64), budget)
            self.blocks = total >= 0
            if self.blocks:
                return (out[:total] if total <= budget else None), int(total), int(rewritten)
        total, rewritten = measure(sym, self.out_lengths, ruled)
        if total > budget:
            return None, int(total), int(rewritten)
        out = np.empty(total // 8 + BLOCK * self.words.shape[1] + 2, np.uint64)
        assert expand(sym, self.out_lengths, self.words, out) == total
        if sys.byteorder == "big":  # the words' values are little-endian
            out.byteswap(inplace=True)
        return out.view(np.uint8)[:total], int(total), int(rewritten)

    def rewrite_marked(self, sym: np.ndarray, marks: list[tuple[np.ndarray, Alternative]]) -> np.ndarray:
        """One step where the modules ``idx`` of each (idx, alternative) pair get that successor."""
        marked = sym.copy()
        used = []
        for idx, alt in marks:
            marked[idx] = self.placeholder[id(alt)]
            used.append(self.placeholder[id(alt)])
        return self._expand(marked.tobytes(), used)

    def _expand(self, data: bytes, used: list[int]) -> np.ndarray:
        keys = sorted({bytes([ph]) for ph in used}, key=lambda k: len(self.successor[k]))
        for key in keys:  # the shortest successors first: each later pass has less to scan
            data = data.replace(key, self.successor[key])
        return np.frombuffer(bytearray(data), dtype=np.uint8)
