"""A small, safe arithmetic expression language compiled to vectorised numpy closures.

.lsys files and saves are shared between players, so nothing here ever calls Python's ``eval``:
expressions are parsed by a Pratt parser into a tree and compiled into closures over numpy
functions from a fixed whitelist. A compiled expression evaluates a whole parameter column at once.

Grammar (lowest to highest precedence): ``or ||``, ``and &&``, ``not !``, comparisons
``< <= > >= == !=``, ``+ -``, ``* / %``, unary ``- +``, ``^`` (power, right-assoc), calls, atoms.
Trigonometric functions take radians.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

import numpy as np

from arbor.engine.lsystem.cursor import Cursor

Value = np.ndarray | float


@dataclass
class EvalContext:
    """What a compiled expression sees: bound variable columns, the column length and the RNG."""

    vars: Mapping[str, Value]
    n: int = 1
    rng: np.random.Generator = field(default_factory=lambda: np.random.default_rng(0))


Compiled = Callable[[EvalContext], Value]


def _rand(ctx: EvalContext, *args: Value) -> Value:
    u = ctx.rng.random(ctx.n)
    if len(args) == 0:
        return u
    if len(args) == 1:
        return u * args[0]
    return args[0] + u * (args[1] - args[0])


def _nary(fn: Callable[[Value, Value], Value]) -> Callable[..., Value]:
    def reduce(*args: Value) -> Value:
        out = args[0]
        for a in args[1:]:
            out = fn(out, a)
        return out

    return reduce


# name -> (function, min arity, max arity)
FUNCTIONS: dict[str, tuple[Callable[..., Value], int, int]] = {
    "sqrt": (np.sqrt, 1, 1),
    "sin": (np.sin, 1, 1),
    "cos": (np.cos, 1, 1),
    "tan": (np.tan, 1, 1),
    "asin": (np.arcsin, 1, 1),
    "acos": (np.arccos, 1, 1),
    "atan": (np.arctan, 1, 1),
    "atan2": (np.arctan2, 2, 2),
    "exp": (np.exp, 1, 1),
    "log": (np.log, 1, 1),
    "abs": (np.abs, 1, 1),
    "floor": (np.floor, 1, 1),
    "ceil": (np.ceil, 1, 1),
    "sign": (np.sign, 1, 1),
    "min": (_nary(np.minimum), 1, 16),
    "max": (_nary(np.maximum), 1, 16),
    "pow": (np.power, 2, 2),
    "clamp": (lambda x, lo, hi: np.minimum(np.maximum(x, lo), hi), 3, 3),
}
RANDOM_FUNCTIONS = {"rand": (0, 2)}

_BINARY: dict[str, tuple[int, Callable[[Value, Value], Value]]] = {
    "or": (1, np.logical_or),
    "||": (1, np.logical_or),
    "and": (2, np.logical_and),
    "&&": (2, np.logical_and),
    "<": (4, np.less),
    "<=": (4, np.less_equal),
    ">": (4, np.greater),
    ">=": (4, np.greater_equal),
    "==": (4, np.equal),
    "=": (4, np.equal),
    "!=": (4, np.not_equal),
    "+": (5, np.add),
    "-": (5, np.subtract),
    "*": (6, np.multiply),
    "/": (6, np.divide),
    "%": (6, np.fmod),
    "^": (8, np.power),
}
_OPS_BY_LENGTH = sorted(_BINARY, key=len, reverse=True)
_NOT_PREC = 3
_UNARY_PREC = 7


MAX_DEPTH = 48  # nesting of operations in one expression: deeper is refused (a hostile file cannot
# exhaust the parser's or the evaluator's stack)


@dataclass(frozen=True)
class Expr:
    """A compiled expression: ``fn(ctx)`` evaluates it; ``const`` is set when it folded to a number;
    ``depth`` is how deeply its compiled calls nest."""

    fn: Compiled
    const: float | None
    names: frozenset[str]
    depth: int = 0


def _constant(value: float) -> Expr:
    return Expr(lambda ctx: value, float(value), frozenset())


def _deeper(cur: Cursor) -> None:
    """Count one more level of nesting while parsing; refuse past MAX_DEPTH."""
    cur.depth = getattr(cur, "depth", 0) + 1
    if cur.depth > MAX_DEPTH:
        raise cur.error(f"expression nested too deeply (more than {MAX_DEPTH} levels)")


def _peek_binary(cur: Cursor) -> str | None:
    cur.skip_ws()
    for op in _OPS_BY_LENGTH:
        if cur.text.startswith(op, cur.pos):
            if op.isalpha():
                end = cur.pos + len(op)
                if end < len(cur.text) and (cur.text[end].isalnum() or cur.text[end] == "_"):
                    continue
            return op
    return None


HostFunctions = Mapping[str, tuple[Callable[..., Value], int, int]]


def parse_expression(
    cur: Cursor,
    constants: Mapping[str, float],
    variables: frozenset[str] | set[str],
    min_prec: int = 0,
    host: HostFunctions | None = None,
) -> Expr:
    """Parse one expression from ``cur`` and compile it.

    Stops before a top-level ``,`` or ``)`` or any text that cannot continue the expression.
    ``constants`` are folded in; names in ``variables`` become column lookups; any other name is an
    error naming its column.
    """
    _deeper(cur)
    left = _parse_prefix(cur, constants, variables, host)
    while True:
        op = _peek_binary(cur)
        if op is None or _BINARY[op][0] < min_prec:
            cur.depth -= 1
            return left
        prec, fn = _BINARY[op]
        at = cur.pos
        cur.pos += len(op)
        next_min = prec if op == "^" else prec + 1  # ^ is right-associative
        right = parse_expression(cur, constants, variables, next_min, host)
        left = _combine(fn, [left, right])
        if left.depth > MAX_DEPTH:
            raise cur.error(f"expression too long to evaluate (more than {MAX_DEPTH} chained operations)", at)


def _parse_prefix(
    cur: Cursor, constants: Mapping[str, float], variables: frozenset[str] | set[str], host: HostFunctions | None
) -> Expr:
    cur.skip_ws()
    start = cur.pos
    if cur.accept("("):
        inner = parse_expression(cur, constants, variables, 0, host)
        cur.expect(")", "')' to close '('")
        return inner
    if cur.peek(1) == "-" or cur.peek(1) == "+":
        sign = cur.text[cur.pos]
        cur.pos += 1
        operand = parse_expression(cur, constants, variables, _UNARY_PREC, host)
        return operand if sign == "+" else _combine(np.negative, [operand])
    if cur.peek(1) == "!" and cur.peek(2) != "!=":
        cur.pos += 1
        return _combine(np.logical_not, [parse_expression(cur, constants, variables, _NOT_PREC, host)])
    number = cur.number()
    if number is not None:
        return _constant(number)
    name = cur.name()
    if name is None:
        raise cur.error(f"expected a number, a name or '(', found {cur.describe_next()}")
    if name == "not":
        return _combine(np.logical_not, [parse_expression(cur, constants, variables, _NOT_PREC, host)])
    if cur.peek(1) == "(":
        return _parse_call(cur, name, start, constants, variables, host)
    if name in variables:
        return Expr(lambda ctx: ctx.vars[name], None, frozenset([name]))
    if name in constants:
        return _constant(constants[name])
    if name in ("true", "false"):
        return _constant(1.0 if name == "true" else 0.0)
    raise cur.error(f"unknown name {name!r} (not a parameter or #define constant)", start)


def _parse_call(
    cur: Cursor,
    name: str,
    start: int,
    constants: Mapping[str, float],
    variables: frozenset[str] | set[str],
    host: HostFunctions | None,
) -> Expr:
    table = {**FUNCTIONS, **(host or {})}
    if name not in table and name not in RANDOM_FUNCTIONS:
        raise cur.error(f"unknown function {name!r}", start)
    cur.expect("(")
    args: list[Expr] = []
    if not cur.accept(")"):
        while True:
            args.append(parse_expression(cur, constants, variables, 0, host))
            if cur.accept(")"):
                break
            cur.expect(",", "',' or ')' in the argument list")
    if name in RANDOM_FUNCTIONS:
        lo, hi = RANDOM_FUNCTIONS[name]
        _check_arity(cur, name, start, len(args), lo, hi)
        fns = [a.fn for a in args]
        names = frozenset().union(*(a.names for a in args))
        depth = 1 + max((a.depth for a in args), default=0)
        return Expr(lambda ctx: _rand(ctx, *(f(ctx) for f in fns)), None, names, depth)
    fn, lo, hi = table[name]
    _check_arity(cur, name, start, len(args), lo, hi)
    return _combine(fn, args)


def _check_arity(cur: Cursor, name: str, start: int, got: int, lo: int, hi: int) -> None:
    if not lo <= got <= hi:
        want = str(lo) if lo == hi else f"{lo} to {hi}"
        raise cur.error(f"{name}() takes {want} argument(s), got {got}", start)


def _combine(fn: Callable[..., Value], args: list[Expr]) -> Expr:
    names = frozenset().union(*(a.names for a in args))
    if all(a.const is not None for a in args):
        with np.errstate(all="ignore"):
            value = float(fn(*(a.const for a in args)))
        return _constant(value)
    fns = [a.fn for a in args]
    depth = 1 + max(a.depth for a in args)
    if len(fns) == 1:
        f0 = fns[0]
        return Expr(lambda ctx: fn(f0(ctx)), None, names, depth)
    if len(fns) == 2:
        f0, f1 = fns
        return Expr(lambda ctx: fn(f0(ctx), f1(ctx)), None, names, depth)
    return Expr(lambda ctx: fn(*(f(ctx) for f in fns)), None, names, depth)


def compile_expression(
    text: str,
    constants: Mapping[str, float] | None = None,
    variables: frozenset[str] | set[str] = frozenset(),
    file: str = "<string>",
    line: int = 1,
) -> Expr:
    """Compile a complete expression string (the whole text must be one expression)."""
    cur = Cursor(text, file, line)
    expr = parse_expression(cur, constants or {}, variables)
    if not cur.at_end():
        raise cur.error(f"unexpected {cur.describe_next()} after expression")
    return expr


def evaluate(expr: Expr, ctx: EvalContext) -> np.ndarray:
    """Evaluate ``expr`` to a float64 column of length ``ctx.n`` (constants are broadcast)."""
    with np.errstate(all="ignore"):
        value = expr.fn(ctx)
    out = np.asarray(value, dtype=np.float64)
    if out.shape != (ctx.n,):
        out = np.broadcast_to(out, (ctx.n,)).astype(np.float64)
    return out
