"""Save files: a readable TOML text holding the tree's L-string, its rules, sim and RNG state.

A player can open a save in any text editor and read the L-string (wrapped at 100 characters).
Saves are shared between players, so loading treats them as hostile: TOML is parsed by the standard
library (no eval), the embedded .lsys source by our own parser, the L-string by ``parse_lstring``;
every problem is a :class:`SaveError` naming the file, line and column. Writes are atomic.
"""

from __future__ import annotations

import hashlib
import json
import math
import re
import time
import tomllib
from collections.abc import Callable
from pathlib import Path

import numpy as np

from engine.base.errors import LSysError
from engine.base.files import atomic_write
from engine.life.sim import Rules, SimState, Simulation
from engine.life.world import World
from engine.lsystem.lstring import format_number, parse_lstring
from engine.lsystem.lsys import parse_lsystem

FORMAT = 1
WRAP = 100
MAX_BYTES = 64 * 1024 * 1024
MIGRATIONS: dict[int, Callable[[dict], dict]] = {}  # format N -> function turning a format-N dict into format N + 1


class SaveError(LSysError):
    """A save file that cannot be loaded; the file itself is left untouched."""


def _escape(text: str, keep_newlines: bool = False) -> str:
    out = text.replace("\\", "\\\\").replace('"', '\\"')
    controls = {c for c in out if ord(c) < 32 or ord(c) == 127} - ({"\n", "\t"} if keep_newlines else {"\t"})
    for c in controls:
        out = out.replace(c, f"\\u{ord(c):04x}")
    return out


def _toml_string(text: str) -> str:
    return '"' + _escape(text) + '"'


def _toml_text(text: str) -> str:
    """A multi-line basic string keeping the text's own lines (for the embedded .lsys source)."""
    return '"""\n' + _escape(text, keep_newlines=True) + '"""'


def _toml_block(text: str) -> str:
    """Whitespace-free text wrapped with line-ending backslashes (TOML joins the lines on reading)."""
    pieces = [text[i : i + WRAP] for i in range(0, len(text), WRAP)] or [""]
    escaped = [_escape(p) for p in pieces]
    return '"""\\\n' + "\\\n".join(escaped) + '\\\n"""'


