"""Parser for .lsys sources in ABOP notation (untrusted input: no eval, errors with positions).

A source is read line by line::

    // comment line (also '# ' followed by text)
    #define a 18.95             constants, may use earlier ones
    #ignore: + - / &            symbols skipped in context matching (or #consider: the opposite)
    #extern T R                 names the host program supplies at each derivation step
    #host children              functions the host program supplies (the file cannot run alone)
    n: 6                        header values: n, delta (or angle), step, width, width_scale, seed,
                                budget, leaf_size, leaves_at_tips, unit (metres per turtle unit)
    w: !(1)F(200)/(45)A         the axiom (also 'axiom:' or 'ω:')
    p1: A : * -> !(vr)F(50)[&(a)F(50)A]
    p2: B(x) < A(y) > C : x > y -> A(x + y)
    p3: A -> (0.3) B | (0.7) C  stochastic alternatives (or one line per alternative, weights merged)

A line with ``->`` (or ``→``) is a production; '*' as condition means always; an empty successor
or 'ε' erases the module. Directives and number headers may end in a ``// comment``.
"""

from __future__ import annotations

import hashlib
import math
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from arbor.engine.base.errors import LSysError
from arbor.engine.base.reader import read_user_text
from arbor.engine.lsystem.cursor import Cursor
from arbor.engine.lsystem.expr import EvalContext, Expr, HostFunctions, evaluate, parse_expression
from arbor.engine.lsystem.lstring import MAX_PARAMS, LString, valid_symbol

HEADER_KEYS = {
    "n": "iterations",
    "derivation_length": "iterations",
    "delta": "angle",
    "δ": "angle",
    "angle": "angle",
    "step": "step",
    "width": "width",
    "width_scale": "width_scale",
    "leaf_size": "leaf_size",
    "leaves_at_tips": "leaves_at_tips",
    "tropism_x": "tropism_x",
    "tropism_y": "tropism_y",
    "tropism_z": "tropism_z",
    "seed": "seed",
    "budget": "budget",
    "unit": "unit",
}
AXIOM_KEYS = {"w", "ω", "axiom"}
_LABEL = re.compile(r"\s*[pP]\d+\s*:")
_ARROW = re.compile(r"->|→")
_PATTERN_STOP = set("<>:")


@dataclass(frozen=True)
class Pattern:
    """A module in a predecessor or context: symbol and formal parameter names."""

    symbol: int
    formals: tuple[str, ...]


@dataclass
class Alternative:
    """One successor of a production with its probability weight."""

    weight: float
    symbols: np.ndarray  # uint8 symbol per successor module
    nparams: np.ndarray  # uint8 parameter count per successor module
    exprs: list[list[Expr]]  # parameter expressions per successor module


@dataclass
class Production:
    """A parsed production; alternatives are tried by probability when there is more than one."""

    pred: Pattern
    left: tuple[Pattern, ...]
    right: tuple[Pattern, ...]
    condition: Expr | None
    alternatives: list[Alternative]
    line: int
    key: str
    stochastic: bool = False

    @property
    def variables(self) -> set[str]:
        """All formal parameter names bound by this production."""
        return {f for p in (*self.left, self.pred, *self.right) for f in p.formals}


@dataclass
class LSystem:
    """A parsed L-system: axiom, productions and the defaults the turtle and game use."""

    axiom: LString
    productions: list[Production]
    constants: dict[str, float] = field(default_factory=dict)
    ignore: np.ndarray = field(default_factory=lambda: np.zeros(256, bool))
    iterations: int = 0
    angle: float = 90.0
    step: float = 1.0
    width: float | None = None
    width_scale: float = 1.0
    leaf_size: float | None = None
    leaves_at_tips: int | None = None
    seed: int = 0
    budget: int | None = None
    unit: float | None = None  # metres per turtle unit ('unit: 0.01': F(1) is a centimetre); None: the scene's
    externs: tuple[str, ...] = ()
    overrides: dict[str, float] = field(default_factory=dict)
    tropism_x: float | None = None
    tropism_y: float | None = None
    tropism_z: float | None = None
    host: dict = field(default_factory=dict)
    file: str = "<string>"
    source: str = ""

    @property
    def sha256(self) -> str:
        """Hash of the source text, so a save can say exactly which rules grew its tree."""
        return hashlib.sha256(self.source.encode("utf-8")).hexdigest()

    @property
    def tropism(self) -> tuple[float, float, float] | None:
        """The world vector 'T' bends towards (header tropism_x/y/z), if the source sets one."""
        parts = (self.tropism_x, self.tropism_y, self.tropism_z)
        if all(p is None for p in parts):
            return None
        return tuple(float(p or 0.0) for p in parts)

    @property
    def has_context(self) -> bool:
        """True if any production is context-sensitive."""
        return any(p.left or p.right for p in self.productions)


