"""Parallel, vectorised derivation of parametric, stochastic, context-sensitive L-systems.

One step works per production, never per module: the modules a production may rewrite are found
with one comparison over the symbol array, its parameters are bound as whole columns, its condition
and successor expressions are evaluated on those columns, and the new string is assembled with
numpy scatter operations. A module budget bounds the result: when a full rewrite would exceed it,
only the highest-priority rewrites are applied (the rest of the tree waits), and the step says so.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from arbor.engine.lsystem import brackets, context
from arbor.engine.lsystem.expr import EvalContext, evaluate
from arbor.engine.lsystem.lstring import BareLString, LString, ragged_arange
from arbor.engine.lsystem.lsys import Alternative, LSystem, Pattern, Production
from arbor.engine.lsystem.symbolic import SymbolRewriter

CUT = ord("%")
PRIORITIES = ("order", "position", "random")
DEFAULT_BUDGET = 2_000_000  # modules, when neither the source (budget:) nor the caller sets one
MAX_BUDGET = 20_000_000  # modules at most, whatever is asked: about 0.3 GB at rest, 1 GB while rewriting


@dataclass
class StepReport:
    """What one derivation step did: rewrites applied, rewrites held back by the budget."""

    modules_in: int
    modules_out: int
    rewritten: int
    deferred: int = 0

    @property
    def budget_hit(self) -> bool:
        """True when the module budget held back at least one rewrite."""
        return self.deferred > 0

    @property
    def only_copied(self) -> bool:
        """True when the budget held back every rewrite: the string came out as it went in, and every
        further step would copy it again (so :meth:`Deriver.derive` stops there)."""
        return self.deferred > 0 and self.rewritten == 0


@dataclass
class _Match:
    idx: np.ndarray  # modules it rewrites
    alt: Alternative  # the successor they get
    env: dict[str, np.ndarray]  # bound parameters (columns over idx)
    values: list[list[np.ndarray]] = field(default_factory=list)  # successor parameters, once evaluated

    @property
    def length(self) -> int:
        return len(self.alt.symbols)

    def keep(self, mask: np.ndarray) -> None:
        """Only the rewrites where ``mask`` holds stay (the budget held the others back)."""
        self.idx = self.idx[mask]
        self.env = {k: v[mask] if np.ndim(v) else v for k, v in self.env.items()}

    def evaluate(self, rng: np.random.Generator) -> None:
        """Evaluate the successor's parameters: only after the budget check, so memory for them is
        bounded by the budget too."""
        ectx = EvalContext(self.env, len(self.idx), rng)
        self.values = [[evaluate(e, ectx) for e in exprs] for exprs in self.alt.exprs]


@dataclass
class Deriver:
    """Derives an L-system step by step with a seeded RNG and an optional module budget.

    ``priority`` picks which rewrites keep growing when the budget is hit: ``order`` (lowest branch
    order first: trunk and main limbs keep growing), ``position`` (earliest in the string), or
    ``random``.
    """

    system: LSystem
    seed: int | None = None
    budget: int | None = None
    priority: str = "order"
    seconds: float | None = None  # a time budget for :meth:`derive` (None: none; the game's steps are small)
    rng: np.random.Generator = field(init=False)
    out_of_time: bool = field(init=False, default=False)  # derive() stopped at the time budget

    def __post_init__(self) -> None:
        if self.priority not in PRIORITIES:
            raise ValueError(f"priority must be one of {PRIORITIES}")
        seed = self.system.seed if self.seed is None else self.seed
        self.rng = np.random.Generator(np.random.PCG64(seed))
        self._extern: dict[str, float] = {}
        if self.budget is None:
            self.budget = self.system.budget if self.system.budget is not None else DEFAULT_BUDGET
        self.budget = min(int(self.budget), MAX_BUDGET)
        self._symbols = SymbolRewriter(self.system) if SymbolRewriter.usable(self.system) else None
        symbols = [prod.pred.symbol for prod in self.system.productions]
        self._shared = {s for s in symbols if symbols.count(s) > 1}  # several productions compete for these
        self._cuts = any(CUT in alt.symbols for prod in self.system.productions for alt in prod.alternatives)

    def step(self, ls: LString, extern: dict[str, float] | None = None,
             only: np.ndarray | None = None) -> tuple[LString, StepReport]:
        """Rewrite every module of ``ls`` once, in parallel; ``extern`` supplies the #extern values.

        ``only`` (a boolean mask over the modules) limits rewriting to those modules (region edits).
        """
        self._extern = self._check_extern(extern or {})
        with np.errstate(all="ignore"):
            if self._symbols is not None and len(ls.params) == 0 and only is None:
                fast = self._direct_step(ls)
                if fast is not None:
                    return fast
            matches = self._match_all(ls, only)
            deferred = self._apply_budget(ls, matches)
            if self._symbols is not None and len(ls.params) == 0:
                result = _bare(self._symbols.rewrite_marked(ls.sym, [(m.idx, m.alt) for m in matches]))
            else:
                for m in matches:
                    m.evaluate(self.rng)
                result = _assemble(ls, matches, _out_lengths(len(ls), matches))
        rewritten = sum(len(m.idx) for m in matches)
        return _finish(ls, result, rewritten, deferred, self._may_cut(ls))

    def _direct_step(self, ls: LString) -> tuple[LString, StepReport] | None:
        """The step of a plain deterministic system without parameters, when it fits the budget."""
        assert self._symbols is not None
        if self._symbols.direct_map is None:
            return None
        assert self.budget is not None
        sym, _total, rewritten = self._symbols.rewrite_direct(ls.sym, self.budget)
        if sym is None:
            return None
        result = _bare(sym)
        return _finish(ls, result, rewritten, 0, self._may_cut(ls))

    def _may_cut(self, ls: LString) -> bool:
        """Whether the step's result can hold a cut: a successor writes one, or the input has one."""
        return self._cuts or bool(np.any(ls.sym == CUT))

    def _check_extern(self, extern: dict[str, float]) -> dict[str, float]:
        missing = [name for name in self.system.externs if name not in extern]
        if missing:
            raise ValueError(f"{self.system.file}: values needed for #extern {', '.join(missing)}")
        return {name: float(extern[name]) for name in self.system.externs}

    def derive(
        self, ls: LString | None = None, steps: int | None = None, extern: dict[str, float] | None = None
    ) -> tuple[LString, list[StepReport]]:
        """Apply ``steps`` steps (default: the source's ``n:``) starting from ``ls`` (default: axiom).

        Stops early at a step that only copied (the budget full and held back every rewrite: see
        :attr:`StepReport.only_copied`, the last report), so a huge step count costs no more than the
        steps that grow; ``len(reports)`` says how many steps were taken."""
        current = self.system.axiom if ls is None else ls
        reports, started, last = [], time.perf_counter(), 0.0
        self.out_of_time = False
        for _ in range(self.system.iterations if steps is None else steps):
            if self._next_step_too_late(started, last, reports):
                self.out_of_time = True
                break
            begun = time.perf_counter()
            current, report = self.step(current, extern)
            last = time.perf_counter() - begun
            reports.append(report)
            if report.only_copied:
                break
        return current, reports

    def _next_step_too_late(self, started: float, last: float, reports: list[StepReport]) -> bool:
        """Whether the next step would end past the time budget (``seconds``): the last step's time,
        grown as the string grew in it, added to the time already spent (a step is never cut halfway)."""
        if self.seconds is None or not reports:
            return False
        growth = max(reports[-1].modules_out / max(reports[-1].modules_in, 1), 1.0)
        return time.perf_counter() - started + last * growth > self.seconds

    def _match_all(self, ls: LString, only: np.ndarray | None = None) -> list[_Match]:
        n = len(ls)
        taken = np.zeros(n, dtype=bool) if only is None else ~np.asarray(only, dtype=bool)
        ctx = _ContextIndex(ls, self.system) if self.system.has_context else None
        matches: list[_Match] = []
        by_symbol: dict[int, np.ndarray] = {}
        bare = len(ls.params) == 0  # no module has parameters: only formal-free patterns can match
        for prod in self.system.productions:
            s = prod.pred.symbol
            if s not in by_symbol:
                by_symbol[s] = np.flatnonzero(ls.sym == s)
            cand = by_symbol[s]
            if only is not None or s in self._shared or not bare:  # else nothing can have taken them
                cand = np.compress(~taken[cand] & (ls.nparams[cand] == len(prod.pred.formals)), cand)
            elif prod.pred.formals:
                continue
            if len(cand):
                cand, env = _bind(ls, prod, cand, ctx)
                env.update(self._extern)
                if len(cand) and prod.condition is not None:
                    ok = evaluate(prod.condition, EvalContext(env, len(cand), self.rng)) != 0
                    cand, env = cand[ok], {k: v[ok] if np.ndim(v) else v for k, v in env.items()}
                if len(cand):
                    taken[cand] = True
                    matches.extend(self._expand(prod, cand, env))
        return matches

    def _expand(self, prod: Production, idx: np.ndarray, env: dict[str, np.ndarray]) -> list[_Match]:
        alts = prod.alternatives
        if len(alts) == 1:
            choice = np.zeros(len(idx), dtype=np.int64)
        else:
            weights = np.array([a.weight for a in alts], dtype=np.float64)
            cum = np.cumsum(weights / weights.sum())
            draw = self.rng.random(len(idx))
            choice = np.zeros(len(idx), dtype=np.int8 if len(alts) < 128 else np.int64)
            for bound in cum[:-1]:  # a few comparisons beat a binary search for a few alternatives
                choice += draw >= bound
        out = []
        for a, alt in enumerate(alts):
            pick = choice == a
            sub = idx if len(alts) == 1 else np.compress(pick, idx)  # compress: 3x faster than idx[pick]
            if len(sub) == 0:
                continue
            sub_env = env if len(alts) == 1 else {k: np.compress(pick, v) if np.ndim(v) else v
                                                  for k, v in env.items()}
            out.append(_Match(sub, alt, sub_env))
        return out

    def _apply_budget(self, ls: LString, matches: list[_Match]) -> int:
        total = len(ls) + sum(len(m.idx) * (m.length - 1) for m in matches)
        if self.budget is None or total <= self.budget:
            return 0
        out_len = _out_lengths(len(ls), matches)
        growth = out_len - 1
        growing = np.flatnonzero(growth > 0)
        room = self.budget - (len(ls) + int(growth[growth < 0].sum()))
        order = self._priority_order(ls, growing)
        fits = np.cumsum(growth[growing[order]]) <= max(room, 0)
        held = growing[order[~fits]]
        keep = np.ones(len(ls), dtype=bool)
        keep[held] = False
        for m in matches:
            mask = keep[m.idx]
            if not mask.all():
                m.keep(mask)
        matches[:] = [m for m in matches if len(m.idx)]
        return len(held)

    def _priority_order(self, ls: LString, growing: np.ndarray) -> np.ndarray:
        if self.priority == "position":
            return np.arange(len(growing))
        if self.priority == "random":
            return self.rng.permutation(len(growing))
        depth = brackets.depths(ls.sym)[growing]
        return np.argsort(depth, kind="stable")


