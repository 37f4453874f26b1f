"""One strict schema for the files a teacher writes (lab experiments and sweeps), with positions.

Every key of every table is declared once here with its type, range, unit and meaning; a file is read
against it: an unknown key is an error at its line and column with the nearest known key as the fix
("did you mean 'sample_every'?", by difflib), every value is type- and range-checked, and whole numbers
(seeds) must really be whole. tomllib gives no positions, so :class:`Locator` finds a key's line and
column in the text (top-level keys, ``[table]`` and ``[[array]]`` tables, keys of inline tables).

No schema library is used: neither pydantic nor msgspec is installed, and what they would give (types,
ranges) is a few lines here, while positions from the TOML source they cannot give at all.
"""

from __future__ import annotations

import difflib
import math
import re
from dataclasses import dataclass

from arbor.engine.base.errors import LSysError
from arbor.engine.life.rules.schema import SCHEMA as RULE_SCHEMA

_HEADER = re.compile(r"\s*(\[\[?)\s*([^\]]*?)\s*\]\]?\s*(#.*)?$")


@dataclass(frozen=True)
class Key:
    """One key of a table: ``kind`` is number, whole, text, flag, table, tables, list or any; ``low`` and
    ``high`` bound a number (``above``: strictly above ``low``); ``unit`` and ``meaning`` document it."""

    kind: str
    meaning: str
    unit: str = ""
    low: float | None = None
    high: float | None = None
    above: bool = False

    def describe(self) -> str:
        """The range in words, e.g. 'from 0 to 1 meter (0..1)'."""
        unit = f" {self.unit}" if self.unit else ""
        low, high = _num(self.low), _num(self.high)
        if self.low is not None and self.high is not None:
            return f"{'above' if self.above else 'from'} {low} {'and at most' if self.above else 'to'} {high}{unit}"
        return f"above {low}{unit}" if self.low is not None else self.unit


def _num(value: float | None) -> str:
    """A number as a teacher writes it: whole numbers whole (4294967295, not 4.29e+09)."""
    if value is None:
        return ""
    return str(int(value)) if float(value).is_integer() else f"{value:g}"


WEEK = 7 * 24 * 3600.0
SEED_MAX = 2**32 - 1

WATERING = {
    "below": Key("number", "start watering when the water meter falls below this", "meter (0..1)", 0.0, 1.0),
    "until": Key("number", "stop watering when the meter reaches this", "meter (0..1)", 0.0, 1.0),
    "every": Key("number", "or: water on a timetable, this long between waterings", "s", 0.0, WEEK, above=True),
    "seconds": Key("number", "how long each timetable watering lasts", "s", 0.0, 3600.0, above=True),
}
PRUNE = {
    "every_days": Key("number", "prune this often (the first time after this many game days)", "game days",
                      0.0, 365.0, above=True),
    "keep_height": Key("number", "head the tree back: cut every shoot at the first piece of wood above this", "m",
                       0.0, 50.0, above=True),
    "lowest": Key("number", "raise the crown: cut this share of the trunk's branches, the lowest first",
                  "share, 0..1", 0.0, 1.0),
}
SUN = {
    "orbit_height": Key("number", "height of the sun's orbit centre (-1 always night, 1 always day)", "orbit radii",
                        -1.0, 1.0),
    "sun_speed": Key("number", "the sun's angular speed (0.05: a game day of 126 s)", "rad per s", 1e-7, 10.0),
    "day_length": Key("number", "hours of daylight in a game day of 24 game hours (sets orbit_height)", "h",
                      1.0, 23.0),
    "sun_elevation": Key("number", "the sun's elevation at noon (sets sun.side)", "degrees", 15.0, 90.0),
    "latitude": Key("number", "or: a place on Earth, with day_of_year (sets day_length and sun_elevation)",
                    "degrees north", -66.0, 66.0),
    "day_of_year": Key("whole", "the date at that latitude (1 = 1 January, 172 = midsummer in the north)", "day",
                       1, 365),
}
LOWEST_SUN = SUN["sun_elevation"].low  # degrees: the lowest noon sun a file may ask for
TREE = {
    "name": Key("text", "the tree's name in charts, tables and save names (unique)"),
    **SUN,
    "watering": Key("any", "\"never\", or a table { below = 0.5, until = 0.7 } or { every = 120, seconds = 5 }"),
    "prune": Key("table", "a pruning schedule: { every_days = 7, keep_height = 2.5 } and/or { lowest = 0.25 }"),
    "rules": Key("table", "overrides of rules.toml: { \"water.drain_rate\" = 0.01 } (docs/rules.md)"),
}
BASE = {k: v for k, v in TREE.items() if k != "name"}
COMMON = {
    "title": Key("text", "the title of the figures"),
    "duration": Key("duration", "how long the trees grow: s of game time, or a text \"14 days\" or \"30 years\"",
                    "s of game time", 0.0, WEEK, above=True),
    "sample_every": Key("duration", "time between two samples: s of game time, or a text \"1 day\"",
                        "s of game time", 0.0, WEEK, above=True),
    "species": Key("text", "the .lsys file in assets/lsystems the trees grow from"),
    "pace": Key("text", "the pace of rules.toml the rules are read at (demo or home)"),
    "seasons": Key("flag", "false: an endless summer"),
}
EXPERIMENT = {
    **COMMON,
    "seed": Key("whole", "the seed every tree starts from", "", 0, SEED_MAX),
    "lsystem": Key("text", "old name of 'species'"),
    "spacing": Key("number", "trees share one plot this far apart in a row and shade each other (competition)",
                   "m", 0.0, 50.0, above=True),
    "tree": Key("tables", "one [[tree]] table per tree"),
}
STOP = {
    "dies": Key("flag", "true: a run stops when its tree dies (the rest is not simulated)"),
    "response": Key("text", "a run stops when this response (docs/columns.md) crosses 'above' or 'below'"),
    "above": Key("number", "stop when the response reaches this or more (checked at each sample)",
                 "the response's unit"),
    "below": Key("number", "stop when the response falls to this or less (checked at each sample)",
                 "the response's unit"),
}
SWEEP = {
    **COMMON,
    "seeds": Key("any", "how many seeds (1..N) or a list of seeds"),
    "responses": Key("list", "what to record (docs/columns.md lists them)"),
    "base": Key("table", "what every run shares: like a lab [[tree]] without a name"),
    "factor": Key("tables", "one [[factor]] table per factor (1 or 2)"),
    "stop": Key("table", "when a run stops early: { dies = true } and/or { response = \"height\", above = 2.5 }"),
}
FACTOR = {
    "name": Key("text", "the factor's name in the tables and on the figures' axes"),
    "key": Key("text", "what it varies: a sun or watering key, species, or a \"section.key\" of rules.toml"),
    "levels": Key("list", "the values it takes"),
}
FACTOR_KEYS = {**SUN, "watering.every": WATERING["every"], "watering.below": WATERING["below"],
               **{f"prune.{key}": spec for key, spec in PRUNE.items()}}


