"""The game rules: the schema's defaults with the overrides of assets/rules.toml, read strictly, with named paces.

A pace scales time: the same rules run at the tamagotchi thesis's demonstration pace (a day of the sun in about
two minutes, growth earned after 20 s above half) or at a home pace (a day of the sun in a day, meters
that last about a day, seasons of a week). Times are multiplied by the pace's time scale and rates
divided by it, so the 20 s / 40 s rules keep their shape; a pace may also override single rules, and may
give a new garden a faster first day (``first_day_speed``: the game lives a garden whose trees are all in
their first day of the sun that many times as fast, so a first session sees its tree grow).
The rules themselves (defaults, ranges, units, what a pace scales) are declared once in schema.py;
the dataclasses here are made from it.
"""

from __future__ import annotations

import functools
import math
from dataclasses import field, make_dataclass
from pathlib import Path

from arbor.engine.base.config import toml_position
from arbor.engine.base.errors import LSysError, RulesError
from arbor.engine.base.reader import read_user_toml
from arbor.engine.life.rules.schema import SCHEMA, SECTION_DOCS, TABLE_MARKERS, Rule, find_rule, rules_table_markdown

SECTIONS = tuple(SECTION_DOCS)


@functools.cache
def rules_class(schema: tuple[Rule, ...] = SCHEMA) -> type:
    """The ``Rules`` dataclass for ``schema``: one field per section (a dataclass of its rules, with the
    schema's defaults), then the pace the rules are at, its time scale (real s per s of the demo pace) and
    how many times as fast a new garden's first day runs at it (1: no faster first day)."""
    sections = []
    for section, (name, doc) in SECTION_DOCS.items():
        own = [(r.name, type(r.default), field(default=r.default)) for r in schema if r.section == section]
        cls = make_dataclass(name, own, namespace={"__doc__": doc, "__module__": __name__})
        sections.append((section, cls, field(default_factory=cls)))
    return make_dataclass("Rules", [*sections, ("pace", str, field(default="demo")),
                                    ("time_scale", float, field(default=1.0)),
                                    ("first_day_speed", float, field(default=1.0))],
                          namespace={"__doc__": "All game rules, one section per table of rules.toml.",
                                     "__module__": __name__, "SCHEMA": schema})


Rules = rules_class(SCHEMA)
_fields = Rules.__dataclass_fields__
GrowthRules, SunRules, WaterRules, HealthRules, ReplantRules, LightRules, WindRules, SeasonRules, WeatherRules, \
    TimeAwayRules, RootRules, CarbonRules = (_fields[s].default_factory for s in SECTIONS)
TIMES = tuple(r.key for r in SCHEMA if r.scales == "time")  # multiplied by a pace's time scale
RATES = tuple(r.key for r in SCHEMA if r.scales == "rate")  # per second: divided by it
PACE_KEYS = ("time_scale", "first_day_speed")  # a pace's own settings (its other keys override single rules)
FIRST_DAY_MOST = 1000.0  # x: the fastest first day a pace may ask for
RULE_RANGES = {r.key: (r.low, r.high) for r in SCHEMA if r.low is not None}  # physical limits of every number


def load_rules(path: str | Path, pace: str | None = None, schema: tuple[Rule, ...] = SCHEMA) -> Rules:
    """Read rules.toml at ``pace`` (default: the file's ``pace``). An unknown table or key, a value of the
    wrong type or out of its range, or a bad pace is a RulesError naming the file, line and column."""
    path = Path(path)
    file = str(path)
    text, data = read_user_toml(path, RulesError)  # (the one reader of files a user can hand us: bounded)
    paces = data.pop("paces", {})
    chosen = pace or data.pop("pace", "demo")
    data.pop("pace", None)
    if not isinstance(paces, dict) or not isinstance(chosen, str) or (chosen != "demo" and chosen not in paces):
        raise RulesError(f"unknown pace {chosen!r}: rules.toml names {', '.join(['demo', *paces])}", file,
                         *toml_position(text, "", "pace"))
    rules = rules_class(schema)()
    for table, values in data.items():
        if table not in SECTIONS or not isinstance(values, dict):
            raise RulesError(f"unknown table [{table}]", file, *toml_position(text, table))
        for name, value in values.items():
            set_rule(rules, f"{table}.{name}", value, file, at=toml_position(text, table, name))
    check_rules(rules, file)
    return apply_pace(rules, chosen, paces.get(chosen, {}), file, text)