class _ContextIndex:
    """Left/right context neighbours of every module, computed once per step when needed. Index n is
    a sentinel ("no neighbour") whose symbol matches no pattern, so lookups need no masking."""

    def __init__(self, ls: LString, system: LSystem) -> None:
        n = len(ls)
        sym, nparams = np.append(ls.sym, 0), np.append(ls.nparams, 0)
        self.chains = []
        for nbr in context.neighbours(ls.sym, system.ignore):
            nbr = np.append(np.where(nbr < 0, n, nbr), n)
            key = sym[nbr].astype(np.int32) | (nparams[nbr].astype(np.int32) << 8)
            self.chains.append((nbr, key))  # neighbour, and its symbol and parameter count in one key

    def follow(self, patterns, side: int, cand: np.ndarray, ok: np.ndarray, where: list) -> None:
        """Match ``patterns`` walking from ``cand`` to one side (0 left, 1 right): clear ``ok`` where
        they fail; record where each pattern lies when its parameters or a further pattern need it."""
        nbr, key = self.chains[side]
        patterns = list(patterns)
        at = cand
        for i, pat in enumerate(patterns):
            ok &= key[at] == pat.symbol | (len(pat.formals) << 8)  # the next module's symbol and count
            if pat.formals or i + 1 < len(patterns):
                at = nbr[at]
                if pat.formals:
                    where.append((pat, at))


