"""The rule schema: every rule declared once, and the files that set rules checked against it with the
real line and column of the offending key; the docs' table and the figures' units come from it too."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from arbor.engine.base.errors import ExperimentError, LSysError, RulesError, SettingsError, SweepError
from arbor.engine.life.experiment.lab import Lab, load_experiment
from arbor.engine.life.experiment.sweep import Factor
from arbor.engine.life.experiment.sweep_file import load_sweep
from arbor.engine.life.rules.rules import (
    OVERRIDE_MARKERS,
    RATES,
    TIMES,
    Rules,
    clamp_orbit,
    file_overrides,
    load_rules,
    overrides_markdown,
    restated_defaults,
    write_rules_doc,
)
from arbor.engine.life.rules.schema import SCHEMA, TABLE_MARKERS, Rule, rules_table_markdown

ROOT = Path(__file__).resolve().parent.parent
ASSETS = ROOT / "assets"
DEMO = "pace = \"demo\"\n"


def write(tmp_path: Path, text: str, name: str = "rules.toml") -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


REGENERATE = ("python -c \"from arbor.engine.life.rules.rules import write_rules_doc; "
              "write_rules_doc('docs/rules.md', 'assets/rules.toml')\"")


def _between(text: str, markers: tuple[str, str]) -> str:
    start, end = markers
    assert start in text and end in text, f"docs/rules.md lost its markers {markers}"
    return text.partition(start)[2].partition(end)[0]


def test_docs_tables_are_the_schema_and_the_rules_file():
    """docs/rules.md's two tables are made from the schema and from assets/rules.toml: a rule changed in
    either (say the can's fill_rate set in rules.toml) leaves the doc stale and fails here."""
    text = (ROOT / "docs" / "rules.md").read_text(encoding="utf-8")
    assert _between(text, TABLE_MARKERS) == rules_table_markdown(), f"docs/rules.md is out of date: {REGENERATE}"
    assert _between(text, OVERRIDE_MARKERS) == overrides_markdown(ASSETS / "rules.toml"), (
        f"docs/rules.md does not list what assets/rules.toml changes: {REGENERATE}")
    assert REGENERATE.partition("-c ")[2].strip('\\"') in text.replace("`", "")
    assert "(docs/rules.md)" in (ROOT / "README.md").read_text(encoding="utf-8")


def test_the_rules_file_holds_only_overrides():
    """Every default lives in the schema alone: assets/rules.toml repeats none (not even at a pace's scale)."""
    assert restated_defaults(ASSETS / "rules.toml") == [], "rules.toml repeats these defaults: remove them"
    for table, key, value, default in file_overrides(ASSETS / "rules.toml"):
        assert value != default, (table, key)


def test_a_restated_default_is_found(tmp_path):
    fill = next(r for r in SCHEMA if r.key == "water.fill_rate")
    death = next(r for r in SCHEMA if r.key == "health.death_time")
    path = write(tmp_path, f"pace = \"demo\"\n[water]\nfill_rate = {fill.default!r}\ndrain_rate = 0.5\n"
                           f"[paces.slow]\ntime_scale = 10\n\"health.death_time\" = {death.default * 10!r}\n")
    assert restated_defaults(path) == ["(top) pace = 'demo'", f"[water] fill_rate = {fill.default!r}",
                                       f"[paces.slow] health.death_time = {death.default * 10!r}"]
    path.write_text(path.read_text().replace("fill_rate", "fill_rate = 0.3\n#"))
    assert f"[water] fill_rate = {fill.default!r}" not in restated_defaults(path)


def test_the_docs_regenerate(tmp_path):
    doc = tmp_path / "rules.md"
    doc.write_text("intro\n" + "".join(TABLE_MARKERS) + "between\n" + "".join(OVERRIDE_MARKERS) + "end\n")
    rules = write(tmp_path, "pace = \"demo\"\n[sun]\nside = 0.5\n")
    write_rules_doc(doc, rules)
    text = doc.read_text()
    assert text.startswith("intro\n") and "between\n" in text and text.endswith("end\n")
    side = next(r for r in SCHEMA if r.key == "sun.side").default
    assert f"| [sun] | `side` | 0.5 | {side:g} |" in _between(text, OVERRIDE_MARKERS)
    assert _between(text, TABLE_MARKERS) == rules_table_markdown()


def test_a_rule_added_to_the_schema_is_read_checked_scaled_and_documented(tmp_path):
    bloom = Rule("growth.bloom_time", 5.0, 1.0, 9.0, "s", "how long blossoms stay", "time")
    schema = (*SCHEMA, bloom)
    rules = load_rules(write(tmp_path, DEMO), schema=schema)
    assert rules.growth.bloom_time == 5.0  # its default
    assert load_rules(write(tmp_path, DEMO + "[growth]\nbloom_time = 7\n"), schema=schema).growth.bloom_time == 7.0
    home = load_rules(ASSETS / "rules.toml", "home", schema=schema)
    assert home.growth.bloom_time == 5.0 * home.time_scale and home.time_scale > 1  # a time
    with pytest.raises(RulesError, match="'bloom_time' in \\[growth\\] must be from 1 to 9 s") as err:
        load_rules(write(tmp_path, DEMO + "[growth]\nthreshold = 0.5\n  bloom_time = 12\n"), schema=schema)
    assert (err.value.line, err.value.col) == (4, 3)
    with pytest.raises(RulesError, match=r"unknown rule 'growth\.bloom_time'"):
        load_rules(write(tmp_path, DEMO + "[growth]\nbloom_time = 7\n"))  # not in the game's own schema
    row = "| `bloom_time` | 5 | 1 .. 9 | s | how long blossoms stay | x time_scale |"
    assert row in rules_table_markdown(schema) and row not in rules_table_markdown()


@pytest.mark.parametrize("text, words, line, col", [
    (DEMO + "\n[growth]\nthreshold = 0.5\nhold_tme = 3\n", "unknown rule 'growth.hold_tme'", 5, 1),
    (DEMO + "[growth]\nthreshold = 0.5\n\n[sunshine]\nspeed = 1\n", "unknown table [sunshine]", 5, 1),
    (DEMO + "[water]\ndrain_rate = 0.001\ndrown_level = 1.5   # too much\n", "must be from 0 to 1 meter", 4, 1),
    (DEMO + "[sun]\nside = 0.4\n    speed = 'fast'\n", "'speed' in [sun] must be a finite number", 4, 5),
    (DEMO + "[seasons]\nenabled = 1\n", "'enabled' in [seasons] must be true or false", 3, 1),
    ("pace = \"home\"\n[paces.home]\ntime_scale = 10\n\"seasons.year_days\" = 0\n", "from 1 to 1000", 4, 1),
    ("pace = \"home\"\n[paces.home]\n\"replant.meter_min\" = 0.9\n\"replant.meter_max\" = 0.5\n",
     "meter_min must not be above meter_max", 1, 1),
    ("pace = \"home\"\n[paces.home]\ntime_scale = 10\n\"sun.glare\" = 1\n", "[paces.home]: unknown rule", 4, 1),
    ("pace = \"slow\"\n[paces.home]\ntime_scale = 10\n", "unknown pace 'slow'", 1, 1),
    ("pace = \"home\"\n[paces.home]\ntime_scale = 10\nfirst_day_speed = 0.5\n", "first_day_speed must be", 4, 1),
    ("pace = \"home\"\n[paces.home]\nfirst_day_speed = true\n", "from 1 to 1000", 3, 1),
])
def test_bad_rules_files_name_the_key_where_it_is(tmp_path, text, words, line, col):
    path = write(tmp_path, text)
    with pytest.raises(RulesError) as err:
        load_rules(path)
    assert words in err.value.message and err.value.file == str(path)
    assert (err.value.line, err.value.col) == (line, col)


def test_the_schema_is_what_the_rules_and_paces_use():
    assert all(r.low is None or r.low <= r.default <= r.high for r in SCHEMA)
    assert all(getattr(getattr(Rules(), r.section), r.name) == r.default for r in SCHEMA)  # every default, as declared
    assert {r.key for r in SCHEMA} == {f"{s}.{k}" for s, section in vars(Rules()).items()
                                       if not isinstance(section, str | float) for k in vars(section)}
    assert TIMES == ("growth.hold_time", "growth.deadline", "growth.penalty_time", "growth.daylight_memory",
                     "water.drown_time", "water.repair_time", "water.oxygen_time",
                     "health.death_time", "light.interval", "carbon.reserve_time", "carbon.keep_time",
                     "carbon.winter_keep", "carbon.starve_time", "carbon.root_catch_up")
    assert "water.fill_rate" not in RATES and len(RATES) == 15  # the watering can is held for seconds at any pace


LAB = """duration = 60
[[tree]]
name = "a"
rules = {{ {rule} }}
"""


def test_lab_overrides_are_range_checked_like_the_rules_file(tmp_path):
    path = write(tmp_path, LAB.format(rule='"water.drain_rate" = -0.5'), "lab.toml")
    with pytest.raises(ExperimentError, match="'drain_rate' in \\[water\\] must be from 0 to 100"):
        load_experiment(path, ASSETS / "lsystems")
    slow = load_experiment(write(tmp_path, LAB.format(rule='"sun.speed" = 0.9'), "lab.toml"), ASSETS / "lsystems")
    with pytest.raises(ExperimentError, match="speed must lie between speed_min and speed_max"):
        Lab(slow, load_rules(ASSETS / "rules.toml", pace="demo"))


def test_sweep_rule_levels_are_range_checked_and_sweep_files_raise_sweep_errors(tmp_path):
    sweep = """duration = 60
seeds = 2
[[factor]]
key = "seasons.year_days"
levels = [{levels}]
"""
    lsystems = ASSETS / "lsystems"
    assert load_sweep(write(tmp_path, sweep.format(levels="7, 28"), "s.toml"), lsystems).factors[0].levels == (7, 28)
    with pytest.raises(SweepError, match="'year_days' in \\[seasons\\] must be from 1 to 1000"):
        load_sweep(write(tmp_path, sweep.format(levels="7, 0"), "s.toml"), lsystems)
    with pytest.raises(SweepError, match="'duration' must be a number"):  # found by the lab's shared reader
        load_sweep(write(tmp_path, sweep.format(levels="7").replace("duration = 60", "duration = 'x'"), "s.toml"),
                   lsystems)


def test_kiosk_settings_errors_are_settings_errors_with_the_line(tmp_path):
    from arbor.game.screens.kiosk import load_kiosk_config

    with pytest.raises(SettingsError, match="unknown kiosk setting 'pinn'") as err:
        load_kiosk_config(write(tmp_path, "language = \"en\"\npinn = \"1234\"\n", "kiosk.toml"))
    assert err.value.line == 2 and isinstance(err.value, LSysError)
    with pytest.raises(SettingsError, match="4 to 8 digits") as err:
        load_kiosk_config(write(tmp_path, "speed = 10.0\n\npin = \"12\"\n", "kiosk.toml"))
    assert err.value.line == 3


def test_sweep_figures_label_rule_axes_with_the_rules_unit():
    from arbor.game.render.figures import axis_label

    assert axis_label(Factor("Drain", "water.drain_rate", (0.001, 0.01))) == "Drain (meter per s)"
    assert axis_label(Factor("Sun orbit height", "orbit_height", (0.0, 1.0))) == "Sun orbit height (orbit radii)"
    assert axis_label(Factor("Species", "species", ("a.lsys",))) == "Species"


def test_the_sun_sliders_are_clamped_in_one_place():
    """clamp_orbit keeps the orbit height and the sun's speed within their slider ranges; no other code
    clamps them by hand (a slider, a loaded save and a save being written all call it)."""
    sun = Rules().sun
    assert clamp_orbit(sun, sun.orbit_height_max + 1, sun.speed_min / 2) == (sun.orbit_height_max, sun.speed_min)
    assert clamp_orbit(sun, sun.orbit_height_min - 1, sun.speed_max * 2) == (sun.orbit_height_min, sun.speed_max)
    assert clamp_orbit(sun, sun.orbit_height, sun.speed) == (sun.orbit_height, sun.speed)
    by_hand = re.compile(r"min\(max\(.*\b(orbit_height|speed)_(min|max)\b")
    paths = [p for top in ("engine", "game") for p in sorted((ROOT / top).rglob("*.py")) if p.name != "rules.py"]
    found = [f"{path.relative_to(ROOT)}:{n}" for path in paths
             for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1) if by_hand.search(line)]
    assert found == [], f"the sun's sliders clamped by hand (call clamp_orbit): {found}"


def test_no_test_restates_a_rule_value():
    """Tests read a rule's value from the schema or the rules object: a test comparing the rule
    growth.hold_time with a written 20.0 would go on passing after the rule changed, testing nothing."""
    rules = {r.key for r in SCHEMA}
    compared = re.compile(r"\.(\w+)\.(\w+)\s*(==|!=)\s*\(?-?\d")
    found = [f"{path.name}:{n}: {line.strip()}" for path in sorted((ROOT / "tests").glob("*.py"))
             for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1)
             for m in compared.finditer(line.split("#")[0]) if f"{m[1]}.{m[2]}" in rules]
    assert found == [], "rule values written into tests: read them from the schema (find_rule) or the rules"
