"""A tree's crown lobes in its save (``[trees.crown]``, format 3; older saves have none and load without
lobes): each lobe's mesh as text (its vertices and triangles as space-separated numbers, one string per
lobe), its stroke rings' layout, how it grew (``crown_style``, the crown panel's options) and the tree before
the crown (``crown_base``, an L-string, written only while the tree is as the crown grew it: a lobe edit
after loading then regrows the crown from it, as in the session that drew it).

The save is untrusted: at most MAX_LOBES lobes of at most MAX_LOBE_VERTICES vertices and
MAX_LOBE_FACES triangles, every number finite and within POSITION_LIMIT, every triangle's corners
vertices of its lobe, the stroke rings within the vertices; anything else is a SaveError naming the
file, line and column of the key.
"""

from __future__ import annotations

import numpy as np

from arbor.engine.base.errors import LSysError
from arbor.engine.life.keep.save_check import POSITION_LIMIT, SaveError, Where, lstring_sane
from arbor.engine.lsystem.lstring import LString, parse_lstring
from arbor.engine.lsystem.text import format_number
from arbor.engine.modeling.crown_style import CrownStyle, load_styles
from arbor.engine.modeling.crowned import MAX_LOBE_FACES, MAX_LOBE_VERTICES, MAX_LOBES, CrownRecord
from arbor.engine.modeling.lobes import Lobe

NUMBER_CHARACTERS = 32  # characters a saved number may take (with its space)
KEYS = ("lobe_vertices", "lobe_faces", "lobe_rings", "lobe_ring_sizes")
STYLE_KEYS = ("twig", "fork", "straight", "rise", "leaf_size", "leaves")  # the crown panel's (crown_style.py)


def crown_lines(crown: CrownRecord | None, tree: LString, lstring_text) -> list[str]:
    """The ``[trees.crown]`` lines of a tree whose crown is ``crown`` (none: no lines); ``tree`` is the
    tree's L-string now and ``lstring_text`` writes an L-string as the save does."""
    if crown is None or not crown.lobes:
        return []
    lobes = crown.lobes[:MAX_LOBES]
    vertices = [" ".join(format_number(float(v)) for v in
                         np.clip(np.nan_to_num(lobe.vertices), -POSITION_LIMIT, POSITION_LIMIT).ravel())
                for lobe in lobes]
    faces = [" ".join(str(int(i)) for i in lobe.faces.ravel()) for lobe in lobes]
    lines = ["[trees.crown]",
             "lobe_vertices = [" + ", ".join(f'"{v}"' for v in vertices) + "]",
             "lobe_faces = [" + ", ".join(f'"{f}"' for f in faces) + "]",
             f"lobe_rings = [{', '.join(str(int(lobe.rings)) for lobe in lobes)}]",
             f"lobe_ring_sizes = [{', '.join(str(int(lobe.ring_size)) for lobe in lobes)}]"]
    if crown.style is not None:
        values = ", ".join(f"{name} = {format_number(float(getattr(crown.style, name)))}" for name in STYLE_KEYS)
        lines.append(f"crown_style = {{{values}}}")
    if crown.base is not None and crown.grown is tree:
        lines.append(f"crown_base = {lstring_text(crown.base)}")
    return [*lines, ""]


def _numbers(text, dtype, count: int, key: str, k: int, where: Where) -> np.ndarray:
    """Lobe ``k``'s space-separated numbers under ``key``: at most ``count`` of them, all of ``dtype``."""
    if not isinstance(text, str):
        raise where.error(f"'{key}' #{k + 1} must be text (numbers between spaces)", key)
    if len(text) > count * NUMBER_CHARACTERS:
        raise where.error(f"'{key}' #{k + 1} is too long ({len(text):,} characters)", key)
    try:
        numbers = np.array(text.split(), dtype=dtype)
    except (ValueError, OverflowError):
        raise where.error(f"'{key}' #{k + 1} must hold {'whole ' if dtype is np.int64 else ''}numbers only",
                          key) from None
    if len(numbers) > count:
        raise where.error(f"'{key}' #{k + 1} holds {len(numbers):,} numbers, at most {count:,}", key)
    return numbers


def _count(v, key: str, k: int, most: int, where: Where) -> int:
    """Lobe ``k``'s whole number under ``key``, 0 to ``most``."""
    if isinstance(v, bool) or not isinstance(v, int) or not 0 <= v <= most:
        raise where.error(f"'{key}' #{k + 1} must be a whole number from 0 to {most} (its vertices)", key)
    return v