MAX_SOURCE_BYTES = 1024 * 1024  # an .lsys source is text a person writes: a megabyte is plenty


def load_lsystem(path: str | Path) -> LSystem:
    """Read and parse an .lsys file (through the one reader for users' files: a regular file itself, not a
    link, FIFO or device, of at most a megabyte of UTF-8 text, a BOM allowed); errors name the file, line
    and column."""
    text = read_user_text(path, MAX_SOURCE_BYTES, LSysError)
    return parse_lsystem(text, str(path))


def parse_lsystem(text: str, file: str = "<string>", overrides: dict[str, float] | None = None,
                  host: HostFunctions | None = None) -> LSystem:
    """Parse .lsys source text into an :class:`LSystem`.

    ``overrides`` replace #define values (species presets); ``host`` adds functions the program
    supplies (e.g. GeoMaTree's seed directions) to the expression language.
    """
    system = LSystem(axiom=LString.empty(), productions=[], file=file, source=text)
    system.overrides = dict(overrides or {})
    system.host = dict(host or {})
    axiom_seen = False
    for number, raw in enumerate(text.splitlines(), start=1):
        line = raw.rstrip()
        stripped = line.strip()
        if not stripped or _is_comment(stripped):
            continue
        if stripped.startswith("#"):
            _directive(system, _strip_trailing_comment(line), file, number)
        elif _ARROW.search(line):
            _production(system, line, file, number)
        else:
            axiom_seen |= _header(system, line, file, number)
    if not axiom_seen:
        raise LSysError("no axiom: add a line like 'w: F'", file, 1, 1)
    return system


def _strip_trailing_comment(line: str) -> str:
    """Directives and number headers may end with '// text' (never axioms or productions: '/' rolls)."""
    at = line.find("//")
    return line if at < 0 else line[:at]


def _is_comment(stripped: str) -> bool:
    return stripped.startswith("//") or stripped == "#" or stripped.startswith(("# ", "##", "#\t"))


def _directive(system: LSystem, line: str, file: str, number: int) -> None:
    cur = Cursor(line, file, number)
    cur.expect("#")
    word_at = cur.pos
    word = cur.name()
    if word == "define":
        name = cur.name()
        if name is None:
            raise cur.error("expected a constant name after #define")
        value = parse_expression(cur, system.constants, set(), 0, system.host)
        if value.const is None:
            raise cur.error("a #define value must be a constant expression")
        if not cur.at_end():
            raise cur.error(f"unexpected {cur.describe_next()} after #define value")
        system.constants[name] = system.overrides.get(name, value.const)
    elif word == "extern":
        cur.accept(":")
        names = []
        while not cur.at_end():
            at = cur.pos
            name = cur.name()
            if name is None:
                raise cur.error(f"expected a name in #extern, found {cur.describe_next()}")
            if name in system.constants:
                raise cur.error(f"{name!r} is already a #define constant", at)
            names.append(name)
            cur.accept(",")
        system.externs = tuple(dict.fromkeys((*system.externs, *names)))
    elif word == "host":
        cur.accept(":")
        while not cur.at_end():
            at = cur.pos
            name = cur.name()
            if name is None:
                raise cur.error(f"expected a function name in #host, found {cur.describe_next()}")
            if name not in system.host:
                raise cur.error(f"this L-system needs the program to supply the function {name}() "
                                "(it cannot be loaded on its own)", at)
            cur.accept(",")
    elif word in ("ignore", "consider"):
        cur.accept(":")
        table = np.zeros(256, bool)
        while not cur.at_end():
            ch = cur.text[cur.pos]
            if not valid_symbol(ch):
                raise cur.error(f"{ch!r} is not a module symbol")
            table[ord(ch)] = True
            cur.pos += 1
        system.ignore = table if word == "ignore" else ~table
    else:
        raise cur.error(f"unknown directive #{word or ''}: expected #define, #extern, #host, #ignore or #consider",
                        word_at)