class Locator:
    """Finds where a key is written in a TOML text, so an error can name its line and column."""

    def __init__(self, text: str) -> None:
        self.lines = text.splitlines()
        self.headers: list[tuple[int, str, bool]] = []  # (0-based line, table name, is an [[array]])
        for number, line in enumerate(self.lines):
            match = _HEADER.match(line)
            if match:
                self.headers.append((number, re.sub(r"[\s\"']", "", match.group(2)), match.group(1) == "[["))

    def _section(self, path: tuple) -> tuple[int, int, int, tuple]:
        """(first line, end line, the header's line or -1, the keys left) of the table ``path`` starts in."""
        ends = [h[0] for h in self.headers] + [len(self.lines)]
        if path and isinstance(path[0], str):
            name, rest = path[0], path[1:]
            index = rest[0] if rest and isinstance(rest[0], int) else 0
            if rest and isinstance(rest[0], int):
                rest = rest[1:]
            found = [k for k, h in enumerate(self.headers) if h[1] == name]
            if len(found) > index:
                k = found[index]
                end = next((ends[j] for j in range(k + 1, len(self.headers))
                            if not self.headers[j][1].startswith(name + ".")), len(self.lines))
                if rest and isinstance(rest[0], str):
                    sub = [j for j in range(k + 1, len(self.headers)) if self.headers[j][0] < end
                           and self.headers[j][1] == f"{name}.{rest[0]}"]
                    if sub:
                        return self.headers[sub[0]][0] + 1, ends[sub[0] + 1], self.headers[sub[0]][0], rest[1:]
                return self.headers[k][0] + 1, ends[k + 1], self.headers[k][0], rest
        return 0, ends[0], -1, path

    def find(self, path: tuple) -> tuple[int, int]:
        """1-based (line, column) of the key at ``path`` (e.g. ("tree", 1, "watering", "below")): the key
        itself, else the nearest enclosing key or table header, else (1, 1)."""
        first, end, header, keys = self._section(path)
        keys = [k for k in keys if isinstance(k, str)]
        where = (header + 1, self.lines[header].index("[") + 1) if header >= 0 else (1, 1)
        if not keys:
            return where
        for number in range(first, end):
            match = re.match(rf"\s*([\"']?){re.escape(keys[0])}\1\s*[=.]", self.lines[number])
            if match:
                col = len(self.lines[number]) - len(self.lines[number].lstrip())
                where = (number + 1, col + 1)
                for key in keys[1:]:
                    found = _inline(self.lines, number, end, col, key)
                    if found is None:
                        break
                    where = found
                    number, col = found[0] - 1, found[1] - 1
                return where
        return where


    def value(self, path: tuple, item: int | None = None) -> tuple[int, int]:
        """1-based (line, column) of the value of the key at ``path`` (where a wrong value is to be fixed,
        not its key), of its ``item``-th element when it is a list; the key's place when the value is not
        found after it."""
        line, col = self.find(path)
        keys = [k for k in path if isinstance(k, str)]
        if not keys or line > len(self.lines):
            return line, col
        text = self.lines[line - 1]
        match = re.compile(rf"\s*([\"']?){re.escape(keys[-1])}\1\s*=[ \t]*").match(text, col - 1)
        if match is None or match.end() >= len(text):
            return line, col
        start = match.end()
        if item is not None and text[start] == "[":
            found = _element(text, start, item)
            if found is not None:
                return line, found + 1
        return line, start + 1


