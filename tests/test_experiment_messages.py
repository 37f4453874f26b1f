"""Messages a teacher gets from a bad file or a stopped sweep (issue 49): a duplicate factor is named, an
unknown species lists the species there are, a missing closing quote is named at its opening quote, a bad
value's column is the value's (not its key's), and a stopped sweep says how to resume."""

from __future__ import annotations

import pytest

from arbor.engine.base.errors import ExperimentError, SweepError
from arbor.engine.life.experiment.lab import load_experiment
from arbor.engine.life.experiment.sweep_file import load_sweep
from arbor.game.paths import ASSETS

LSYS = ASSETS / "lsystems"
SWEEP = """title = "Sun"
duration = 100
sample_every = 50
seeds = [1, 2]
seasons = false
responses = ["height"]

[[factor]]
name = "Sun"
key = "orbit_height"
levels = [0.0, 1.0]

[[factor]]
name = "Drain"
key = "water.drain_rate"
levels = [0.004, 0.01]
"""
LAB = """title = "Two trees"
seed = 5
duration = 300

[[tree]]
name = "Watered"
orbit_height = 0.6
"""


def _sweep_error(tmp_path, text: str) -> str:
    path = tmp_path / "bad.toml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(SweepError) as err:
        load_sweep(path, LSYS)
    assert "\n" not in str(err.value)
    return str(err.value).removeprefix(f"{path}:")


def _lab_error(tmp_path, text: str) -> str:
    path = tmp_path / "bad_lab.toml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(ExperimentError) as err:
        load_experiment(path, LSYS)
    return str(err.value).removeprefix(f"{path}:")


def test_a_duplicate_factor_name_is_named_at_the_second_name(tmp_path):
    said = _sweep_error(tmp_path, SWEEP.replace('name = "Drain"', 'name = "Sun"'))
    assert said == "14:8: two factors are named 'Sun': give each factor a name of its own"
    said = _sweep_error(tmp_path, SWEEP.replace('name = "Drain"', 'name = "seed"'))
    assert said.startswith("14:8: a factor cannot be named 'seed'")
    said = _sweep_error(tmp_path, SWEEP.replace('"water.drain_rate"', '"orbit_height"'))
    assert said.startswith("15:7: two factors vary 'orbit_height'")


def test_an_unknown_species_lists_the_species_there_are(tmp_path):
    there = sorted(p.name for p in LSYS.glob("*.lsys"))
    assert "game_tree.lsys" in there and "game_poplar.lsys" in there
    for said in (_sweep_error(tmp_path, 'species = "oak.lsys"\n' + SWEEP),
                 _lab_error(tmp_path, 'species = "oak.lsys"\n' + LAB)):
        assert said == f"1:11: no species 'oak.lsys' in assets/lsystems (the species are: {', '.join(there)})"
    said = _sweep_error(tmp_path, SWEEP.replace('"orbit_height"', '"species"').replace(
        "[0.0, 1.0]", '["game_tree.lsys", "game_popla.lsys"]'))
    assert said.startswith("11:29: no species 'game_popla.lsys' in assets/lsystems (did you mean "
                           "'game_poplar.lsys'? the species are: ")


@pytest.mark.parametrize("old, new, where, quote", [
    ('title = "Sun"', 'title = "Sun', "1:9", '"'),
    ('responses = ["height"]', 'responses = ["height]', "6:14", '"'),
    ('name = "Drain"', "name = 'Drain # a comment", "14:8", "'"),
    ('title = "Sun"', 'title = "Sun \\" still open', "1:9", '"'),
])
def test_a_missing_closing_quote_is_named_at_its_opening_quote(tmp_path, old, new, where, quote):
    said = _sweep_error(tmp_path, SWEEP.replace(old, new))
    col = where.split(":")[1]
    assert said == f"{where}: the text opened with {quote} at column {col} is not closed: end it with {quote} on " \
        "the same line"
    assert "Illegal character" not in _lab_error(tmp_path, LAB.replace('name = "Watered"', 'name = "Watered'))


def test_other_toml_mistakes_are_still_the_readers_own_line(tmp_path):
    said = _sweep_error(tmp_path, SWEEP.replace("seeds = [1, 2]", "seeds = [1, 2"))
    assert "not valid TOML" in said and "not closed" not in said


@pytest.mark.parametrize("old, new, bad", [
    ("levels = [0.0, 1.0]", "levels = [0.0, 5]", "5]"),
    ("levels = [0.004, 0.01]", "levels = [0.004,   -0.01]", "-0.01]"),
    ("seeds = [1, 2]", "seeds = [1, 2, 2]", "2]"),
    ("seeds = [1, 2]", "seeds =    [1, 2.5]", "2.5]"),
    ("levels = [0.0, 1.0]", "levels = [0.0, 1.0, 0.0]", "0.0]"),
    ('responses = ["height"]', 'responses = ["height", "beauty"]', '"beauty"]'),
    ("duration = 100", "duration = -5", "-5"),
    ('key = "water.drain_rate"', 'key =  "water.drain_rat"', '"water.drain_rat"'),
])
def test_the_column_points_at_the_bad_value_not_its_key(tmp_path, old, new, bad):
    text = SWEEP.replace(old, new)
    said = _sweep_error(tmp_path, text)
    line, col = (int(v) for v in said.split(":")[:2])
    assert text.splitlines()[line - 1][col - 1:] == bad, said


def test_a_sweep_stopped_at_any_moment_says_how_to_resume(tmp_path, monkeypatch):
    from arbor.game.commands import sweep as command

    path = tmp_path / "s.toml"
    path.write_text(SWEEP.replace("levels = [0.004, 0.01]", "levels = [0.004]").replace("[1, 2]", "[1]"),
                    encoding="utf-8")

    def interrupted(*args, **kw):
        raise KeyboardInterrupt

    monkeypatch.setattr(command, "write_outputs", interrupted)  # Ctrl-C after the runs, while writing tables
    said: list[str] = []
    assert command.run_sweep(path, tmp_path / "out", workers=1, plots=False, echo=said.append) == 130
    assert said[-1] == f"stopped: 2 finished run(s) kept in {tmp_path / 'out' / 'runs'}; run the same command " \
        "to resume"
    monkeypatch.undo()
    said.clear()
    assert command.run_sweep(path, tmp_path / "out", workers=1, plots=False, echo=said.append) == 0
    assert "2 already done" in said[0] and (tmp_path / "out" / "tidy.csv").is_file()


def test_a_lab_duration_in_game_days_needs_one_day_for_all_its_trees(tmp_path):
    """A lab's "3 days" is three turns of its trees' sun; trees whose suns turn at other speeds have no one
    game day, so only seconds are taken (one line at the value says what is)."""
    import math

    text = ('title = "Days"\nduration = "3 days"\nsample_every = 30\n'
            '[[tree]]\nname = "a"\n{0}\n[[tree]]\nname = "b"\n')
    path = tmp_path / "days.toml"
    path.write_text(text.format("sun_speed = 0.1"), encoding="utf-8")
    with pytest.raises(ExperimentError, match="'duration' in days or years needs one game day") as caught:
        load_experiment(path, ASSETS / "lsystems")
    assert (caught.value.line, caught.value.col) == (2, 12)
    path.write_text(text.format(""), encoding="utf-8")
    experiment = load_experiment(path, ASSETS / "lsystems")
    from arbor.engine.life.rules.rules import load_rules

    assert experiment.duration == pytest.approx(3 * 2 * math.pi / load_rules(ASSETS / "rules.toml", "demo").sun.speed)
