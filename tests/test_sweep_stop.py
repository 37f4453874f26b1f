"""Stop conditions of a sweep ([stop]: when the tree dies, when a response crosses a value), recorded in the
tidy table as why and when each run stopped."""

from __future__ import annotations

import csv
import io
from pathlib import Path

import pytest

from arbor.engine.base.errors import SweepError
from arbor.engine.life.experiment.sweep_file import load_sweep
from arbor.game.commands.sweep import run_sweep
from arbor.game.paths import ASSETS

DRY = """title = "Never watered"
duration = 600
sample_every = 100
seeds = [1, 2]
seasons = false
responses = ["height", "alive", "water"]

[base]
watering = "never"

[[factor]]
name = "Drain"
key = "water.drain_rate"
levels = [0.004, 0.02]
"""


def _sweep(tmp_path: Path, text: str, name: str) -> list[dict]:
    path = tmp_path / f"{name}.toml"
    path.write_text(text, encoding="utf-8")
    assert run_sweep(path, tmp_path / name, workers=1, plots=False, echo=lambda _: None) == 0
    return list(csv.DictReader(io.StringIO((tmp_path / name / "tidy.csv").read_text(encoding="utf-8"))))


def _by_run(rows: list[dict]) -> dict[str, list[dict]]:
    runs: dict[str, list[dict]] = {}
    for row in rows:
        runs.setdefault(row["run"], []).append(row)
    return runs


def test_a_run_stops_the_step_its_tree_dies_and_the_table_says_why_and_when(tmp_path):
    full = _by_run(_sweep(tmp_path, DRY, "full"))
    stopped = _by_run(_sweep(tmp_path, DRY + "\n[stop]\ndies = true\n", "stopped"))
    assert "stop" not in next(iter(full.values()))[0]  # (no [stop]: the table as before)
    for name, rows in stopped.items():
        last = rows[-1]
        assert last["stop"] == "died" and last["alive"] == "0"
        assert {r["stop"] for r in rows} == {"died"} and {r["stop_time_s"] for r in rows} == {last["time_s"]}
        when = float(last["stop_time_s"])
        assert 0 < when < 600  # not simulated to the end
        assert all(r["alive"] == "1" for r in rows[:-1])  # it stopped at its death, not later
        before = [{k: v for k, v in r.items() if k not in ("stop", "stop_time_s")} for r in rows[:-1]]
        assert before == full[name][:len(before)]  # stopping changes nothing that came before
        assert float(full[name][-1]["time_s"]) == 600 and full[name][-1]["alive"] == "0"
    drains = {rows[0]["Drain"]: float(rows[-1]["stop_time_s"]) for rows in stopped.values()}
    assert drains["0.02"] < drains["0.004"]  # a faster drain kills sooner


def test_a_run_stops_at_the_sample_a_response_crosses_its_value(tmp_path):
    text = DRY.replace('levels = [0.004, 0.02]', 'levels = [0.004]') + \
        '\n[stop]\nresponse = "water"\nbelow = 0.3\n'
    for rows in _by_run(_sweep(tmp_path, text, "water")).values():
        assert rows[-1]["stop"] == "water <= 0.3" and float(rows[-1]["water"]) <= 0.3
        assert all(float(r["water"]) > 0.3 for r in rows[:-1])
        assert float(rows[-1]["stop_time_s"]) == float(rows[-1]["time_s"]) < 600
    text = text.replace('"water"\nbelow = 0.3', '"height"\nabove = 40')  # never reached before the end
    for rows in _by_run(_sweep(tmp_path, text, "never")).values():
        assert rows[-1]["stop"] == "end" and rows[-1]["stop_time_s"] == "600"


def test_a_run_stopped_early_stays_at_its_last_values_in_the_mean_over_seeds(tmp_path):
    """The time series' mean over seeds: a run that stopped at a crossing is held where it crossed (it was
    left out, so the mean jumped to the runs still going: the fast growers left first)."""
    from arbor.game.commands.sweep import _series

    text = DRY.replace('levels = [0.004, 0.02]', 'levels = [0.004]') + '\n[stop]\nresponse = "water"\nbelow = 0.3\n'
    path = tmp_path / "s.toml"
    path.write_text(text, encoding="utf-8")
    sweep = load_sweep(path, ASSETS / "lsystems")
    rows = [{"run": run, "Drain": "0.004", "time_s": str(t), "water": str(w), "stop": stop}
            for run, samples, stop in (("a", [(0, 0.9), (100, 0.25)], "water <= 0.3"),
                                       ("b", [(0, 0.9), (100, 0.6), (200, 0.5)], "end"))
            for t, w in samples]
    sweep.responses = ("water",)
    times, values = _series(sweep, rows)[("0.004",)]
    assert list(times) == [0, 100, 200] and list(values["water"][0]) == [0.9, 0.25, 0.25]


@pytest.mark.parametrize("table, line, col, words", [
    ("[stop]\ndie = true", 17, 1, "unknown key 'die' in [stop] (did you mean 'dies'?)"),
    ("[stop]\ndies = 1", 17, 8, "'dies' must be true or false"),
    ('[stop]\nresponse = "hieght"\nabove = 2', 17, 12, "unknown response 'hieght' (did you mean 'height'?)"),
    ('[stop]\nresponse = "height"', 17, 1, "needs 'above' or 'below'"),
    ('[stop]\nresponse = "height"\nabove = 2\nbelow = 1', 17, 1, "needs 'above' or 'below' (one of them)"),
    ("[stop]\nabove = 2", 17, 1, "[stop] needs a 'response'"),
    ("[stop]\ndies = false", 16, 1, "[stop] stops nothing"),
])
def test_bad_stop_tables_name_the_problem(tmp_path, table, line, col, words):
    path = tmp_path / "bad.toml"
    path.write_text(DRY + "\n" + table + "\n", encoding="utf-8")
    with pytest.raises(SweepError) as err:
        load_sweep(path, ASSETS / "lsystems")
    assert str(err.value).startswith(f"{path}:{line}:{col}: ") and words in str(err.value), str(err.value)
