"""Breeding: two L-systems cross into a child L-system (the productions are the tree's DNA: the tamagotchi
thesis, 6.10).

The cross works on the parents' source text, line by line, so the child is ordinary, readable .lsys
text that saves and shares like any other:

- every production label the mother has (p1, p2, ...) is kept in her order; where the father has the
  same label for the same predecessor symbol, a coin decides whose version the child gets; labels
  only the father has are inherited with a coin too;
- every numeric #define either parent has is mixed (a random point between the two values) and
  mutated by a small log-normal factor (whole numbers stay whole); one-sided constants are inherited;
- #extern names are the union; the axiom and the header come from the mother, the budget is the smaller.

Everything random comes from one seeded generator, so the same parents and seed always give the same
child. The child text is parsed before it is returned; should a combination not parse (productions of
unrelated vocabularies), the father's version of the offending line is dropped for the mother's.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np

from arbor.engine.base.errors import LSysError
from arbor.engine.lsystem.lsys import LSystem, parse_lsystem

MUTATION = 0.05  # standard deviation of the log-normal factor on every mixed constant
_LABEL = re.compile(r"^\s*([pP]\d+)\s*:\s*([^\s(:<>]+)")
_KEPT_DIRECTIVE = re.compile(r"^\s*#(ignore|consider|host)\b")
_HEADER = re.compile(r"^\s*(seed|budget)\s*:", re.IGNORECASE)


@dataclass
class Cross:
    """A bred child: its source text and what it took from whom (for the journal and tests)."""

    source: str
    system: LSystem
    from_father: list[str]  # production labels the child got from the father
    constants: dict[str, float]


def cross(mother: LSystem, father: LSystem, seed: int, name: str = "child") -> Cross:
    """The child of ``mother`` x ``father`` from ``seed`` (see module docstring)."""
    rng = np.random.default_rng(np.random.SeedSequence([int(seed) % 2**63, 0xA7B0]))
    mine, theirs = _productions(mother.source), _productions(father.source)
    chosen, from_father = [], []
    for label, (pred, line) in mine.items():
        other = theirs.get(label)
        if other is not None and other[0] == pred and other[1] != line and rng.random() < 0.5:
            chosen.append((label, other[1]))
            from_father.append(label)
        else:
            chosen.append((label, line))
    for label, (_, line) in theirs.items():
        if label not in mine and rng.random() < 0.5:
            chosen.append((label, line))
            from_father.append(label)
    constants = mix_constants(mother.constants, father.constants, rng)
    externs = tuple(dict.fromkeys((*mother.externs, *father.externs)))
    budgets = [b for b in (mother.budget, father.budget) if b]
    header = _header_lines(mother.source, seed, min(budgets) if budgets else None)
    text = _child_text(name, seed, externs, constants, header, [line for _, line in chosen])
    try:
        system = parse_lsystem(text, name)
    except LSysError:  # a father's production that does not fit the mother's vocabulary: hers instead
        chosen = [(label, mine[label][1]) for label, _ in chosen if label in mine]
        from_father = []
        text = _child_text(name, seed, externs, constants, header, [line for _, line in chosen])
        system = parse_lsystem(text, name)
    return Cross(text, system, from_father, constants)


def mix_constants(a: dict[str, float], b: dict[str, float], rng: np.random.Generator) -> dict[str, float]:
    """Every constant of either parent: shared ones mixed and mutated, whole numbers kept whole."""
    out = {}
    for name in sorted(set(a) | set(b)):
        if name in a and name in b:
            x, y = float(a[name]), float(b[name])
            value = x + (y - x) * rng.random()
            value *= math.exp(rng.normal(0.0, MUTATION))
            if x == int(x) and y == int(y):
                value = float(round(value))
                value = min(max(value, min(x, y) - 1), max(x, y) + 1)  # a whole number stays near its parents
        else:
            value = float(a.get(name, b.get(name)))
        out[name] = value
    return out


def _productions(source: str) -> dict[str, tuple[str, str]]:
    """Labelled production lines of a source: label -> (predecessor symbol, the whole line)."""
    out: dict[str, tuple[str, str]] = {}
    for line in source.splitlines():
        m = _LABEL.match(line)
        if m and ("->" in line or "→" in line):
            out.setdefault(m.group(1).lower(), (m.group(2)[0], line.strip()))
    return out


def _header_lines(source: str, seed: int, budget: int | None) -> list[str]:
    """The mother's header lines (other than seed and budget) and axiom, with the child's seed and budget."""
    lines = [f"seed: {int(seed) % 2**31}"]
    if budget:
        lines.append(f"budget: {budget}")
    for line in source.splitlines():
        stripped = line.strip()
        if _KEPT_DIRECTIVE.match(line):
            lines.append(stripped)
            continue
        if not stripped or stripped.startswith(("//", "#")) or "->" in line or "→" in line:
            continue
        if _HEADER.match(line):
            continue
        lines.append(stripped)
    return lines


def _child_text(name: str, seed: int, externs: tuple[str, ...], constants: dict[str, float],
                header: list[str], productions: list[str]) -> str:
    lines = [f"// {name}: bred by Arbor (seed {seed}); constants mixed from both parents, productions chosen"]
    if externs:
        lines.append("#extern " + " ".join(externs))
    lines += [f"#define {k} {_number(v)}" for k, v in constants.items()]
    return "\n".join([*lines, *header, *productions]) + "\n"


def _number(v: float) -> str:
    return str(int(v)) if v == int(v) and abs(v) < 1e15 else repr(float(v))