def apply_pace(rules: Rules, name: str, pace: dict, file: str = "<rules>", text: str = "") -> Rules:
    """Scale ``rules`` to a pace: times x ``time_scale``, rates / it, then the pace's own overrides
    (``"section.key" = value``, at the pace's own scale, range-checked like the file's rules)."""
    table = f"paces.{name}"
    if not isinstance(pace, dict):
        raise RulesError(f"[{table}] must be a table", file, *toml_position(text, table))
    scale = pace.get("time_scale", 1.0)
    if isinstance(scale, bool) or not isinstance(scale, int | float) or not 0.01 <= scale <= 1e5:
        raise RulesError(f"[{table}] time_scale must be a number from 0.01 to 100000", file,
                         *toml_position(text, table, "time_scale"))
    for rule in type(rules).SCHEMA:
        if rule.scales:
            target = getattr(rules, rule.section)
            value = getattr(target, rule.name)
            setattr(target, rule.name, value * scale if rule.scales == "time" else value / scale)
    first = pace.get("first_day_speed", 1.0)
    if isinstance(first, bool) or not isinstance(first, int | float) or not 1 <= first <= FIRST_DAY_MOST:
        raise RulesError(f"[{table}] first_day_speed must be a number from 1 to {FIRST_DAY_MOST:g}", file,
                         *toml_position(text, table, "first_day_speed"))
    for key, value in pace.items():
        if key not in PACE_KEYS:
            set_rule(rules, key, value, file, at=toml_position(text, table, key), what=f"[{table}]: ")
    check_rules(rules, file)
    rules.pace, rules.time_scale, rules.first_day_speed = name, float(scale), float(first)
    return rules


def first_day(rules: Rules) -> float:
    """Game seconds of a garden's first day: a day of the sun at the pace's default sun speed (a pace's
    ``first_day_speed`` runs that long of a new garden's life faster)."""
    return 2 * math.pi / rules.sun.speed


def set_rule(rules: Rules, key: str, value, file: str, error: type[LSysError] = RulesError,
             at: tuple[int, int] = (1, 1), what: str = "") -> None:
    """Set the rule ``key`` (``"section.name"``) of ``rules`` to ``value`` after checking it against the
    schema (a known rule, the rule's type, within its range); ``error`` at ``at`` otherwise."""
    rule = find_rule(key, type(rules).SCHEMA)
    if rule is None:
        raise error(f"{what}unknown rule {key!r}", file, *at)
    setattr(getattr(rules, rule.section), rule.name, checked_value(rule, value, file, error, at))


def checked_value(rule: Rule, value, file: str, error: type[LSysError] = RulesError,
                  at: tuple[int, int] = (1, 1)) -> float | bool:
    """``value`` as ``rule``'s type (a whole number is a float) if it lies within the rule's range."""
    named = f"'{rule.name}' in [{rule.section}]"
    if isinstance(rule.default, bool):
        if not isinstance(value, bool):
            raise error(f"{named} must be true or false", file, *at)
        return value
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise error(f"{named} must be a finite number ({rule.unit})", file, *at)
    if not rule.low <= value <= rule.high:
        raise error(f"{named} must be from {rule.low:g} to {rule.high:g} {rule.unit} (it is {value:g})", file, *at)
    return float(value)


def check_rules(rules: Rules, file: str, error: type[LSysError] = RulesError) -> None:
    """Every slider range the right way round (the single rules are checked as they are set)."""
    sun = rules.sun
    if not sun.orbit_height_min <= sun.orbit_height <= sun.orbit_height_max:
        raise error("[sun] orbit_height must lie between orbit_height_min and orbit_height_max", file)
    if not sun.speed_min <= sun.speed <= sun.speed_max:
        raise error("[sun] speed must lie between speed_min and speed_max", file)
    if rules.replant.meter_min > rules.replant.meter_max:
        raise error("[replant] meter_min must not be above meter_max", file)