def _header(system: LSystem, line: str, file: str, number: int) -> bool:
    cur = Cursor(line, file, number)
    key_start = cur.pos
    key = line.split(":", 1)[0].strip().lower().replace(" ", "_")
    if ":" not in line or (key not in HEADER_KEYS and key not in AXIOM_KEYS):
        raise cur.error("expected 'w: axiom', a header like 'n: 5', a #directive or a production with '->'", key_start)
    cur.pos = line.index(":") + 1
    if key in AXIOM_KEYS:
        mods = _successor(cur, system.constants, set(), stop_at_bar=False, host=system.host)
        system.axiom = _constant_lstring(mods)
        return True
    cur.text = _strip_trailing_comment(cur.text)
    value = parse_expression(cur, system.constants, set())
    if value.const is None or not cur.at_end():
        raise cur.error(f"'{key}:' needs one constant number")
    _set_header(system, HEADER_KEYS[key], value.const, cur)
    return False


WHOLE_LIMITS = {"iterations": 1000, "seed": 2**63 - 1, "budget": 20_000_000, "leaves_at_tips": 16}
NUMBER_LIMIT = 1e9  # any other header (angle, step, width, ...) in magnitude


def _set_header(system: LSystem, attr: str, value: float, cur: Cursor) -> None:
    if not math.isfinite(value):
        raise cur.error(f"'{attr}' must be a finite number")
    if attr in WHOLE_LIMITS:
        top = WHOLE_LIMITS[attr]
        if value != int(value) or value < 0 or value > top:
            raise cur.error(f"'{attr}' must be a whole number from 0 to {top:,}")
        setattr(system, attr, int(value))
    elif attr == "unit" and not 1e-6 <= value <= 1000:
        raise cur.error("'unit' is metres per turtle unit: from 0.000001 (a micrometre) to 1000")
    elif abs(value) > NUMBER_LIMIT:
        raise cur.error(f"'{attr}' must be between {-NUMBER_LIMIT:g} and {NUMBER_LIMIT:g}")
    else:
        setattr(system, attr, float(value))


def _production(system: LSystem, line: str, file: str, number: int) -> None:
    arrow = _ARROW.search(line)
    assert arrow is not None
    label = _LABEL.match(line)
    start = label.end() if label else 0
    head = Cursor(line[: arrow.start()], file, number)
    head.pos = start
    head.skip_ws()
    start = head.pos
    left, pred, right = _patterns(head)
    formals = [f for p in (*left, pred, *right) for f in p.formals]
    dupes = {f for f in formals if formals.count(f) > 1 or f in system.externs}
    if dupes:
        raise head.error(f"parameter name(s) {sorted(dupes)} used twice (or also #extern) in one production", start)
    variables = set(formals) | set(system.externs)
    condition = None
    if head.accept(":"):
        if head.accept("*"):
            condition = None
        else:
            condition = parse_expression(head, system.constants, variables, 0, system.host)
            if condition.const is not None and condition.const != 0:
                condition = None
    if not head.at_end():
        raise head.error(f"expected ':' condition or '->', found {head.describe_next()}")
    body = Cursor(line, file, number)
    body.pos = arrow.end()
    alternatives = _alternatives(body, system.constants, variables, system.host)
    key = re.sub(r"\s+", "", line[start : arrow.start()])
    prev = system.productions[-1] if system.productions else None
    explicit = _starts_with_probability(line, arrow.end())
    if prev is not None and explicit and prev.stochastic and prev.key == key:
        prev.alternatives.extend(alternatives)
        return
    system.productions.append(Production(pred, left, right, condition, alternatives, number, key, explicit))


def _patterns(cur: Cursor) -> tuple[tuple[Pattern, ...], Pattern, tuple[Pattern, ...]]:
    cur.skip_ws()
    pred_at = cur.pos
    first = _pattern_list(cur)
    left: list[Pattern] = []
    if cur.accept("<"):
        pred_at = cur.pos
        left, first = first, _pattern_list(cur)
    if len(first) != 1:
        raise cur.error("the predecessor must be exactly one module (use '<' and '>' for context)", pred_at)
    right: list[Pattern] = []
    if cur.accept(">"):
        right = _pattern_list(cur)
        if not right:
            raise cur.error("expected a right-context module after '>'")
    if cur.peek(1) == "<":
        raise cur.error("left context '<' must come before the predecessor")
    return _drop_wildcard(left), first[0], _drop_wildcard(right)


