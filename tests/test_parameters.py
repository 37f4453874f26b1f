"""No public function or constructor in engine/ or game/ takes more than MOST parameters (self aside):
what belongs together travels as one object (HudParts, CareParts, LobeGrowth, stage.Scene, ...).

Numba kernels are exempt (compiled code takes arrays, not objects); the few listed below may keep what
they take today and no more, each with why it is not done yet.
"""

from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MOST = 8
NOT_YET = {  # "path:Class.function" -> its parameters today, the most it may keep
    "engine/life/plant/growth.py:GrowingTree.sense": 10,  # the plant science is being rewritten around it
    "engine/modeling/crown_fill.py:grow_within": 9,  # its one caller is engine/life/world/commands.py
}


def _numba(node: ast.FunctionDef) -> bool:
    def name(d: ast.expr) -> str:
        d = d.func if isinstance(d, ast.Call) else d
        return d.attr if isinstance(d, ast.Attribute) else getattr(d, "id", "")
    return any(name(d) in ("njit", "jit", "vectorize", "guvectorize") for d in node.decorator_list)


def parameter_counts(root: Path = ROOT) -> dict[str, int]:
    """Every public function, method and constructor of engine/ and game/ -> its parameters (self and
    cls aside, *args and **kwargs counting one each); numba kernels left out."""
    counts = {}
    for path in sorted(p for top in ("engine", "game") for p in (root / top).rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        owners = {id(f): c for c in ast.walk(tree) if isinstance(c, ast.ClassDef) for f in c.body}
        for node in ast.walk(tree):
            if not isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef) or _numba(node):
                continue
            owner = owners.get(id(node))
            public = node.name == "__init__" or not node.name.startswith("_")
            if not public or (owner is not None and owner.name.startswith("_")):
                continue
            args = node.args
            names = [a.arg for a in args.posonlyargs + args.args + args.kwonlyargs]
            if owner is not None and names and names[0] in ("self", "cls"):
                names = names[1:]
            where = f"{owner.name}.{node.name}" if owner is not None else node.name
            counts[f"{path.relative_to(root)}:{where}"] = (len(names) + (args.vararg is not None)
                                                          + (args.kwarg is not None))
    return counts


def too_many(counts: dict[str, int]) -> list[str]:
    """The functions over MOST parameters that are not listed, or listed and grown past what they had."""
    return [f"{name} takes {n}" for name, n in counts.items() if n > NOT_YET.get(name, MOST)]


def test_no_public_function_takes_more_than_most_parameters():
    assert too_many(parameter_counts()) == [], (
        f"more than {MOST} parameters: pass what belongs together as one object (a dataclass)")


def test_the_count_bites(tmp_path):
    (tmp_path / "engine").mkdir()
    (tmp_path / "game").mkdir()
    (tmp_path / "engine" / "x.py").write_text(
        "import numba\n\n\nclass Hud:\n    def __init__(self, a, b, c, d, e, f, g, h, *, i):\n        pass\n\n"
        "    def _inner(self, a, b, c, d, e, f, g, h, i):\n        pass\n\n\n"
        "def fine(a, b, c, d, e, f, g, *rest):\n    pass\n\n\n"
        "@numba.njit(cache=True)\ndef kernel(a, b, c, d, e, f, g, h, i):\n    pass\n")
    counts = parameter_counts(tmp_path)
    assert counts == {"engine/x.py:Hud.__init__": 9, "engine/x.py:fine": 8}
    assert too_many(counts) == ["engine/x.py:Hud.__init__ takes 9"]
