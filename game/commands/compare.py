"""`arbor compare DIR... --out DIR`: a class's sweep folders merged into one table and one figure.

Each DIR is one student's `arbor sweep --out` folder (its sweep.toml, the file the sweep ran, and its
finished tidy.csv). They must have run the same experiment: the same factors and levels, duration,
sampling, responses, conditions, species, pace, seasons and stop conditions; only the seeds (a class may
share its seeds out) and the title may differ. A folder of another experiment is refused by its name, with
the keys that differ. The output is class.csv (every student's tidy rows, a `student` column first: the
folder's name), class.png/svg (every student's runs in one figure) and a line per student saying how many
of their runs are identical to the first folder's (same seed and levels: a run is reproducible, so a
difference means another Arbor, other rules or an edited table).
"""

from __future__ import annotations

import csv
import io
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from arbor.engine.base.errors import LSysError, SweepError
from arbor.engine.base.reader import read_user_text
from arbor.engine.life.experiment.sweep import Sweep, by_run, cell, differences, final_values
from arbor.engine.life.experiment.sweep_file import load_sweep
from arbor.game import report
from arbor.game.commands.sweep_runs import write_atomic
from arbor.game.errors import UserError
from arbor.game.paths import ASSETS

MAX_FOLDERS = 200  # a class or two
TIDY_LIMIT = 256 * 1024 * 1024  # bytes of one student's tidy.csv (a sweep of the largest size writes about 100 MB)


@dataclass
class Student:
    """One student's folder: their name (the folder's), their sweep and their tidy rows."""

    name: str
    folder: Path
    sweep: Sweep
    rows: list[dict[str, str]]


def read_student(folder: Path, name: str) -> Student:
    """A finished sweep folder: its sweep.toml read as a sweep file and its tidy.csv (every row checked to
    have the table's columns and numbers where numbers belong); a problem is one line naming the file."""
    if not folder.is_dir():
        raise UserError(f"{folder}: not a folder (give the --out folders of arbor sweep)")
    stamp, tidy = folder / "sweep.toml", folder / "tidy.csv"
    if not stamp.is_file():
        raise UserError(f"{folder}: no sweep.toml: not a folder arbor sweep wrote")
    if not tidy.is_file():
        raise UserError(f"{folder}: no tidy.csv: the sweep is not finished (run its arbor sweep command again to "
                        "finish it)")
    sweep = load_sweep(stamp, ASSETS / "lsystems")
    text = read_user_text(tidy, TIDY_LIMIT, SweepError)
    reader = csv.DictReader(io.StringIO(text))
    want = ["run", "seed", *(f.name for f in sweep.factors), "time_s", *sweep.responses]
    if reader.fieldnames is None or reader.fieldnames[:len(want)] != want:
        raise SweepError(f"the columns are not those of its sweep.toml ({', '.join(want)})", str(tidy), 1, 1)
    rows = []
    numbers = ["seed", "time_s", *sweep.responses]
    for line, row in enumerate(reader, 2):
        if None in row or None in row.values():
            raise SweepError("a row with another number of cells than the header", str(tidy), line, 1)
        for key in numbers:
            try:
                float(row[key])
            except ValueError:
                raise SweepError(f"{key!r} is not a number: {row[key][:40]!r}", str(tidy), line, 1) from None
        rows.append(row)
    if not rows:
        raise SweepError("no rows", str(tidy), 1, 1)
    return Student(name, folder, sweep, rows)


def check_levels(student: Student) -> None:
    """Every row's factor cells are levels its sweep ran (an edited table could name one it never ran); else
    one line naming the file and the row."""
    levels = {f.name: {cell(level) for level in f.levels} for f in student.sweep.factors}
    for line, row in enumerate(student.rows, 2):
        for name, known in levels.items():
            if row[name] not in known:
                raise UserError(f"{student.folder / 'tidy.csv'}:{line}:1: {name!r} = {row[name][:40]!r} is none of "
                                "the sweep's levels (an edited table?); run the sweep again")