DURATION_TEXT = re.compile(r"\s*(\d+(?:\.\d*)?|\.\d+)\s*(days?|years?)\s*")


def _element(text: str, start: int, item: int) -> int | None:
    """The index in ``text`` where element ``item`` of the list opening at ``start`` begins (the list on one
    line; strings and nested lists skipped), or None."""
    depth, index, quote = 0, 0, ""
    for k in range(start, len(text)):
        c = text[k]
        if quote:
            quote = "" if c == quote and text[k - 1] != "\\" else quote
            continue
        if depth == 1 and index == item and not c.isspace() and c not in ",]#":
            return k
        if c in "\"'":
            quote = c
        elif c in "[{":
            depth += 1
        elif c in "]}":
            depth -= 1
            if depth == 0:
                return None
        elif c == "," and depth == 1:
            index += 1
        elif c == "#":
            return None
    return None


def _inline(lines: list[str], number: int, end: int, col: int, key: str) -> tuple[int, int] | None:
    """The position of ``key`` inside an inline table starting at line ``number``, column ``col``."""
    pattern = re.compile(rf"([{{,.\s])([\"']?){re.escape(key)}\2\s*=")
    for n in range(number, min(end, number + 20)):
        match = pattern.search(lines[n], col if n == number else 0)
        if match:
            return n + 1, match.start(2) + 1
    return None


