"""``puma-course check``: a student's own notebook graded on the public cases, as grading judges them."""

from __future__ import annotations

import dataclasses
import shutil

import numpy as np

from puma_course.cli import main
from puma_course.grading import EXERCISES, load_bank
from puma_course.grading.publish.public import public_cases_only
from tests.support import ROOT


def test_check_finds_an_exercise_of_the_course_by_name(course_copy, capsys, monkeypatch):
    # the course's own ex01 is a full answer, so 15 / 15 shows it was checked, not the repository's
    shutil.copy(ROOT / "solutions" / "ex01_rotations.ipynb", course_copy / "exercises")
    monkeypatch.chdir(course_copy / "notebooks")
    for name in ("ex01_rotations", "ex01_rotations.ipynb"):
        assert main(["check", name]) == 0
        assert "15 / 15 on the public cases" in capsys.readouterr().out
    assert main(["check", "ex99_nothing"]) == 2
    err = capsys.readouterr().err
    assert "notebook: expected" in err and str(course_copy / "exercises" / "ex99_nothing.ipynb") in err


def test_check_of_a_missing_file_outside_a_course_exits_2(outside, capsys, monkeypatch):
    monkeypatch.chdir(outside)
    assert main(["check", "ex01_rotations"]) == 2
    err = capsys.readouterr().err
    assert "no such file here, and no course" in err and repr(str(outside)) in err
    assert main(["check", str(outside / "sub" / "ex01_rotations.ipynb")]) == 2
    assert "does not exist" in capsys.readouterr().err


def test_check_grades_a_notebook_on_public_cases(capsys):
    assert main(["check", str(ROOT / "solutions" / "ex01_rotations.ipynb")]) == 0
    out = capsys.readouterr().out
    assert "15 / 15 on the public cases" in out
    assert main(["check", str(ROOT / "exercises" / "ex01_rotations.ipynb")]) == 0
    assert "0 / 15" in capsys.readouterr().out


def test_check_rejects_an_unknown_exercise(tmp_path, capsys):
    nb = tmp_path / "mine.ipynb"
    nb.write_text("{}", encoding="utf-8")
    assert main(["check", str(nb)]) == 2
    assert "unknown exercise" in capsys.readouterr().err


def test_check_keeps_bonus_and_answer_key_rules_of_the_grader(tmp_path, capsys):
    """`puma-course check` must judge the public cases exactly as grading does.

    The ex06 solution answers the bonus too: 10 points plus a 3-point bonus, not 13 / 13.
    """
    nb = tmp_path / "ex06_porter_explicit.ipynb"
    shutil.copy(ROOT / "solutions" / "ex06_porter_explicit.ipynb", nb)
    assert main(["check", str(nb)]) == 0
    out = capsys.readouterr().out
    assert "13 / 10" in out and "(bonus)" in out


def test_check_grades_on_the_public_cases_alone_and_keeps_every_other_rule():
    """The exercise check grades: no hidden case drawn, every other field of the exercise and its questions kept."""
    load_bank(ROOT)
    ex = EXERCISES["ex06_porter_explicit"]  # a bonus question and answer-key tripwires: what must survive
    public = public_cases_only(ex)
    rng = np.random.default_rng(0)
    assert any(q.hidden(rng) for q in ex.questions)  # the course's own draws hidden cases ...
    assert all(q.hidden(np.random.default_rng(s)) == [] for q in public.questions for s in range(3))  # ... check none
    assert [len(q.cases(rng)) for q in public.questions] == [len(q.public) for q in ex.questions]  # public alone
    for name in (f.name for f in dataclasses.fields(ex) if f.name != "questions"):
        assert getattr(public, name) is getattr(ex, name), name
    for q, p in zip(ex.questions, public.questions, strict=True):
        for name in (f.name for f in dataclasses.fields(q) if f.name != "hidden"):
            assert getattr(p, name) is getattr(q, name), (q.qid, name)
    assert any(q.hidden(rng) for q in ex.questions)  # the bank's exercise itself is left as it was
