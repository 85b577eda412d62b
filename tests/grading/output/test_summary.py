"""The instructor's class summary: who passed each question and which mistakes were common."""

from __future__ import annotations

import shutil

import nbformat
import pytest

from puma_course.cli import main
from puma_course.grading import EXERCISES, NotebookResult
from puma_course.grading.output.summary import class_summary, question_summaries, summary_path, write_summary
from tests.support import ROOT

EX = EXERCISES["ex01_rotations"]


def _result(student, scores, mistakes=None, status="ok", notes=None):
    r = NotebookResult.blank(student, EX, status)
    for qid, points in scores.items():
        r.scores[qid] = points
        r.question_notes[qid] = notes.get(qid, ["1/1 cases pass"]) if notes else ["1/1 cases pass"]
    r.mistakes.update(mistakes or {})
    return r


@pytest.fixture
def results():
    stub = {"q3": ["0/7 cases pass", "public case 1: not attempted yet (NotImplementedError)"]}
    return [
        _result("ann", {"q1": 2, "q2": 3, "q3": 3, "q4": 2, "q5": 3, "q6": 2}),
        _result("bob", {"q1": 0, "q2": 1, "q3": 0, "q4": 2, "q5": 3, "q6": 2},
                {"q1": ["rotation_sense"] * 9, "q2": ["unnormalised"]},
                notes={"q1": ["0/9 cases pass", "case 1: your matrix turns the wrong way"], "q3": stub["q3"]}),
        _result("cat", {"q1": 0, "q2": 0, "q3": 0, "q4": 0, "q5": 0, "q6": 2}, {"q1": ["rotation_sense", "degrees"]},
                notes={"q1": ["0/9 cases pass", "case 1: your matrix turns the wrong way"]}),
        NotebookResult.blank("dan", EX, "missing", "no file"),
    ]  # fmt: skip


def test_counts_per_question(results):
    s = {x.question.qid: x for x in question_summaries(results)}
    assert s["q1"].submitted == 3  # dan handed nothing in
    assert (s["q1"].passed, s["q1"].failed, s["q1"].partly) == (1, 2, 0)
    assert (s["q2"].passed, s["q2"].partly, s["q2"].failed) == (1, 1, 1)
    assert s["q3"].not_attempted == 1 and s["q3"].passed == 1
    assert s["q1"].mistakes["rotation_sense"] == 2  # counted once per student, not per case
    assert s["q1"].common() == [("rotation_sense", 2), ("degrees", 1)]
    assert s["q4"].mean == pytest.approx(4 / 3)


def test_the_markdown_names_every_question_and_the_mistakes_in_words(results):
    text = class_summary(results)
    assert text.startswith("# Class summary: 4 students, 1 exercise")
    assert "Handed in by 3 of 4 students." in text
    row = next(line for line in text.splitlines() if line.startswith("| q1 "))
    assert row.startswith("| q1 `elementary_rotation` | 2 | 1 | 0 | 2 | 0 | 0.67 |")
    assert "a rotation turned the wrong way (by -θ for θ) (`rotation_sense`): 2" in row
    for q in EX.questions:
        assert f"| {q.qid} `{q.function}`" in text


def test_written_next_to_the_grades_with_a_short_text(tmp_path, results):
    assert summary_path(tmp_path / "grades.csv") == tmp_path / "grades-summary.md"
    path, text = write_summary(results, tmp_path / "grades.csv")
    assert path.read_text(encoding="utf-8") == class_summary(results)
    lines = text.splitlines()
    assert lines[0] == f"class summary: {path}"
    assert lines[1] == (
        "  ex01_rotations q1 elementary_rotation: 1/3 passed; commonest mistake: "
        "a rotation turned the wrong way (by -θ for θ) (2)"
    )


def test_puma_course_grade_writes_and_prints_the_summary(tmp_path, capsys):
    """A class of two: one hands in the solution, one transposes every rotation of question 1 (turned the wrong way)."""
    subs = tmp_path / "subs"
    for student in ("ann", "bob"):
        (subs / student).mkdir(parents=True)
    shutil.copy(ROOT / "solutions" / "ex01_rotations.ipynb", subs / "ann")
    nb = nbformat.read(ROOT / "solutions" / "ex01_rotations.ipynb", as_version=4)
    answer = next(c for c in nb.cells if "question:q1" in c.metadata.get("tags", []))
    answer.source += (
        "\n\n\n_right = elementary_rotation\n\n\ndef elementary_rotation(axis, angle):\n"
        "    return _right(axis, angle).T\n"
    )
    nbformat.write(nb, subs / "bob" / "ex01_rotations.ipynb")
    out = tmp_path / "grades.csv"
    code = main(["grade", str(subs), "-o", str(out), "--exercise", "ex01_rotations", "--seed", "3",
                 "--course", str(ROOT)])  # fmt: skip
    assert code == 0
    printed = capsys.readouterr().out
    summary = tmp_path / "grades-summary.md"
    assert f"class summary: {summary}" in printed
    assert (
        "ex01_rotations q1 elementary_rotation: 1/2 passed; commonest mistake: a rotation turned the wrong way"
        in printed
    )
    text = summary.read_text(encoding="utf-8")
    assert (
        "| q1 `elementary_rotation` | 2 | 1 | 0 | 1 | 0 | 1.00 | a rotation turned the wrong way (by -θ for θ) "
        "(`rotation_sense`): 1 |" in text
    )
