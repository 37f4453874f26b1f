"""Every path a comment, a docstring, an .lsys, a .toml or a doc names exists, and docs/layout.md names every
top-level game module and every assets/ folder (files move; the words that point at them must follow).

A named path is ``engine/...``, ``game/...``, ``assets/...``, ``docs/...``, ``tests/...`` or ``benchmarks/...``
(a ``*`` or an upper-case placeholder such as ``NAME`` is a pattern: it must match a file; ``ui.Menu`` is a
name in ``ui.py``), or a short ``plant/carbon.py`` relative to an engine or game package (engine/life/plant/...).
"""

from __future__ import annotations

import ast
import io
import re
import tokenize
from collections.abc import Iterator
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
TOPS = ("engine", "game", "assets", "docs", "tests", "benchmarks")
NAMED = re.compile(rf"(?<![\w/.\-])((?:{'|'.join(TOPS)})/[\w./\-*]*[\w/*])")
SHORT = re.compile(r"(?<![\w/.\-])([a-z_]+/[a-z_]+\.py)\b")
PLACEHOLDER = re.compile(r"\b[A-Z][A-Z_]+\b")


def _python_texts(text: str) -> Iterator[tuple[int, str]]:
    """The comments and docstrings of a Python source, with their lines."""
    for token in tokenize.generate_tokens(io.StringIO(text).readline):
        if token.type == tokenize.COMMENT:
            yield token.start[0], token.string
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, ast.Module | ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
            doc = ast.get_docstring(node, clean=False)
            if doc:
                yield node.body[0].lineno, doc


def prose(path: Path) -> Iterator[tuple[int, str]]:
    """The words of ``path`` that may name files: a Python file's comments and docstrings, any other's lines."""
    text = path.read_text(encoding="utf-8")
    if path.suffix == ".py":
        yield from _python_texts(text)
    else:
        yield from enumerate(text.splitlines(), 1)


def files_with_prose(root: Path = ROOT) -> list[Path]:
    """The files whose words are checked: our Python, the assets' .lsys and .toml, docs/*.md and README.md."""
    found = [p for top in ("engine", "game", "tests", "benchmarks") for p in sorted((root / top).rglob("*.py"))]
    found += sorted((root / "assets").rglob("*.lsys")) + sorted((root / "assets").rglob("*.toml"))
    return found + sorted((root / "docs").glob("*.md")) + [root / "README.md"]


def _exists(named: str, root: Path) -> bool:
    named = named.rstrip(".")
    if (root / named).exists():
        return True
    module, _, attribute = named.rpartition(".")
    if module and attribute.isidentifier() and (root / f"{module}.py").is_file():  # game/render/ui.Menu
        return True
    pattern = PLACEHOLDER.sub("*", named)
    return "*" in pattern and any(root.glob(pattern))


def _short_exists(named: str, root: Path) -> bool:
    bases = [root / "engine" / "life", root / "engine", root / "game"]
    return any((base / named).is_file() for base in bases)


def missing_paths(root: Path = ROOT) -> list[str]:
    """``file:line: path`` for every named path that does not exist."""
    bad = []
    for path in files_with_prose(root):
        for line, words in prose(path):
            named = [n for n in NAMED.findall(words) if not _exists(n, root)]
            named += [n for n in SHORT.findall(words) if n.split("/")[0] not in TOPS and not _short_exists(n, root)]
            bad += [f"{path.relative_to(root)}:{line}: {n}" for n in named]
    return bad


def test_every_path_named_in_a_comment_or_doc_exists():
    assert missing_paths() == []


@pytest.mark.parametrize("where, words", [
    ("engine/x.py", "# the sun (engine/life/light.py)\n"),
    ("engine/x.py", '"""Crossing: see engine/life/breed.py."""\n'),
    ("engine/x.py", "def f():\n    \"\"\"Shares (plant/vigor.py).\"\"\"\n"),
    ("assets/lsystems/x.lsys", "// read by the host (engine/life/growth.py):\n"),
    ("assets/x.toml", "# made from engine/life/rules/schemas.py\n"),
    ("docs/x.md", "Presets live in `assets/preset/NAME.toml`.\n"),
])
def test_a_stale_path_is_found(tmp_path, where, words):
    for folder in ("engine/life/plant", "engine/life/lineage", "engine/life/rules", "assets/lsystems",
                   "assets/presets", "docs", "game", "tests", "benchmarks"):
        (tmp_path / folder).mkdir(parents=True, exist_ok=True)
    for real in ("engine/life/plant/light.py", "engine/life/plant/vigour.py", "engine/life/lineage/breed.py",
                 "engine/life/rules/schema.py", "assets/presets/broadleaf.toml", "README.md"):
        (tmp_path / real).write_text("")
    (tmp_path / where).write_text(words)
    assert len(missing_paths(tmp_path)) == 1
    fixed = (words.replace("life/light", "life/plant/light").replace("life/breed", "life/lineage/breed")
             .replace("vigor", "vigour").replace("life/growth", "life/plant/light").replace("schemas", "schema")
             .replace("preset/", "presets/"))
    (tmp_path / where).write_text(fixed)
    assert missing_paths(tmp_path) == []


def test_the_layout_names_every_game_module_and_assets_folder():
    layout = (ROOT / "docs" / "layout.md").read_text(encoding="utf-8")
    modules = [f"game/{p.name}" for p in sorted((ROOT / "game").glob("*.py")) if p.name != "__init__.py"]
    folders = [f"assets/{p.name}/" for p in sorted((ROOT / "assets").iterdir())
               if p.is_dir() and not p.name.startswith(("_", "."))]
    packages = [f"{p.parent.relative_to(ROOT)}/" for top in ("engine", "game")
                for p in (ROOT / top).glob("*/__init__.py")]
    unnamed = [name for name in modules + folders + packages if f"`{name}`" not in layout]
    assert unnamed == [], f"docs/layout.md does not say what these are: {unnamed}"