class Reader:
    """Checks the tables of one file against their keys; every problem is ``error`` at the key's place."""

    def __init__(self, file: str, text: str, error: type[LSysError]) -> None:
        self.file, self.error, self.locator = file, error, Locator(text)
        self.notes: list[str] = []
        self.calendar: tuple[float, float] | None = None  # (s of game time a game day, game days a year)

    def fail(self, message: str, path: tuple, value: bool = False, item: int | None = None) -> LSysError:
        """The error for ``message`` at the key ``path`` (with ``value``: at its value, the ``item``-th
        element of a list value, where the fix is to be typed)."""
        where = self.locator.value(path, item) if value or item is not None else self.locator.find(path)
        return self.error(message, self.file, *where)

    def table(self, data, keys: dict[str, Key], path: tuple, what: str) -> dict:
        """``data`` as a table whose every key is one of ``keys`` (an unknown key: the nearest known one)."""
        if not isinstance(data, dict):
            raise self.fail(f"{what} must be a table", path)
        for key in data:
            if key not in keys:
                close = difflib.get_close_matches(key, list(keys), n=1, cutoff=0.6)
                fix = f"did you mean {close[0]!r}?" if close else f"known keys: {', '.join(keys)}"
                raise self.fail(f"unknown key {key!r} in {what} ({fix})", (*path, key))
        return data

    def known(self, name: str, known: list[str], what: str, path: tuple, otherwise: str,
              item: int | None = None, value: bool = True) -> None:
        """``name`` is one of ``known``; else an error at the value of ``path`` (its ``item``-th element; at the
        key itself when not ``value``: a name given as a key) with the nearest one as the fix (``otherwise``
        when none is near)."""
        if name in known:
            return
        close = difflib.get_close_matches(name, known, n=1, cutoff=0.75)  # (not a near miss: no guess)
        raise self.fail(f"unknown {what} {name!r} ({f'did you mean {close[0]!r}?' if close else otherwise})", path,
                        value=value, item=item)

    def rule(self, key: str, path: tuple, also: tuple[str, ...] = (), what: str = "rule", value: bool = False) -> None:
        """``key`` is a rule of rules.toml ("section.name") or one of ``also``; else an error at ``path`` (its
        value with ``value``: a rule named as a value) with the nearest known key as the fix."""
        otherwise = f"use {', '.join(also)} or a rule of docs/rules.md" if also else "docs/rules.md lists every rule"
        self.known(key, [*also, *(r.key for r in RULE_SCHEMA)], what, path, otherwise, value=value)

    def value(self, data: dict, key: str, spec: Key, path: tuple, default=None):
        """``data[key]`` checked against ``spec`` (``default`` when missing; missing and no default: an error)."""
        if key not in data:
            if default is None:
                raise self.fail(f"{key!r} is missing: {spec.meaning}", path)
            return default
        return self.check(data[key], key, spec, (*path, key))

    def check(self, value, key: str, spec: Key, path: tuple, item: int | None = None):
        """One value (the ``item``-th element of a list) against its key's type and range; an error points
        at the value."""
        if spec.kind in ("number", "whole"):
            return self._number(value, key, spec, path, item)
        if spec.kind == "duration":
            return self._number(self._seconds(value, key, path), key, spec, path, item)
        kinds = {"text": str, "flag": bool, "table": dict, "tables": list, "list": list}
        want = kinds.get(spec.kind)
        if want is not None and not isinstance(value, want):
            words = {"text": "a text in quotes", "flag": "true or false", "table": "a table",
                     "tables": f"[[{key}]] tables", "list": "a list [...]"}
            raise self.fail(f"{key!r} must be {words[spec.kind]}", path, value=True, item=item)
        return value

    def _seconds(self, value, key: str, path: tuple):
        """A duration's value in s of game time: a number as it is, a text "N days" or "N years" by the
        file's calendar (game days: turns of the sun at its speed; a year: seasons.year_days of them)."""
        if not isinstance(value, str):
            return value
        match = DURATION_TEXT.fullmatch(value)
        if match is None:
            raise self.fail(f"{key!r} must be a number of s of game time, or a text such as \"14 days\" or "
                            f"\"30 years\" (not {value[:40]!r})", path, value=True)
        if self.calendar is None:
            raise self.fail(f"{key!r} in days or years needs one game day for every tree (their suns turn at "
                            "different speeds here): give it in s of game time", path, value=True)
        day, year_days = self.calendar
        return float(match.group(1)) * day * (year_days if match.group(2).startswith("year") else 1.0)

    def _number(self, value, key: str, spec: Key, path: tuple, item: int | None) -> float | int:
        if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
            unit = f" ({spec.unit})" if spec.unit else ""
            raise self.fail(f"{key!r} must be a number{unit}, not {value!r}", path, value=True, item=item)
        if spec.kind == "whole" and isinstance(value, float):  # (2.0 too: a seed is written whole)
            raise self.fail(f"{key!r} must be a whole number, not {value!r}", path, value=True, item=item)
        low, high = spec.low, spec.high
        if (low is not None and (value <= low if spec.above else value < low)) or (high is not None and value > high):
            raise self.fail(f"{key!r} must be {spec.describe()} (it is {_num(value)})", path, value=True, item=item)
        return int(value) if spec.kind == "whole" else float(value)


def day_length_height(hours: float) -> float:
    """The orbit height whose sun is up ``hours`` of a game day's 24 hours (the sun's height on its orbit is
    orbit_height + sin(angle), so it is up a share 1/2 + asin(orbit_height)/pi of the day)."""
    return math.sin(math.pi * (hours / 24.0 - 0.5))


def latitude_sun(latitude: float, day_of_year: float) -> tuple[float, float]:
    """(hours of daylight, noon elevation in degrees) at ``latitude`` (degrees north) on ``day_of_year``:
    the sun's declination -23.44 deg x cos(2 pi (day + 10) / 365), the noon elevation 90 - |latitude -
    declination|, the day 2 acos(-tan(latitude) tan(declination)) / 15 deg hours long (Cooper's formula
    and the sunrise equation, the sun as a point, no refraction)."""
    declination = -23.44 * math.cos(2 * math.pi * (day_of_year + 10) / 365)
    lat, dec = math.radians(latitude), math.radians(declination)
    cos_hour = max(-1.0, min(1.0, -math.tan(lat) * math.tan(dec)))
    return 2 * math.degrees(math.acos(cos_hour)) / 15.0, 90.0 - abs(latitude - declination)


def elevation_side(degrees: float, orbit_height: float) -> float:
    """The sun's sideways offset (rule sun.side) that puts the noon sun ``degrees`` above the horizon on an
    orbit of this height (at noon the sun stands at (0, orbit_height + 1, side))."""
    return (orbit_height + 1.0) / math.tan(math.radians(degrees)) if degrees < 90 else 0.0