def _toml_value(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf") if math.isinf(value) else repr(value)
    return _toml_string(str(value))


def _table(name: str, data: dict) -> list[str]:
    lines = [f"[{name}]"]
    nested = []
    for key, value in data.items():
        if isinstance(value, dict):
            nested.append((f"{name}.{key}", value))
        else:
            lines.append(f"{key} = {_toml_value(value)}")
    for sub, values in nested:
        lines += ["", *_table(sub, values)]
    return lines


def _rng_text(rng: np.random.Generator) -> str:
    return json.dumps(rng.bit_generator.state, separators=(",", ":"))


def save_text(world: World, lsystem_name: str, saved_at: float | None = None) -> str:
    """The text of a save file for ``world`` (see module docstring); ``saved_at`` defaults to now."""
    ls = world.tree.lstring
    lines = [
        "# Arbor save file: a tree, its rules and its state. The L-string is at the end.",
        f"format = {FORMAT}",
        f"saved_at = {time.time() if saved_at is None else saved_at!r}",
        f"seed = {world.seed}",
        f"steps = {world.steps}",
        f"position = [{format_number(float(world.position[0]))}, {format_number(float(world.position[1]))}]",
        f"lsystem = {_toml_string(lsystem_name)}",
        f"lsystem_sha256 = {_toml_string(world.system.sha256)}",
        f"lsystem_source = {_toml_text(world.system.source)}",
        "",
        *_table("sim", world.sim.state.to_dict()),
        "",
        "[tree]",
        f"last_rewrite_T = {format_number(world.tree.last_rewrite_T)}",
        *_light_lines(world),
        f"rng_world = {_toml_string(_rng_text(world.rng))}",
        f"rng_tree = {_toml_string(_rng_text(world.tree.deriver.rng))}",
        f"modules = {len(ls)}",
        f"lstring = {_toml_block(ls.to_text())}",
        "",
    ]
    return "\n".join(lines)


def _light_lines(world: World) -> list[str]:
    """The light state that is not in the L-string: when light was last read, the remembered mean
    light direction and light, and how many branches were shed (for the player's records)."""
    tree = world.tree
    lines = [f"light_dir = [{', '.join(format_number(float(v)) for v in tree.light_dir)}]",
             f"mean_light = {format_number(tree.mean_light)}",
             f"shed_total = {tree.shed_total}"]
    if np.isfinite(world.last_light):
        lines.append(f"last_light = {format_number(world.last_light)}")
    if tree.last_sense_length is not None and tree.last_sense_girth is not None:
        lines += [f"last_sense_length = {format_number(tree.last_sense_length)}",
                  f"last_sense_girth = {format_number(tree.last_sense_girth)}"]
    return lines


def _restore_light(world: World, tree: dict, path: Path, text: str) -> None:
    """Inverse of :func:`_light_lines`; every key is optional (saves from before the living tree)."""
    def number(key: str, default: float | None) -> float | None:
        if key not in tree:
            return default
        value = _require(tree, key, int | float, path, text)
        if not math.isfinite(value):
            raise SaveError(f"'{key}' must be a finite number", str(path), _line_of(text, key), 1)
        return float(value)

    direction = tree.get("light_dir", [0.0, 1.0, 0.0])
    if (not isinstance(direction, list) or len(direction) != 3
            or not all(isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v) for v in direction)
            or not 0.5 < math.hypot(*direction) < 2.0):
        raise SaveError("'light_dir' must be a unit vector [x, y, z]", str(path), _line_of(text, "light_dir"), 1)
    t = world.tree
    t.light_dir = np.array(direction, float) / math.hypot(*direction)
    t.mean_light = min(max(number("mean_light", 1.0), 0.0), 1.0)
    shed = tree.get("shed_total", 0)
    t.shed_total = shed if isinstance(shed, int) and not isinstance(shed, bool) and shed >= 0 else 0
    world.last_light = number("last_light", float("-inf"))
    t.last_sense_length = number("last_sense_length", None)
    t.last_sense_girth = number("last_sense_girth", None)


def save_world(world: World, path: str | Path, lsystem_name: str = "game_tree.lsys",
               saved_at: float | None = None) -> None:
    """Write ``world`` to ``path`` atomically (temp file, fsync, rename)."""
    atomic_write(path, save_text(world, lsystem_name, saved_at).encode("utf-8"))


def _toml_error_position(message: str) -> tuple[int, int]:
    m = re.search(r"line (\d+), column (\d+)", message)
    return (int(m.group(1)), int(m.group(2))) if m else (1, 1)


def _read(path: Path) -> tuple[dict, str]:
    try:
        raw = path.read_bytes()
    except OSError as exc:
        raise SaveError(f"cannot read: {exc.strerror}", str(path)) from None
    if len(raw) > MAX_BYTES:
        raise SaveError(f"too large ({len(raw):,} bytes; at most {MAX_BYTES:,})", str(path))
    try:
        text = raw.decode("utf-8")
        return tomllib.loads(text), text
    except UnicodeDecodeError as exc:
        raise SaveError(f"not UTF-8 text (byte {exc.start})", str(path)) from None
    except tomllib.TOMLDecodeError as exc:
        line, col = _toml_error_position(str(exc))
        raise SaveError(f"not a valid save: {exc}", str(path), line, col) from None


def _line_of(text: str, key: str) -> int:
    m = re.search(rf"^\s*{re.escape(key)}\s*=", text, re.MULTILINE)
    return text.count("\n", 0, m.start()) + 1 if m else 1


def _require(data: dict, key: str, kind, path: Path, text: str):
    if key not in data:
        raise SaveError(f"missing '{key}'", str(path))
    value = data[key]
    if not isinstance(value, kind) or (isinstance(value, bool) and kind is not bool):
        raise SaveError(f"'{key}' has the wrong type", str(path), _line_of(text, key), 1)
    return value