def _lobe(data: dict, k: int, where: Where) -> Lobe:
    """Lobe ``k`` of a checked ``[trees.crown]``."""
    vertices = _numbers(data["lobe_vertices"][k], np.float64, 3 * MAX_LOBE_VERTICES, "lobe_vertices", k, where)
    if len(vertices) % 3 or len(vertices) < 12 or not (np.abs(vertices) <= POSITION_LIMIT).all():
        raise where.error(f"'lobe_vertices' #{k + 1} must be 4 or more points (x y z), each number finite and "
                          f"within +-{POSITION_LIMIT:g}", "lobe_vertices")
    faces = _numbers(data["lobe_faces"][k], np.int64, 3 * MAX_LOBE_FACES, "lobe_faces", k, where)
    n = len(vertices) // 3
    if len(faces) % 3 or len(faces) < 12 or faces.min() < 0 or faces.max() >= n:
        raise where.error(f"'lobe_faces' #{k + 1} must be 4 or more triangles (three vertex numbers 0 to {n - 1})",
                          "lobe_faces")
    rings, size = (_count(data[key][k], key, k, n, where) for key in ("lobe_rings", "lobe_ring_sizes"))
    if rings and not (rings >= 2 and size >= 3 and rings * size + 2 <= n):  # (two caps beside the rings)
        raise where.error(f"lobe #{k + 1}: {rings} rings of {size} points do not fit its {n} vertices (2 or more "
                          "rings of 3 or more points, and two caps)", "lobe_rings")
    return Lobe(vertices.reshape(-1, 3), faces.reshape(-1, 3), size, rings)


def read_crown(data: dict, where: Where, tree: LString, limit: int) -> CrownRecord | None:
    """The crown of a tree's checked ``[trees.crown]`` table (None: the save has none); ``tree`` is its
    loaded L-string, ``limit`` the most modules its crown base may hold."""
    crown = data.get("crown")
    if crown is None:
        return None
    if not isinstance(crown, dict):
        raise where.error("'crown' must be a table", "crown")
    for key in KEYS:
        if not isinstance(crown.get(key), list) or len(crown[key]) > MAX_LOBES:
            raise where.error(f"[trees.crown] needs '{key}', a list of at most {MAX_LOBES} entries (one per lobe)",
                              key)
    count = len(crown["lobe_vertices"])
    if any(len(crown[key]) != count for key in KEYS):
        raise where.error("[trees.crown]'s lobe lists must be the same length (one entry per lobe)", "lobe_faces")
    lobes = tuple(_lobe(crown, k, where) for k in range(count))
    base = _base(crown, where, limit) if "crown_base" in crown else None
    style = _style(crown["crown_style"], where) if "crown_style" in crown else None
    return CrownRecord(lobes, base, tree if base is not None else None, style) if lobes else None


def _style(values, where: Where) -> CrownStyle:
    """How the crown grew (the crown panel's options), each a number within its range (assets/crowns.toml)."""
    options, _ = load_styles()
    if not isinstance(values, dict) or not set(values) <= set(options):
        raise where.error(f"'crown_style' must be a table of {', '.join(sorted(options))}", "crown_style")
    for name, value in values.items():
        option = options[name]
        if isinstance(value, bool) or not isinstance(value, int | float) or not option.low <= value <= option.high:
            raise where.error(f"'crown_style' {name} must be a number from {option.low:g} to {option.high:g}",
                              "crown_style")
    return CrownStyle(**{name: float(value) for name, value in values.items()})


def _base(crown: dict, where: Where, limit: int) -> LString:
    """The tree before the crown, checked as the tree's own L-string is."""
    text = crown["crown_base"]
    if not isinstance(text, str) or len(text) > 64 * max(limit, 1):
        raise where.error("'crown_base' must be an L-string no longer than the tree's budget allows", "crown_base")
    try:
        base = parse_lstring(text, str(where.path))
    except LSysError as err:
        raise SaveError(f"in the crown base: {err.message}", str(where.path), where.line("crown_base") + err.line,
                        err.col) from None
    if len(base) > limit:
        raise where.error(f"the crown base is larger than this L-system's budget allows ({limit:,} modules)",
                          "crown_base")
    lstring_sane(base, where, key="crown_base")
    return base