def _bind(
    ls: LString, prod: Production, cand: np.ndarray, ctx: _ContextIndex | None
) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """Check contexts and bind formal parameters as columns; returns surviving candidates."""
    ok = np.ones(len(cand), dtype=bool)
    where: list[tuple[Pattern, np.ndarray]] = [(prod.pred, cand)]
    if ctx is not None:
        ctx.follow(reversed(prod.left), 0, cand, ok, where)
        ctx.follow(prod.right, 1, cand, ok, where)
    if not ok.all():
        cand = np.compress(ok, cand)
        where = [(p, np.compress(ok, at)) for p, at in where]
    env = {}
    for pat, at in where:
        for j, name in enumerate(pat.formals):
            env[name] = ls.param_column(at, j)
    return cand, env


def _assemble(ls: LString, matches: list[_Match], out_len: np.ndarray) -> LString:
    """Build the rewritten string from the identity modules and each rule's successors."""
    starts = np.cumsum(out_len) - out_len
    total = int(out_len.sum())
    sym = np.empty(total, dtype=np.uint8)
    nparams = np.empty(total, dtype=np.uint8)
    ident = np.ones(len(ls), dtype=bool)
    for m in matches:
        ident[m.idx] = False
    keep = np.flatnonzero(ident)
    sym[starts[keep]] = ls.sym[keep]
    nparams[starts[keep]] = ls.nparams[keep]
    for m in matches:
        if m.length:
            pos = starts[m.idx][:, None] + np.arange(m.length)
            sym[pos] = m.alt.symbols
            nparams[pos] = m.alt.nparams
    offsets = np.cumsum(nparams, dtype=np.int64) - nparams
    params = np.empty(int(nparams.sum(dtype=np.int64)), dtype=np.float64)
    counts = ls.nparams[keep].astype(np.int64)
    params[ragged_arange(offsets[starts[keep]], counts)] = ls.params[ragged_arange(ls.offsets[keep], counts)]
    for m in matches:
        for j, vals in enumerate(m.values):
            if vals:
                base = offsets[starts[m.idx] + j]
                for t, v in enumerate(vals):
                    params[base + t] = v
    return LString(sym, nparams, offsets, params)


