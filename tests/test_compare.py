"""arbor compare: three students' sweep folders merged into one tidy table and one figure; a folder of
another experiment refused by name; a run that differs from the reference's found."""

from __future__ import annotations

import csv
import io
import shutil
from pathlib import Path

import pytest

from arbor.game.commands.compare import compare
from arbor.game.commands.sweep import run_sweep
from arbor.game.errors import UserError

SWEEP = """title = "Class sun"
duration = 200
sample_every = 100
seeds = SEEDS
seasons = false
responses = ["height", "leaves", "alive"]

[base]
watering = { below = 0.5, until = 0.7 }

[[factor]]
name = "Sun orbit height"
key = "orbit_height"
levels = [-0.4, 1.0]
"""
CLASS = {"alice": "[1, 2]", "bob": "[2, 3]", "carol": "[1, 4]"}  # the class shares its seeds out


@pytest.fixture(scope="module")
def folders(tmp_path_factory) -> dict[str, Path]:
    root = tmp_path_factory.mktemp("class")
    out = {}
    for name, seeds in CLASS.items():
        path = root / f"{name}.toml"
        path.write_text(SWEEP.replace("SEEDS", seeds), encoding="utf-8")
        assert run_sweep(path, root / name, workers=1, plots=False, echo=lambda _: None) == 0
        out[name] = root / name
    return out


def _rows(path: Path) -> list[dict]:
    return list(csv.DictReader(io.StringIO(path.read_text(encoding="utf-8"))))


def test_three_students_merge_into_one_table_and_one_figure(folders, tmp_path):
    import matplotlib.image as mpimg

    said = []
    files = compare(list(folders.values()), tmp_path / "class", echo=said.append)
    assert [f.name for f in files] == ["class.csv", "class.png", "class.svg"]
    merged = _rows(tmp_path / "class" / "class.csv")
    assert list(merged[0]) == ["student", "run", "seed", "Sun orbit height", "time_s", "height", "leaves", "alive"]
    for name, folder in folders.items():
        own = _rows(folder / "tidy.csv")
        assert [{k: v for k, v in r.items() if k != "student"} for r in merged if r["student"] == name] == own
    assert len(merged) == 3 * 2 * 2 * 3  # students x levels x seeds x samples
    assert said == ["alice: 4 runs (the reference)",
                    "bob: 4 runs; of the 2 with a seed alice ran too, 2 identical to alice's",
                    "carol: 4 runs; of the 2 with a seed alice ran too, 2 identical to alice's"]
    svg = (tmp_path / "class" / "class.svg").read_text(encoding="utf-8")
    assert all(name in svg for name in folders) and "3 students" in svg
    img = mpimg.imread(tmp_path / "class" / "class.png")[..., :3]
    assert img.shape[1] > 600 and img.std() > 0.05


def _copy(folders, tmp_path, name: str, change: tuple[str, str]) -> Path:
    folder = tmp_path / name
    shutil.copytree(folders["alice"], folder)
    stamp = folder / "sweep.toml"
    assert change[0] in stamp.read_text(encoding="utf-8")
    stamp.write_text(stamp.read_text(encoding="utf-8").replace(*change), encoding="utf-8")
    return folder


def test_folders_of_another_experiment_are_refused_by_name(folders, tmp_path):
    dave = _copy(folders, tmp_path, "dave", ("duration = 200", "duration = 300"))
    erin = _copy(folders, tmp_path, "erin", ("levels = [-0.4, 1.0]", "levels = [-0.4, 0.5]"))
    with pytest.raises(UserError) as err:
        compare([folders["alice"], folders["bob"], dave, erin], tmp_path / "class")
    assert str(err.value).startswith("dave, erin ran another experiment than alice: dave (duration); erin (factor)")
    assert "bob" not in str(err.value) and not (tmp_path / "class").exists()


def test_the_command_refuses_in_one_line(folders, tmp_path, capsys):
    from arbor.game.cli import main

    dave = _copy(folders, tmp_path, "dave", ("seasons = false", "seasons = true"))
    assert main(["compare", str(folders["alice"]), str(dave), "--out", str(tmp_path / "c"), "--no-plots"]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "dave ran another experiment than alice: dave (seasons)" in err
    assert main(["compare", str(folders["alice"]), str(folders["bob"]), "--out", str(tmp_path / "c"), "-q",
                 "--no-plots"]) == 0
    assert (tmp_path / "c" / "class.csv").is_file() and not (tmp_path / "c" / "class.png").exists()


def test_a_run_that_differs_from_the_references_is_found(folders, tmp_path):
    frank = tmp_path / "frank"
    shutil.copytree(folders["bob"], frank)
    tidy = frank / "tidy.csv"
    lines = tidy.read_text(encoding="utf-8").splitlines()
    seed2 = next(k for k, line in enumerate(lines) if line.split(",")[1] == "2")
    cells = lines[seed2].split(",")
    cells[5] = "0.123"  # seed 2's height, as another Arbor (or an edited table) would give
    lines[seed2] = ",".join(cells)
    tidy.write_text("\n".join(lines) + "\n", encoding="utf-8")
    said = []
    compare([folders["alice"], frank], tmp_path / "class", plots=False, echo=said.append)
    assert said[1] == "frank: 4 runs; of the 2 with a seed alice ran too, 1 identical to alice's, 1 differ"


def _edited_level(text: str) -> str:
    """The tidy table with its first row's first factor cell changed to a level the sweep never ran."""
    lines = text.splitlines()
    cells = lines[1].split(",")
    cells[2] = "0.777"
    return "\n".join([lines[0], ",".join(cells), *lines[2:]]) + "\n"


def test_one_folder_given_twice_is_refused(folders, tmp_path):
    with pytest.raises(UserError, match="given twice"):
        compare([folders["alice"], folders["bob"], folders["alice"]], tmp_path / "class", plots=False)


@pytest.mark.parametrize("damage, words", [
    (lambda f: (f / "tidy.csv").unlink(), "no tidy.csv: the sweep is not finished"),
    (lambda f: (f / "sweep.toml").unlink(), "no sweep.toml"),
    (lambda f: (f / "tidy.csv").write_text("run,seed\nrun00000,1\n"), "tidy.csv:1:1: the columns are not"),
    (lambda f: (f / "tidy.csv").write_text((f / "tidy.csv").read_text().replace(",1,", ",one,", 1)),
     "tidy.csv:2:1: 'seed' is not a number"),
    (lambda f: (f / "tidy.csv").write_text(_edited_level((f / "tidy.csv").read_text())),
     "tidy.csv:2:1: .* is none of the sweep's levels"),
])
def test_a_broken_folder_is_one_line_naming_it(folders, tmp_path, damage, words):
    broken = tmp_path / "gina"
    shutil.copytree(folders["alice"], broken)
    damage(broken)
    with pytest.raises(UserError, match=words):
        compare([folders["alice"], broken], tmp_path / "class", plots=False)
