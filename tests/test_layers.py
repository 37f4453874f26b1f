"""The architecture as a rule: every package imports only its own layer and the layers below it.

The imports are read from the source (every ``import`` and ``from ... import``, also inside
functions), so an upward import added anywhere fails here.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent

# package -> rank; a module may import its own package or a package of a strictly lower rank.
ENGINE = {"engine.base": 0, "engine.lsystem": 1, "engine.geometry": 2, "engine.forest": 3,
          "engine.modeling": 3, "engine.life": 4,
          # engine/life by job, in ranks of their own (4.0 .. 4.5)
          "engine.life.rules": 4.0, "engine.life.form": 4.1, "engine.life.lineage": 4.1, "engine.life.plant": 4.2,
          "engine.life.world": 4.3, "engine.life.keep": 4.4, "engine.life.experiment": 4.5}
GAME = {"game.paths": 0, "game.errors": 0, "game.signals": 0, "game.report": 0,
        "game.progress": 0.5, "game.strings": 1, "game.loop": 1,  # (progress: report below, first_start above)
        "game.first_start": 1, "game.watchdog": 1, "game.render": 2, "game.audio": 2, "game.input": 2,
        "game.tools": 3, "game.screens": 4, "game.commands": 4, "game.app": 5, "game.cli": 6}
GUI = ("pygame", "moderngl", "glcontext", "OpenGL")


def _package(module: str, table: dict[str, int]) -> str | None:
    """The layer a dotted module name belongs to (its longest matching prefix in ``table``)."""
    parts = module.split(".")
    for k in range(len(parts), 0, -1):
        name = ".".join(parts[:k])
        if name in table:
            return name
    return None


def _module_name(path: Path, root: Path = ROOT) -> str:
    rel = path.relative_to(root).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _ours(name: str) -> str:
    """An imported name as the checkout's folders name it (``arbor.engine.base`` -> ``engine.base``)."""
    return name.removeprefix("arbor.")


def _absolute(node: ast.ImportFrom, path: Path, root: Path) -> str:
    """The module a ``from`` import names, a relative one (``from ..x import y``) resolved against ``path``'s
    package as Python resolves it (our own modules without ``arbor.``)."""
    if node.level == 0:
        return _ours(node.module or "")
    package = _module_name(path, root).split(".")
    if path.name != "__init__.py":
        package.pop()  # a module's own package is its folder; a package's __init__ is the package itself
    base = package[: len(package) - (node.level - 1)] if node.level - 1 <= len(package) else []
    return ".".join([*base, *([node.module] if node.module else [])])


