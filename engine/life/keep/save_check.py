"""The validation layer for save files: every field checked for type, range and finiteness.

Saves are shared between players, so nothing in them is trusted. Each check names the field and the
line it is on; what the game writes always passes (tests/test_save.py round-trips fuzzed states).
Ranges are physical limits (a meter is 0..1, a speed is positive), wide enough for any state the game
can reach, so a save made under other rules still loads.
"""

from __future__ import annotations

import json
import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from arbor.engine.base.errors import LSysError
from arbor.engine.life.plant.carbon import CarbonBudget
from arbor.engine.life.plant.sim import GrowthCycle, SimState
from arbor.engine.life.rules.schema import find_rule

BIG = 1e12  # largest magnitude of any saved number (game time 30,000 years; coordinates far off-screen)


class SaveError(LSysError, ValueError):
    """A save file that cannot be loaded; the file itself is left untouched. Also a ValueError: plain
    data checked outside a file (:func:`sim_state`) fails as bad values do."""


# field -> (kind, low, high): kind "float" (int accepted), "int", "bool"
SIM_FIELDS = {
    "time": ("float", 0.0, BIG), "sun_angle": ("float", -BIG, BIG), "orbit_height": ("float", -10.0, 10.0),
    "sun_speed": ("float", 1e-9, 100.0), "sun_meter": ("float", 0.0, 1.0), "water_meter": ("float", 0.0, 1.0),
    "watering": ("bool", 0, 1), "length_time": ("float", 0.0, BIG), "girth_time": ("float", 0.0, BIG),
    "wilt": ("float", 0.0, 1.0), "drowning": ("float", 0.0, BIG), "dead_for": ("float", 0.0, BIG),
    "alive": ("bool", 0, 1), "sun_turns": ("float", 0.0, BIG), "weather_seed": ("int", 0, 2**63 - 1),
    "root_time": ("float", 0.0, BIG), "daylight": ("float", 0.0, 1.0), "root_vigour": ("float", 0.0, 100.0),
    "oxygen": ("float", 0.0, 1.0),
}
# older saves have none (a tree from before the remembered daylight starts at the light that grows it at length_rate)
OPTIONAL_SIM = {"sun_turns": 0.0, "weather_seed": 0, "root_time": 0.0,
                "daylight": find_rule("growth.daylight_full").default, "root_vigour": 1.0,
                "oxygen": 1.0}  # (a save from before the soil's oxygen: a drained soil's)
CYCLE_FIELDS = {"cycle": ("float", 0.0, BIG), "above": ("float", 0.0, BIG), "rate": ("float", 0.0, 1.0),
                "earned": ("int", 0, 2**53)}
CARBON_FIELDS = {  # [trees.carbon] (engine/life/plant/carbon.py); g, s, g per s, m², m³
    "pool": ("float", 0.0, BIG), "starving": ("float", 0.0, BIG), "fixed": ("float", 0.0, BIG),
    "respired": ("float", 0.0, BIG), "built": ("float", 0.0, BIG), "last_fixed_rate": ("float", 0.0, BIG),
    "last_upkeep_rate": ("float", 0.0, BIG), "vigour": ("float", 0.0, 10.0), "leaf_area": ("float", 0.0, 1e8),
    "sapwood": ("float", 0.0, 1e8), "fill_at_next_reading": ("bool", 0, 1), "roots_built": ("float", 0.0, BIG),
    "stored": ("float", 0.0, 1e9), "root_balance": ("float", 0.0, 1e6),
}
TREE_FIELDS = {"seed": ("int", 0, 2**63 - 1), "steps": ("int", 0, 2**53)}  # [[trees]]
GROWTH_FIELDS = {  # [trees.growth]
    "last_rewrite_T": ("float", 0.0, BIG), "mean_light": ("float", 0.0, 1.0), "shed_total": ("int", 0, 2**53),
    "last_light": ("float", -BIG, BIG), "last_sense_length": ("float", 0.0, BIG),
    "last_sense_girth": ("float", 0.0, BIG), "roots_rewrite": ("float", 0.0, BIG),
    "height": ("float", 0.0, BIG),  # (the top of the wood at the last light reading: apical control reads it)
}
POSITION_LIMIT = 1e4  # a tree's place in the garden, scene units either way
JOURNAL_LIMIT = 1e12  # journal times and numbers (plant/journal.py drops rows beyond it)


