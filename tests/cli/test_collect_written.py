"""``puma-course collect-written``: what it says is what it wrote (tests/grading/test_written.py has the rest)."""

from __future__ import annotations

import csv

import pytest

from puma_course.cli import main
from puma_course.grading.output.marks import read_marks
from puma_course.grading.written import written_questions
from tests.cli.support import hand_in_written
from tests.support import ROOT

EX = "ex02_dh_frames"
(W,) = written_questions(EX)


def test_collect_written_says_the_rows_it_wrote_and_how_many_were_answered(tmp_path, capsys):
    subs = tmp_path / "subs"
    hand_in_written(subs / "ann", EX, True, "$z_1$ up the column.")
    hand_in_written(subs / "bob", EX, False, "The origin of {1} is where the axes cross.")
    hand_in_written(subs / "cy", EX, True, None)  # blank: listed, to be marked 0 or left
    out = tmp_path / "marking"
    assert main(["collect-written", str(subs), "-o", str(out), "--course", str(ROOT)]) == 0
    said = capsys.readouterr().out
    sheet = out / f"{EX}-{W.qid}-marks.csv"
    with open(sheet, newline="", encoding="utf-8") as fh:
        rows = list(csv.reader(fh))[1:]
    assert len(rows) == 3  # what the message must count: the template's rows, one per student who handed it in
    assert f"{EX} {W.qid}: 3 rows in {sheet} (3 students who handed {EX} in: 2 answered, 1 blank)" in said
    assert "wrote 1 marking document and 1 marks template" in said and "fill in the 3 rows" in said
    assert "(s)" not in said
    assert main(["collect-written", str(subs), "-o", str(out), "--course", str(ROOT), "--quiet"]) == 0
    assert capsys.readouterr().out == ""


def test_a_mark_above_a_one_point_criterion_is_refused_in_the_singular(tmp_path):
    head = ["student", "exercise", "question", "points", "comment", *(c.name for c in W.spec.criteria)]
    one = next(c for c in W.spec.criteria if c.points == 1)
    sheet = tmp_path / "marks.csv"
    with open(sheet, "w", newline="", encoding="utf-8") as fh:
        cells = ["ann", EX, W.qid, "", "", *("2" if c is one else "" for c in W.spec.criteria)]
        csv.writer(fh).writerows([head, cells])
    with pytest.raises(ValueError, match=rf"column '{one.name}': expected at most 1 point, got '2'"):
        read_marks([sheet], ["ann"], [EX])