OVERRIDE_MARKERS = ("<!-- rules-overrides -->\n", "<!-- /rules-overrides -->\n")


def file_overrides(path: str | Path, schema: tuple[Rule, ...] = SCHEMA) -> list[tuple[str, str, object, object]]:
    """What a rules file sets, in its order: ``(table, key, value, default)``, ``table`` "" for the top level
    (the pace played at, default "demo") and ``"paces.NAME"`` for a pace, whose default is the schema's
    default at that pace's time scale (a pace's own ``time_scale`` defaults to 1)."""
    _, data = read_user_toml(path, RulesError)
    found = [("", "pace", data["pace"], "demo")] if "pace" in data else []
    for table, values in data.items():
        if table in SECTIONS:
            found += [(table, k, v, find_rule(f"{table}.{k}", schema).default) for k, v in values.items()]
    for name, pace in data.get("paces", {}).items():
        scale = pace.get("time_scale", 1.0)
        for key, value in pace.items():
            rule = find_rule(key, schema)
            default = 1.0 if rule is None else _paced(rule, scale)
            found.append((f"paces.{name}", key, value, default))
    return found


def _paced(rule: Rule, scale: float) -> float | bool:
    """``rule``'s default at a pace of time scale ``scale``."""
    return {"time": rule.default * scale, "rate": rule.default / scale}.get(rule.scales or "", rule.default)


def restated_defaults(path: str | Path, schema: tuple[Rule, ...] = SCHEMA) -> list[str]:
    """Every entry of a rules file that only repeats its default (``"[table] key = value"``): a rules file
    holds overrides, the defaults live in the schema alone."""
    return [f"{f'[{table}]' if table else '(top)'} {key} = {value!r}"
            for table, key, value, default in file_overrides(path, schema)
            if value == default or (isinstance(value, float) and math.isclose(value, default, rel_tol=1e-9))]


def overrides_markdown(path: str | Path, schema: tuple[Rule, ...] = SCHEMA) -> str:
    """docs/rules.md's table of what ``path`` (assets/rules.toml) changes, each with the default it replaces."""

    def shown(value: object) -> str:
        return f'"{value}"' if isinstance(value, str) else str(value).lower() if isinstance(value, bool) \
            else f"{value:g}"

    lines = ["| table | rule | value | default |", "|---|---|---|---|"]
    lines += [f"| {f'[{table}]' if table else '(top)'} | `{key}` | {shown(value)} | {shown(default)} |"
              for table, key, value, default in file_overrides(path, schema)]
    return "\n".join(lines) + "\n"


def write_rules_doc(doc: str | Path, rules_file: str | Path, schema: tuple[Rule, ...] = SCHEMA) -> None:
    """Rewrite docs/rules.md's two generated tables: every rule of ``schema`` and what ``rules_file`` changes."""
    doc = Path(doc)
    text = doc.read_text(encoding="utf-8")
    for (start, end), table in ((TABLE_MARKERS, rules_table_markdown(schema)),
                                (OVERRIDE_MARKERS, overrides_markdown(rules_file, schema))):
        head, _, rest = text.partition(start)
        text = head + start + table + end + rest.partition(end)[2]
    doc.write_text(text, encoding="utf-8")


def clamp_orbit(sun: SunRules, orbit_height: float, speed: float) -> tuple[float, float]:
    """The sun's two sliders (its orbit's height and its angular speed) kept within the rules' slider ranges
    (the one place they are clamped: a slider, a loaded save, a save being written)."""
    return (min(max(orbit_height, sun.orbit_height_min), sun.orbit_height_max),
            min(max(speed, sun.speed_min), sun.speed_max))


def species_trait(constants: dict[str, float], name: str, key: str, default: float) -> float:
    """A species' own value of the rule ``key`` from its .lsys ``#define name`` (untrusted: a shared save
    carries its source), kept within the rule's range; ``default`` (the rules' value) when it gives none or
    one that is not a number."""
    value = constants.get(name)
    if not isinstance(value, int | float) or not math.isfinite(value):
        return default
    rule = find_rule(key)
    return min(max(float(value), rule.low), rule.high)