def fit(v, kind: str, low: float, high: float):
    """``v`` made what the reader accepts for a field of this spec: the writer's half of the one
    validation (a state the game reached beyond a range, or a NaN from a player's .lsys, is saved at the
    nearest accepted value rather than written as a save the next start refuses). NaN becomes the value
    nearest 0; None (a field not written) stays None."""
    if v is None:
        return None
    if kind == "bool":
        return bool(v)
    if kind == "int":
        return min(max(int(v), int(low)), int(high))
    v = float(v)
    if math.isnan(v):
        v = 0.0
    return min(max(v, low), high)


def fitted(data: dict, fields: dict) -> dict:
    """``data`` with every field of ``fields`` passed through :func:`fit` (others, like tables, kept)."""
    return {k: fit(v, *fields[k]) if k in fields else v for k, v in data.items()}


def fitted_params(params: np.ndarray) -> np.ndarray:
    """L-string parameters as the reader accepts them (:func:`lstring_sane`): NaN 0, the rest within
    +-BIG. The same array when nothing needs fixing (the usual case costs one pass)."""
    bad = ~(np.abs(params) <= BIG)
    if not bad.any():
        return params
    return np.clip(np.nan_to_num(params, nan=0.0, posinf=BIG, neginf=-BIG), -BIG, BIG)


@dataclass
class Where:
    """Finds the line a key is on, within one tree's part of the save (for error messages)."""

    path: Path
    text: str
    start: int = 0  # character offset where this tree's part begins
    end: int | None = None

    def line(self, key: str) -> int:
        """The 1-based line of ``key = ...`` in this part (or of its start when the key is missing)."""
        region = self.text[self.start:self.end]
        m = re.search(rf"^\s*{re.escape(key)}\s*=", region, re.MULTILINE)
        at = self.start + (m.start() if m else 0)
        return self.text.count("\n", 0, at) + 1

    def error(self, message: str, key: str | None = None, col: int = 1) -> SaveError:
        """A SaveError about ``key`` (its line), or about this part when no key is given."""
        line = self.line(key) if key else self.text.count("\n", 0, self.start) + 1
        return SaveError(message, str(self.path), line, col)


def value(data: dict, key: str, kind: str, low: float, high: float, where: Where, default=None):
    """``data[key]`` checked: right type, finite, within [low, high]; ``default`` when missing (None:
    required)."""
    if key not in data:
        if default is not None:
            return default
        raise where.error(f"missing '{key}'", key)
    v = data[key]
    if kind == "bool":
        if not isinstance(v, bool):
            raise where.error(f"'{key}' must be true or false", key)
        return v
    if isinstance(v, bool) or not isinstance(v, int | float) or (kind == "int" and not isinstance(v, int)):
        raise where.error(f"'{key}' must be {'a whole number' if kind == 'int' else 'a number'}", key)
    if kind == "float" and not math.isfinite(v):
        raise where.error(f"'{key}' must be a finite number", key)
    if not low <= v <= high:
        raise where.error(f"'{key}' = {v!r} is out of range ({low:g} to {high:g})", key)
    return float(v) if kind == "float" else int(v)


def text_value(data: dict, key: str, where: Where, limit: int) -> str:
    """A required string of at most ``limit`` characters."""
    if key not in data:
        raise where.error(f"missing '{key}'", key)
    v = data[key]
    if not isinstance(v, str):
        raise where.error(f"'{key}' must be text", key)
    if len(v) > limit:
        raise where.error(f"'{key}' is too long ({len(v):,} characters; at most {limit:,})", key)
    return v


def table(data: dict, key: str, where: Where, required: bool = True) -> dict:
    """A sub-table (empty when optional and missing)."""
    if key not in data:
        if required:
            raise where.error(f"missing [{key}]")
        return {}
    if not isinstance(data[key], dict):
        raise where.error(f"'{key}' must be a table", key)
    return data[key]


