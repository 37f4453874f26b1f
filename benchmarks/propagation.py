"""Seed 001 Fig. 6 on our trees: branch and polygon counts per growth step, divisor-function
propagation (Algorithm 2) against a fixed three-way branching rule.

Run: python -m benchmarks.propagation
Both trees are ordinary L-systems derived by the same engine and meshed by the same mesher
(n_surf = 6, straight segments): assets/lsystems/divisor_tree.lsys with children(level) from
engine/forest/divisors.py, and the same file with children() fixed at 3.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from arbor.engine.forest.divisors import PropagationRule, children_function, children_table, sigma, sigma_alt
from arbor.engine.geometry.mesh import wood_mesh
from arbor.engine.geometry.turtle import TurtleConfig, interpret
from arbor.engine.lsystem.derive import derive
from arbor.engine.lsystem.lsys import parse_lsystem

SOURCE = Path(__file__).resolve().parent.parent / "assets" / "lsystems" / "divisor_tree.lsys"
STEPS = 9


def counts(host: dict, steps: int) -> list[tuple[int, int]]:
    """(branches, triangles) after each derivation step."""
    system = parse_lsystem(SOURCE.read_text(), str(SOURCE), overrides={"LEVELS": steps}, host=host)
    out = []
    for n in range(1, steps + 1):
        ls = derive(system, n)
        segs = interpret(ls, TurtleConfig(leaves_at_tips=0)).segments
        out.append((ls.count("F"), wood_mesh(segs, n_surf=6, n_div=1).n_triangles))
    return out


def main() -> None:
    """Print the table."""
    rules = [PropagationRule(lambda k: sigma(0, k)), PropagationRule(lambda k: sigma_alt(0, k), 2),
             PropagationRule(lambda k: sigma(0, k), 3)]
    table = children_table(rules, STEPS, seed=3)
    divisor = counts({"children": children_function(table)}, STEPS)
    fixed = counts({"children": children_function(np.full(STEPS + 1, 3))}, STEPS)
    print(f"children per level (Algorithm 2, seed 3): {table.tolist()}")
    print(f"{'step':>4} {'fixed 3: branches':>18} {'triangles':>10} {'divisor: branches':>18} {'triangles':>10} "
          f"{'ratio':>6}")
    for n, ((fb, ft), (db, dt)) in enumerate(zip(fixed, divisor, strict=True), start=1):
        print(f"{n:>4} {fb:>18,} {ft:>10,} {db:>18,} {dt:>10,} {fb / db:>6.1f}")


if __name__ == "__main__":
    main()