def _migrate(data: dict, path: Path, text: str) -> dict:
    version = _require(data, "format", int, path, text)
    if version > FORMAT:
        raise SaveError(f"saved by a newer Arbor (format {version}); this one reads up to {FORMAT}", str(path),
                        _line_of(text, "format"), 1)
    while version < FORMAT:
        if version not in MIGRATIONS:
            raise SaveError(f"format {version} is too old to read", str(path), _line_of(text, "format"), 1)
        data = MIGRATIONS[version](data)
        version += 1
    return data


def _restore_rng(rng: np.random.Generator, state_text: str, key: str, path: Path, text: str) -> None:
    try:
        state = json.loads(state_text)
        if not isinstance(state, dict) or state.get("bit_generator") != "PCG64":
            raise ValueError("not a PCG64 state")
        rng.bit_generator.state = state
    except (ValueError, TypeError, KeyError) as exc:
        raise SaveError(f"bad random state in '{key}': {exc}", str(path), _line_of(text, key), 1) from None


def load_world(path: str | Path, rules: Rules | None = None, budget_slack: float = 1.0) -> tuple[World, float]:
    """Load a save; returns the world and the wall-clock time it was saved at."""
    path = Path(path)
    data, text = _read(path)
    data = _migrate(data, path, text)
    source = _require(data, "lsystem_source", str, path, text)
    digest = _require(data, "lsystem_sha256", str, path, text)
    if hashlib.sha256(source.encode("utf-8")).hexdigest() != digest:
        line = _line_of(text, "lsystem_sha256")
        raise SaveError("the embedded .lsys source does not match its hash", str(path), line)
    try:
        system = parse_lsystem(source, f"{path} (embedded .lsys)")
    except LSysError as err:
        raise SaveError(err.message, err.file, _line_of(text, "lsystem_source") + err.line, err.col) from None
    world = World(system, rules or Rules(), seed=int(_require(data, "seed", int, path, text)))
    world.steps = int(_require(data, "steps", int, path, text))
    position = data.get("position", [0.0, 0.0])  # optional: saves from before gardens have none
    if (not isinstance(position, list) or len(position) != 2
            or not all(isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v) for v in position)):
        raise SaveError("'position' must be [x, z]", str(path), _line_of(text, "position"), 1)
    world.position = (float(position[0]), float(position[1]))
    try:
        world.sim = Simulation(world.rules, SimState.from_dict(_require(data, "sim", dict, path, text)))
    except (TypeError, ValueError) as exc:
        line = text.count("\n", 0, max(text.find("[sim]"), 0)) + 1
        raise SaveError(f"bad [sim] table: {exc}", str(path), line, 1) from None
    tree = _require(data, "tree", dict, path, text)
    lstring_text = _require(tree, "lstring", str, path, text)
    limit = int((system.budget or 10**6) * 2 * budget_slack)
    if _require(tree, "modules", int, path, text) > limit or len(lstring_text) > 64 * limit:
        raise SaveError(f"the tree is larger than this L-system's budget allows ({limit:,} modules)", str(path),
                        _line_of(text, "modules"))
    try:
        world.tree.lstring = parse_lstring(lstring_text, str(path))
    except LSysError as err:
        pos = err.col - 1  # the L-string is one line once TOML has joined its wrapped lines
        line = _line_of(text, "lstring") + 1 + pos // WRAP
        raise SaveError(f"in the L-string: {err.message}", str(path), line, pos % WRAP + 1) from None
    world.tree.last_rewrite_T = float(_require(tree, "last_rewrite_T", int | float, path, text))
    _restore_light(world, tree, path, text)
    _restore_rng(world.rng, _require(tree, "rng_world", str, path, text), "rng_world", path, text)
    _restore_rng(world.tree.deriver.rng, _require(tree, "rng_tree", str, path, text), "rng_tree", path, text)
    return world, float(_require(data, "saved_at", int | float, path, text))


def load_trees(path: str | Path, rules: Rules | None = None) -> list[World]:
    """Every tree in a save, in planting order (a single-tree save gives one)."""
    world, _ = load_world(path, rules)
    return [world]
