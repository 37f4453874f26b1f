"""A seedling's own genome: the species' L-system with the traits the species lets vary drawn for this seed.

A species' .lsys says which of its ``#define`` values vary between seedlings and by how much: a define
``X_VAR`` (a share, e.g. 0.12) lets ``X`` vary by up to +-12 %. Each seed draws its values once, uniformly
within those ranges, so two seedlings of one species differ in bud fates, branching angles and vigour the
way siblings do, and the same seed always grows the same tree. The drawn values are kept with the tree
(its save's [trees.genome]), so a tree keeps its traits when the species' ranges change.
"""

from __future__ import annotations

import numpy as np

from arbor.engine.lsystem.lsys import LSystem, parse_lsystem

SUFFIX = "_VAR"
MAX_EXPRESSED = 32  # species-and-genome systems kept parsed (systems are never changed after parsing)
_EXPRESSED: dict[tuple, tuple[LSystem, LSystem]] = {}


def ranges(system: LSystem) -> dict[str, float]:
    """The defines ``system`` lets vary, each with its largest share of change (0..0.9)."""
    return {name[: -len(SUFFIX)]: min(max(float(v), 0.0), 0.9) for name, v in system.constants.items()
            if name.endswith(SUFFIX) and name[: -len(SUFFIX)] in system.constants}


def draw(system: LSystem, seed: int) -> dict[str, float]:
    """This seed's values of the varying defines (in a fixed order, so a seed always draws the same)."""
    rng = np.random.default_rng([int(seed) % 2**63, 0x6E0E])
    return {name: float(system.constants[name]) * (1.0 + float(rng.uniform(-share, share)))
            for name, share in sorted(ranges(system).items())}


def checked(system: LSystem, genome: dict[str, float]) -> dict[str, float]:
    """``genome`` (from a shared save: untrusted) kept to the defines the species varies and to their ranges."""
    allowed, out = ranges(system), {}
    for name, value in genome.items():
        if name in allowed and isinstance(value, int | float) and np.isfinite(value):
            base = float(system.constants[name])
            low, high = sorted((base * (1 - allowed[name]), base * (1 + allowed[name])))
            out[name] = min(max(float(value), low), high)
    return out


def expressed(system: LSystem, genome: dict[str, float]) -> LSystem:
    """The species' system with ``genome``'s values in place of its defines (the species itself when none).
    Parsed once per species and genome (the last MAX_EXPRESSED kept): a tree loaded again (a Restore, the next start)
    or replayed does not parse its species anew."""
    if not genome:
        return system
    key = (id(system), tuple(sorted((str(k), float(v)) for k, v in genome.items())))
    kept = _EXPRESSED.get(key)
    if kept is not None and kept[0] is system:
        return kept[1]
    varied = parse_lsystem(system.source, system.file, overrides={**system.overrides, **genome}, host=system.host)
    varied.budget = system.budget
    _EXPRESSED[key] = (system, varied)  # (the species' system is kept too, so its id stays its own)
    while len(_EXPRESSED) > MAX_EXPRESSED:
        del _EXPRESSED[next(iter(_EXPRESSED))]
    return varied
