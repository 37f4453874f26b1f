"""A tree's growth confinement in its save (issue 48: 'the confinement Grow sets is not saved'): the region
a Grow edit holds the tree's growth in and the rewrites it still holds it for, as ``[trees.confine]``
(format 3, optional: a save without it loads with no confinement). The region is a sphere (centre,
radius) or a supertoroid (its eq. 3 parameters by name, engine/modeling/regions.py).

The save is untrusted: the kind one of the two, every number finite and within POSITION_LIMIT, the
sizes above 0, the rewrites left a whole number from 1 to MAX_LEFT; anything else is a SaveError naming
the file, line and column of the key.
"""

from __future__ import annotations

from dataclasses import fields

from arbor.engine.life.keep.save_check import POSITION_LIMIT, Where
from arbor.engine.lsystem.text import format_number
from arbor.engine.modeling.regions import Sphere, Supertoroid

MAX_LEFT = 1000  # rewrites a confinement may still hold (a Grow edit sets 20)
POSITIVE = {"radius", "a_x", "a_y", "a_z", "n", "e"}  # sizes and exponents: above 0


def confine_lines(region, left: int) -> list[str]:
    """The ``[trees.confine]`` lines of a tree confined to ``region`` for ``left`` more rewrites (none: no
    lines)."""
    if region is None or left <= 0 or not isinstance(region, Sphere | Supertoroid):
        return []
    if isinstance(region, Sphere):
        values = {"center": list(region.center), "radius": region.radius}
    else:
        values = {f.name: getattr(region, f.name) for f in fields(Supertoroid)}
    parts = [f'kind = "{"sphere" if isinstance(region, Sphere) else "supertoroid"}"', f"left = {int(left)}"]
    for key, value in values.items():
        text = ("[" + ", ".join(format_number(float(v)) for v in value) + "]" if isinstance(value, list)
                else format_number(float(value)))
        parts.append(f"{key} = {text}")
    return ["[trees.confine]", *parts, ""]


def _number(data: dict, key: str, where: Where) -> float:
    v = data.get(key)
    if isinstance(v, bool) or not isinstance(v, int | float) or not abs(v) <= POSITION_LIMIT or (
            key in POSITIVE and not v > 0):
        raise where.error(f"[trees.confine] '{key}' must be a number within +-{POSITION_LIMIT:g}"
                          + (", above 0" if key in POSITIVE else ""), key)
    return float(v)


def read_confine(data: dict, where: Where) -> tuple[Sphere | Supertoroid | None, int]:
    """The confinement of a tree's checked table (no ``confine``: none, 0 rewrites)."""
    table = data.get("confine")
    if table is None:
        return None, 0
    if not isinstance(table, dict) or table.get("kind") not in ("sphere", "supertoroid"):
        raise where.error("[trees.confine] needs kind = \"sphere\" or \"supertoroid\"", "confine")
    left = table.get("left")
    if isinstance(left, bool) or not isinstance(left, int) or not 1 <= left <= MAX_LEFT:
        raise where.error(f"[trees.confine] 'left' must be a whole number from 1 to {MAX_LEFT}", "left")
    if table["kind"] == "sphere":
        center = table.get("center")
        if not isinstance(center, list) or len(center) != 3:
            raise where.error("[trees.confine] 'center' must be three numbers", "center")
        point = tuple(_number({"center": c}, "center", where) for c in center)
        return Sphere(point, _number(table, "radius", where)), left
    names = [f.name for f in fields(Supertoroid)]
    return Supertoroid(**{name: _number(table, name, where) for name in names if name in table or name in
                          ("a_x", "a_y", "a_z", "alpha_y")}), left