def vector(data: dict, key: str, n: int, where: Where, default: list[float], limit: float = BIG) -> list[float]:
    """An optional list of ``n`` finite numbers within +-``limit``."""
    v = data.get(key, default)
    if (not isinstance(v, list) or len(v) != n
            or not all(isinstance(x, int | float) and not isinstance(x, bool) and math.isfinite(x) and abs(x) <= limit
                       for x in v)):
        raise where.error(f"'{key}' must be a list of {n} numbers", key)
    return [float(x) for x in v]


def sim_state(data: dict, where: Where | None = None) -> SimState:
    """The simulation state a [sim] table (or :meth:`SimState.to_dict`) describes, checked field by field
    against SIM_FIELDS and CYCLE_FIELDS, the one place a saved field's range is said. Unknown fields are
    errors (a typo must not pass); ``where`` places errors in a save file (None: plain data)."""
    where = where or Where(Path("<sim state>"), "")
    unknown = set(data) - set(SIM_FIELDS) - {"sun_cycle", "water_cycle"}
    if unknown:
        raise where.error(f"unknown field '{sorted(unknown)[0]}' in [sim]", sorted(unknown)[0])
    values = {k: value(data, k, *spec, where, default=OPTIONAL_SIM.get(k)) for k, spec in SIM_FIELDS.items()}
    cycles = {}
    for name in ("sun_cycle", "water_cycle"):
        cycle = table(data, name, where)
        bad = set(cycle) - set(CYCLE_FIELDS)
        if bad:
            raise where.error(f"unknown field '{sorted(bad)[0]}' in [sim.{name}]", sorted(bad)[0])
        cycles[name] = GrowthCycle(**{k: value(cycle, k, *spec, where) for k, spec in CYCLE_FIELDS.items()})
    return SimState(**values, **cycles)


def carbon_budget(data: dict | None, where: Where) -> CarbonBudget:
    """The carbon budget a [trees.carbon] table holds, every field checked against CARBON_FIELDS; a save
    from before the carbon budget has none: its tree starts with the pool filled at the first reading."""
    if data is None:
        return CarbonBudget(fill_at_next_reading=True)
    unknown = set(data) - set(CARBON_FIELDS)
    if unknown:
        raise where.error(f"unknown field '{sorted(unknown)[0]}' in [carbon]", sorted(unknown)[0])
    optional = {"roots_built": 0.0, "stored": 0.0, "root_balance": 0.0}  # (saves from before each was kept)
    return CarbonBudget(**{k: value(data, k, *spec, where, default=optional.get(k))
                           for k, spec in CARBON_FIELDS.items()})


def restore_rng(rng: np.random.Generator, state_text: str, key: str, where: Where) -> None:
    """Set a PCG64 generator from its saved JSON state, checking every number."""
    try:
        state = json.loads(state_text)
        ok = (isinstance(state, dict) and state.get("bit_generator") == "PCG64"
              and isinstance(state.get("state"), dict)
              and all(isinstance(state["state"].get(k), int) and 0 <= state["state"][k] < 2**128
                      for k in ("state", "inc"))
              and state.get("has_uint32") in (0, 1)
              and isinstance(state.get("uinteger"), int) and 0 <= state["uinteger"] < 2**32)
        if not ok:
            raise ValueError("not a PCG64 state")
        rng.bit_generator.state = state
    except (ValueError, TypeError, KeyError, RecursionError) as exc:
        raise where.error(f"bad random state in '{key}': {exc}", key) from None


def lstring_sane(ls, where: Where, key: str = "lstring") -> None:
    """Brackets balance and every parameter is a finite number of sane size (before any geometry); errors
    name the line of ``key``."""
    from arbor.engine.lsystem.brackets import BracketError, check_balanced

    try:
        check_balanced(ls.sym)
    except BracketError as err:
        raise where.error(f"in the L-string: {err}", key) from None
    bad = ~np.isfinite(ls.params) | (np.abs(ls.params) > BIG)
    if bad.any():
        raise where.error(f"in the L-string: a parameter is not a finite number of sane size "
                          f"({ls.params[np.argmax(bad)]!r})", key)