def check_same(students: list[Student]) -> None:
    """Every student ran the first one's experiment; else one line naming each who did not, with the keys."""
    first = students[0]
    other = [(s, differences(first.sweep, s.sweep, seeds=False)) for s in students[1:]]
    other = [(s, keys) for s, keys in other if keys]
    if other:
        named = "; ".join(f"{s.name} ({', '.join(keys)})" for s, keys in other)
        raise UserError(f"{', '.join(s.name for s, _ in other)} ran another experiment than {first.name}: {named} "
                        f"differ{'s' if len(other) == 1 and len(other[0][1]) == 1 else ''}; compare folders of one "
                        "sweep file (only the seeds and the title may differ)")


def _names(folders: list[Path]) -> list[str]:
    """Each folder's student name: its own name, or the path as given when two folders share a name."""
    names = [f.resolve().name or str(f) for f in folders]
    return [str(f) if names.count(n) > 1 else n for f, n in zip(folders, names, strict=True)]


def agreement(reference: Student, student: Student) -> tuple[int, int]:
    """(runs of ``student`` that ``reference`` also ran (same seed and levels), of which identical)."""
    names = [f.name for f in reference.sweep.factors]

    def keyed(s: Student) -> dict[tuple, list[dict]]:
        return {(r[0]["seed"], *(r[0][n] for n in names)): r for r in by_run(s.rows).values()}

    theirs, ours = keyed(reference), keyed(student)
    shared = [k for k in ours if k in theirs]
    same = sum(1 for k in shared if [{c: v for c, v in r.items() if c != "run"} for r in ours[k]]
               == [{c: v for c, v in r.items() if c != "run"} for r in theirs[k]])
    return len(shared), same


def class_csv(students: list[Student]) -> str:
    """Every student's tidy rows in one table, a ``student`` column first."""
    buf = io.StringIO()
    columns = ["student", *students[0].rows[0].keys()]
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(columns)
    for s in students:
        for row in s.rows:
            writer.writerow([s.name, *row.values()])
    return buf.getvalue()


def compare(folders: list[Path], out: Path, plots: bool = True,
            echo: Callable[[str], None] = report.say) -> list[Path]:
    """Merge the sweep ``folders`` into ``out`` (class.csv, and with ``plots`` class.png and class.svg);
    returns the files written. Refuses (UserError) folders of another experiment, by name."""
    if not 2 <= len(folders) <= MAX_FOLDERS:
        raise UserError(f"arbor compare takes 2 to {MAX_FOLDERS} sweep folders (got {len(folders)})")
    seen: dict[Path, Path] = {}
    for folder in folders:  # (one folder twice would count its runs twice in the class's spread)
        if folder.resolve() in seen:
            raise UserError(f"{folder}: given twice (as {seen[folder.resolve()]} too); give each student's folder once")
        seen[folder.resolve()] = folder
    try:
        students = [read_student(f, n) for f, n in zip(folders, _names(folders), strict=True)]
    except LSysError as err:
        raise UserError(str(err)) from None
    check_same(students)
    for student in students:
        check_levels(student)
    if out.exists() and not out.is_dir():
        raise UserError(f"{out}: is a file; give a folder for --out")
    out.mkdir(parents=True, exist_ok=True)
    write_atomic(out / "class.csv", class_csv(students))
    files = [out / "class.csv"]
    for s in students:
        runs = len(by_run(s.rows))
        if s is students[0]:
            echo(f"{s.name}: {runs} runs (the reference)")
            continue
        shared, same = agreement(students[0], s)
        echo(f"{s.name}: {runs} runs; of the {shared} with a seed {students[0].name} ran too, {same} identical to "
             f"{students[0].name}'s" + ("" if same == shared else f", {shared - same} differ"))
    if plots:
        from arbor.game.commands.sweep import day_seconds
        from arbor.game.render.figures import class_figure, save_both

        finals = {s.name: final_values(s.rows, s.sweep) for s in students}
        files += save_both(class_figure(students[0].sweep, finals, day_seconds(students[0].sweep)), out / "class")
    return files

