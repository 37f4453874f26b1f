"""arbor worksheet: a printable sheet for each lesson (question, prediction box, setup from the lesson's file,
an empty chart with the right axes and units, discussion, and an answer key drawn from a real run)."""

from __future__ import annotations

import csv
import io
import re

import numpy as np
import pytest

from arbor.game.commands.worksheet import lessons, load_sheet, make_worksheet
from arbor.game.errors import UserError
from tests.conftest import ROOT


def _words(text: str) -> str:
    return " ".join(text.split())


def test_every_lesson_has_a_worksheet_whose_question_is_the_guides():
    assert lessons() == ["competition", "light", "pruning", "water"]
    guide = _words((ROOT / "docs" / "teaching.md").read_text(encoding="utf-8"))
    for name in lessons():
        sheet = load_sheet(name)
        assert sheet.lesson.is_file() and f"**Question.** {sheet.question}" in guide, name
        assert sheet.response in sheet.key and len(sheet.discuss) >= 2


def test_a_sweep_lessons_sheet_has_every_part_and_a_key_from_its_run(tmp_path):
    out = tmp_path / "light.html"
    said = []
    assert make_worksheet("light", out, seeds=1, workers=1, duration=300.0, echo=said.append) == [out]
    page = out.read_text(encoding="utf-8")
    sheet = load_sheet("light")
    for words in (sheet.question, sheet.predict, *sheet.discuss):
        assert _words(words).replace("'", "&#x27;") in _words(page)
    assert page.count("class='box'") == 1 and page.count("<svg") == 2  # the prediction box; the empty and the key
    empty, key = page.split("<svg")[1:]
    assert "Day length (h)" in empty and ">kg<" in empty and "<path" in empty  # the axes, with units
    assert "mean over the seeds" not in empty and "mean over the seeds" in key  # no answer on the sheet's chart
    assert "What changes: Day length (h), at 6, 10, 14, 18." in page and "grows 8 seeds" in page
    assert "1 seed (the lesson&#x27;s file has 8)" in page and "shortened" in page
    rows = list(csv.DictReader(io.StringIO((tmp_path / "light_runs" / "tidy.csv").read_text(encoding="utf-8"))))
    last = {r["Day length"]: float(r["biomass"]) for r in rows}  # (rows in time order: the last sample wins)
    cells = re.findall(r"<tr><td>([^<]+)</td><td>([^<]+)</td>", page)
    assert [c[0] for c in cells] == ["6 h", "10 h", "14 h", "18 h"]
    for (_, biomass), want in zip(cells, ("6", "10", "14", "18"), strict=True):
        assert float(biomass) == pytest.approx(last[want], rel=5e-3)  # the key is the run's numbers
    make_worksheet("light", out, seeds=1, workers=1, duration=300.0, echo=said.append)
    assert any("4 runs, 4 already done" in line for line in said[-3:])  # a second sheet reuses the kept runs
    with pytest.raises(UserError, match="light_runs holds the runs of another answer key"):
        make_worksheet("light", out, seeds=2, workers=1, duration=300.0, echo=said.append)


def test_a_lab_lessons_sheet_is_three_pdf_pages_with_the_trees_numbers(tmp_path):
    from arbor.engine.life.experiment.lab import Lab, load_experiment
    from arbor.engine.life.rules.rules import load_rules
    from arbor.game.commands import worksheet
    from arbor.game.paths import ASSETS

    out = tmp_path / "competition.pdf"
    assert make_worksheet("competition", out, duration=250.0) == [out]
    data = out.read_bytes()
    assert data.startswith(b"%PDF") and len(re.findall(rb"/Type /Page\b", data)) == 3
    captured = {}
    real = worksheet.__dict__["lab_answer"]

    def keep(sheet, lab, day):
        captured["answer"] = real(sheet, lab, day)
        return captured["answer"]

    worksheet.lab_answer = keep
    try:
        make_worksheet("competition", tmp_path / "c.html", duration=250.0)
    finally:
        worksheet.lab_answer = real
    experiment = load_experiment(load_sheet("competition").lesson, ASSETS / "lsystems")
    experiment.duration = 250.0
    lab = Lab(experiment, load_rules(ASSETS / "rules.toml", experiment.pace))
    lab.run()
    answer = captured["answer"]
    assert [row[0] for row in answer.rows] == ["West", "Middle", "East"]
    light = [float(row[1]) for row in answer.rows]
    assert np.allclose(light, [s.values["light_day"][-1] for s in lab.series], rtol=5e-3)
    lowest = ["West", "Middle", "East"][int(np.argmin(light))]
    assert answer.sentences[0].startswith(f"Light intercepted a day on the last day: lowest for {lowest}")


def test_wrong_lessons_and_formats_are_one_line(tmp_path):
    with pytest.raises(UserError, match="no worksheet 'trees': the lessons with one are competition, light, "
                                        "pruning, water"):
        make_worksheet("trees", tmp_path / "x.html")
    with pytest.raises(UserError, match=r"use --out NAME\.html or NAME\.pdf"):
        make_worksheet("light", tmp_path / "x.docx")