def _out_lengths(n: int, matches: list[_Match]) -> np.ndarray:
    """How many modules each of the ``n`` modules becomes."""
    out_len = np.ones(n, dtype=np.int64)
    for m in matches:
        out_len[m.idx] = m.length
    return out_len


def _bare(sym: np.ndarray) -> LString:
    """An L-string of ``sym`` with no parameters."""
    return BareLString(sym)


def _finish(ls: LString, result: LString, rewritten: int, deferred: int,
            cuts: bool = True) -> tuple[LString, StepReport]:
    """Apply cuts (``cuts``: the step may have made one) and report the step."""
    if cuts and np.any(result.sym == CUT):
        result = apply_cut(result)
    return result, StepReport(len(ls), len(result), rewritten, deferred)


def apply_cut(ls: LString) -> LString:
    """Apply the cut symbol '%': remove it and the rest of its branch up to the closing ']'."""
    return ls.select(~brackets.rest_of_branches(ls.sym, np.flatnonzero(ls.sym == CUT)))


def derive(system: LSystem, steps: int | None = None, seed: int | None = None, budget: int | None = None) -> LString:
    """Convenience: the axiom of ``system`` derived ``steps`` times (default ``n:``)."""
    result, _ = Deriver(system, seed=seed, budget=budget).derive(steps=steps)
    return result
