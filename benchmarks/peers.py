"""Plain-Python peers for benchmarks.derive: what a careful Python programmer writes without numpy.

Modules are ``(symbol, params)`` tuples, productions are Python functions from a module's parameters
(and, for context, its neighbours) to a list of modules; one step is a loop over the modules. The
same four workloads as the engine's: parametric with conditions, stochastic, context-sensitive,
non-parametric. Each peer is checked against the engine's result in the benchmark (same lengths;
same string where the workload is deterministic).
"""

from __future__ import annotations

import random

Module = tuple[str, tuple[float, ...]]

# --- parametric with conditions: ABOP fig. 2.8 with conditions (see benchmarks.derive.PARAMETRIC) -------
D1, D2, A, LR, VR, LMAX, WMAX = 94.74, 132.63, 18.95, 1.109, 1.732, 400.0, 100.0


def parametric_step(modules: list[Module]) -> list[Module]:
    """One step of the parametric workload: A(k) branches while k < 20, F(l) elongates while l < 400,
    !(w) thickens while w < 100."""
    out: list[Module] = []
    add, append = out.extend, out.append
    for module in modules:
        s, p = module
        if s == "A" and p[0] < 20:
            k = (p[0] + 1,)
            add((("!", (VR,)), ("F", (50.0,)), ("[", ()), ("&", (A,)), ("F", (50.0,)), ("A", k), ("]", ()),
                 ("/", (D1,)), ("[", ()), ("&", (A,)), ("F", (50.0,)), ("A", k), ("]", ()),
                 ("/", (D2,)), ("[", ()), ("&", (A,)), ("F", (50.0,)), ("A", k), ("]", ())))
        elif s == "F" and p[0] < LMAX:
            append(("F", (p[0] * LR,)))
        elif s == "!" and p[0] < WMAX:
            append(("!", (p[0] * VR,)))
        else:
            append(module)
    return out


# --- stochastic: ABOP fig. 1.27 -----------------------------------------------------------------------
_F, _PLUS, _MINUS, _OPEN, _CLOSE = ("F", ()), ("+", ()), ("-", ()), ("[", ()), ("]", ())
STOCHASTIC = ([_F, _OPEN, _PLUS, _F, _CLOSE, _F, _OPEN, _MINUS, _F, _CLOSE, _F],
              [_F, _OPEN, _PLUS, _F, _CLOSE, _F], [_F, _OPEN, _MINUS, _F, _CLOSE, _F])


def stochastic_step(modules: list[Module], rng: random.Random) -> list[Module]:
    """One step of ABOP fig. 1.27: F -> (1/3) F[+F]F[-F]F | (1/3) F[+F]F | (1/3) F[-F]F."""
    out: list[Module] = []
    pick = rng.random
    for module in modules:
        if module[0] == "F":
            r = pick()
            out.extend(STOCHASTIC[0] if r < 0.33 else STOCHASTIC[1] if r < 0.66 else STOCHASTIC[2])
        else:
            out.append(module)
    return out


# --- context-sensitive: ABOP fig. 1.31a (bracket-aware context, + - F ignored) -----------------------
CONTEXT_RULES = {("0", "0", "0"): "0", ("0", "0", "1"): "1[+F1F1]", ("0", "1", "0"): "1", ("0", "1", "1"): "1",
                 ("1", "0", "0"): "0", ("1", "0", "1"): "1F1", ("1", "1", "0"): "0", ("1", "1", "1"): "0"}
IGNORED = set("+-F")


def _neighbours(symbols: list[str]) -> tuple[list[str | None], list[str | None]]:
    """Left and right context of every module: the previous module on the path from the root (skipping
    ignored ones and whole side branches) and the next one on the same axis."""
    n = len(symbols)
    left: list[str | None] = [None] * n
    stack: list[str | None] = []
    last: str | None = None
    for i, s in enumerate(symbols):
        if s == "[":
            stack.append(last)
        elif s == "]":
            last = stack.pop() if stack else None
        else:
            left[i] = last
            if s not in IGNORED:
                last = s
    right: list[str | None] = [None] * n
    nxt: str | None = None
    pending: list[str | None] = []
    for i in range(n - 1, -1, -1):  # backwards: a ']' starts a side branch, whose last module has none
        s = symbols[i]
        if s == "]":
            pending.append(nxt)
            nxt = None
        elif s == "[":
            nxt = pending.pop() if pending else None
        else:
            right[i] = nxt
            if s not in IGNORED:
                nxt = s
    return left, right


def context_step(modules: list[Module]) -> list[Module]:
    """One step of ABOP fig. 1.31a: 0/1 rewritten by their left and right neighbours; + and - swap."""
    symbols = [m[0] for m in modules]
    left, right = _neighbours(symbols)
    out: list[Module] = []
    for module, s, lc, rc in zip(modules, symbols, left, right, strict=True):
        if s in "01" and lc is not None and rc is not None and lc in "01" and rc in "01":
            out.extend((c, ()) for c in CONTEXT_RULES[(lc, s, rc)])
        elif s == "+":
            out.append(_MINUS)
        elif s == "-":
            out.append(_PLUS)
        else:
            out.append(module)
    return out


# --- non-parametric: ABOP fig. 1.24 a, d, e -----------------------------------------------------------
PLANTS = {"1.24a": ("F", {"F": "F[+F]F[-F]F"}), "1.24d": ("X", {"X": "F[+X]F[-X]+X", "F": "FF"}),
          "1.24e": ("X", {"X": "F[+X][-X]FX", "F": "FF"})}


def plain_step(modules: list[Module], rules: dict[str, str]) -> list[Module]:
    """One step of a non-parametric L-system, module by module."""
    table = {k: [(c, ()) for c in v] for k, v in rules.items()}
    out: list[Module] = []
    for module in modules:
        succ = table.get(module[0])
        if succ is None:
            out.append(module)
        else:
            out.extend(succ)
    return out


# --- string peers for the non-parametric plants: str.replace, and the l-system-fractals package ------
def replace_order(rules: dict[str, str]) -> list[tuple[str, str]]:
    """The rules in an order where sequential ``str.replace`` passes give the parallel step: a rule goes
    after every rule whose predecessor its successor writes (F -> FF before X -> F[+X]F[-X]+X)."""
    left, order = dict(rules), []
    while left:
        ready = [k for k in left if not any(other != k and other in left[k] for other in left)]
        if not ready:
            raise ValueError("successors write each other's predecessors: no replace order is parallel")
        order.append((ready[0], left.pop(ready[0])))
    return order


def replace_step(text: str, order: list[tuple[str, str]]) -> str:
    """One step as one ``str.replace`` pass per rule (two passes for 1.24 d and e)."""
    for symbol, successor in order:
        text = text.replace(symbol, successor)
    return text


def fractals_step(text: str, order: list[tuple[str, str]]) -> str:
    """One step by the ``l-system-fractals`` package (0.0.6, PyPI): its LSystem rewrites with
    ``str.replace`` per rule in the order given, on construction (no drawing)."""
    from l_system_fractals import LSystem

    return LSystem(1, text, order, [], [], 0, 1, 1, 0).string