def imports_of(path: Path, root: Path = ROOT) -> list[tuple[str, int]]:
    """Every module ``path`` imports, with the line of the import (our own modules without ``arbor.``);
    relative imports are resolved, so ``from ...life import x`` counts as ``engine.life.x``."""
    tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [(_ours(alias.name), node.lineno) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            module = _absolute(node, path, root)
            if module:
                found.append((module, node.lineno))
            found += [(f"{module}.{alias.name}".lstrip("."), node.lineno) for alias in node.names]
    return found


def violations(root: Path, table: dict[str, int], top: str) -> list[str]:
    """Upward or sideways imports between the layers of ``table`` in the package ``top``."""
    bad, seen = [], set()
    for path in sorted((root / top).rglob("*.py")):
        me = _package(_module_name(path, root), table)
        if me is None:
            continue
        for name, line in imports_of(path, root):
            if not name.startswith(top + "."):
                continue
            other = _package(name, table)
            if other is None or other == me:
                continue
            if table[other] >= table[me] and (path, line) not in seen:
                seen.add((path, line))
                bad.append(f"{path.relative_to(root)}:{line}: {me} (layer {table[me]}) imports {name} "
                           f"(layer {table[other]})")
    return bad


def test_every_engine_and_game_module_belongs_to_a_layer():
    for top, table in (("engine", ENGINE), ("game", GAME)):
        for path in (ROOT / top).rglob("*.py"):
            name = _module_name(path)
            assert name == top or _package(name, table), f"{name} is in no layer: add it to tests/test_layers.py"


@pytest.mark.parametrize("top,table", [("engine", ENGINE), ("game", GAME)])
def test_lower_layers_never_import_higher_ones(top, table):
    assert violations(ROOT, table, top) == []


def test_our_modules_are_imported_by_their_installed_names():
    """Installed, only `arbor.engine` and `arbor.game` exist: an `import engine...` works in a checkout run from
    its root (the folder is on sys.path) and nowhere else, and would load a second copy of the module."""
    for path in [p for top in ("engine", "game", "tests", "benchmarks") for p in (ROOT / top).rglob("*.py")]:
        tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
        for node in ast.walk(tree):
            names = ([a.name for a in node.names] if isinstance(node, ast.Import)
                     else [node.module] if isinstance(node, ast.ImportFrom) and node.module and node.level == 0 else [])
            for name in names:
                assert name.split(".")[0] not in ("engine", "game"), \
                    f"{path.relative_to(ROOT)}:{node.lineno} imports {name}: say arbor.{name}"


def test_engine_is_pure():
    for path in (ROOT / "engine").rglob("*.py"):
        for name, line in imports_of(path):
            assert not name.startswith(("game", *GUI)), f"{path.relative_to(ROOT)}:{line} imports {name}"


def test_every_package_says_what_it_is():
    for init in list((ROOT / "engine").rglob("__init__.py")) + list((ROOT / "game").rglob("__init__.py")):
        doc = ast.get_docstring(ast.parse(init.read_text(encoding="utf-8")))
        assert doc, f"{init.relative_to(ROOT)} has no docstring"


def test_the_rule_bites(tmp_path):
    """An upward import planted in a copy of a low layer is reported."""
    (tmp_path / "engine" / "base").mkdir(parents=True)
    (tmp_path / "engine" / "life").mkdir()
    (tmp_path / "engine" / "base" / "x.py").write_text("def f():\n    from arbor.engine.life.plant.sim import Rules\n")
    (tmp_path / "engine" / "life" / "y.py").write_text("from arbor.engine.base import x\n")
    bad = violations(tmp_path, ENGINE, "engine")
    assert len(bad) == 1 and "engine/base/x.py:2" in bad[0]


@pytest.mark.parametrize("source, imported", [
    ("from ..life.plant import sim\n", "engine.life.plant"),
    ("from ..life.plant.sim import Rules\n", "engine.life.plant.sim"),
    ("def f():\n    from .. import life\n", "engine.life"),
])
def test_an_upward_relative_import_is_caught(tmp_path, source, imported):
    """A relative import is resolved against its package, so climbing a layer with dots is caught too."""
    (tmp_path / "engine" / "base").mkdir(parents=True)
    (tmp_path / "engine" / "base" / "x.py").write_text(source)
    bad = violations(tmp_path, ENGINE, "engine")
    assert len(bad) == 1 and "engine/base/x.py" in bad[0] and f"imports {imported} " in bad[0], bad


def test_a_relative_import_within_a_layer_is_allowed(tmp_path):
    (tmp_path / "engine" / "life" / "plant").mkdir(parents=True)
    (tmp_path / "engine" / "life" / "plant" / "__init__.py").write_text("from . import sim\n")
    (tmp_path / "engine" / "life" / "plant" / "sim.py").write_text("from .carbon import x\nfrom ..rules import r\n")
    assert violations(tmp_path, ENGINE, "engine") == []


def test_no_class_is_over_250_lines():
    for path in list((ROOT / "engine").rglob("*.py")) + list((ROOT / "game").rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ClassDef):
                lines = node.end_lineno - node.lineno + 1
                assert lines <= 250, f"{path.relative_to(ROOT)}: class {node.name} has {lines} lines; split it by job"


def test_pyproject_ships_every_package():
    """`pip install .` (not only -e) must carry every sub-package under `arbor`; assets ship as arbor.assets;
    benchmarks are never installed."""
    import tomllib

    setup = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    listed = set(setup["packages"])
    for top in ("engine", "game"):
        for init in (ROOT / top).rglob("__init__.py"):
            name = "arbor." + ".".join(init.parent.relative_to(ROOT).parts)
            assert name in listed, f"{name} is missing from [tool.setuptools] packages in pyproject.toml"
    assert "arbor.assets" in listed
    assert all(name.startswith("arbor.") for name in listed), "only the arbor namespace is installed"


def test_data_is_found_through_one_place():
    """Code that finds assets/ beside its own file breaks in an installed copy (assets ship as
    arbor.assets): only engine/base/assets.py may look for them."""
    for path in list((ROOT / "engine").rglob("*.py")) + list((ROOT / "game").rglob("*.py")):
        if path.name == "assets.py" and path.parent.name == "base":
            continue
        text = path.read_text(encoding="utf-8")
        assert not ("__file__" in text and '"assets"' in text), f"{path.relative_to(ROOT)} finds assets by itself"