def _drop_wildcard(context: list[Pattern]) -> tuple[Pattern, ...]:
    """A context of just '*' (ABOP: any module, or none) constrains nothing."""
    if len(context) == 1 and context[0].symbol == ord("*") and not context[0].formals:
        return ()
    return tuple(context)


def _pattern_list(cur: Cursor) -> list[Pattern]:
    out: list[Pattern] = []
    while not cur.at_end():
        ch = cur.text[cur.pos]
        if ch in _PATTERN_STOP:
            break
        if ch in "[]":
            raise cur.error("brackets are not supported in context patterns")
        if not valid_symbol(ch):
            raise cur.error(f"{ch!r} cannot be a module symbol")
        cur.pos += 1
        formals: list[str] = []
        if cur.accept("("):
            while True:
                name = cur.name()
                if name is None:
                    raise cur.error(f"expected a parameter name, found {cur.describe_next()}")
                formals.append(name)
                if cur.accept(")"):
                    break
                cur.expect(",", "',' or ')' after a parameter name")
        out.append(Pattern(ord(ch), tuple(formals)))
    return out


def _starts_with_probability(line: str, pos: int) -> bool:
    return line[pos:].lstrip().startswith("(")


def _alternatives(cur: Cursor, constants: dict[str, float], variables: set[str],
                  host: HostFunctions | None = None) -> list[Alternative]:
    if cur.peek(1) != "(":
        return [_alternative(1.0, _successor(cur, constants, variables, stop_at_bar=False, host=host))]
    alts: list[Alternative] = []
    while True:
        cur.expect("(")
        weight = parse_expression(cur, constants, set())
        if weight.const is None or not weight.const >= 0:
            raise cur.error("a probability must be a constant number >= 0")
        cur.expect(")", "')' after the probability")
        alts.append(_alternative(weight.const, _successor(cur, constants, variables, stop_at_bar=True, host=host)))
        if not cur.accept("|"):
            break
    if not cur.at_end():
        raise cur.error(f"unexpected {cur.describe_next()}")
    return alts


SuccModules = list[tuple[int, list[Expr]]]


def _successor(cur: Cursor, constants: dict[str, float], variables: set[str], stop_at_bar: bool,
               host: HostFunctions | None = None) -> SuccModules:
    mods: SuccModules = []
    open_at: list[int] = []
    while not cur.at_end():
        ch = cur.text[cur.pos]
        if stop_at_bar and ch == "|" and cur.text[cur.pos + 1 :].lstrip().startswith("("):
            break
        if ch == "ε":
            cur.pos += 1
            continue
        if not valid_symbol(ch):
            raise cur.error(f"{ch!r} cannot be a module symbol")
        if ch == "[":
            open_at.append(cur.pos)
        elif ch == "]":
            if not open_at:
                raise cur.error("']' without a matching '['")
            open_at.pop()
        cur.pos += 1
        exprs: list[Expr] = []
        if cur.text.startswith("(", cur.pos):
            cur.pos += 1
            while True:
                exprs.append(parse_expression(cur, constants, variables, 0, host))
                if cur.accept(")"):
                    break
                cur.expect(",", "',' or ')' in the parameter list")
            if len(exprs) > MAX_PARAMS:
                raise cur.error(f"more than {MAX_PARAMS} parameters")
        mods.append((ord(ch), exprs))
    if open_at:
        raise cur.error("'[' is never closed in this successor", open_at[-1])
    return mods


def _alternative(weight: float, mods: SuccModules) -> Alternative:
    symbols = np.array([m[0] for m in mods], np.uint8)
    nparams = np.array([len(m[1]) for m in mods], np.uint8)
    return Alternative(weight, symbols, nparams, [m[1] for m in mods])


def _constant_lstring(mods: SuccModules) -> LString:
    ctx = EvalContext({}, 1, np.random.default_rng(0))
    values = [float(evaluate(e, ctx)[0]) for _, exprs in mods for e in exprs]
    return LString.from_arrays(
        np.array([m[0] for m in mods], np.uint8),
        np.array([len(m[1]) for m in mods], np.uint8),
        np.array(values, np.float64),
    )
