"""``puma-course grade``: a class graded into the CSV and the feedback (tests/grading has the rest)."""

from __future__ import annotations

import csv
import shutil

from puma_course.cli import main
from tests.cli.support import grade_argv
from tests.support import ROOT


def test_grade_grades_the_exercises_the_course_hands_out(course_copy, capsys, monkeypatch):
    (course_copy / "exercises" / "ex99_mine.ipynb").write_text("{}", encoding="utf-8")
    (course_copy / "subs" / "ann").mkdir(parents=True)
    (course_copy / "subs" / "ben").mkdir(parents=True)
    (course_copy / "subs" / "ben" / "ex01_rotations.ipynb").write_text("{}", encoding="utf-8")
    monkeypatch.chdir(course_copy)
    # ann's folder is empty: graded (the CSV says missing); ben handed ex01 in, so only ex01 is graded
    assert main(["grade", "subs", "-o", "g.csv", "--quiet", "--seed", "1"]) == 0
    with open(course_copy / "g.csv", newline="", encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    assert [(r["student"], r["exercise"], r["status"]) for r in rows] == [
        ("ann", "ex01_rotations", "missing"),
        ("ben", "ex01_rotations", "malformed"),
    ]
    err = capsys.readouterr().err
    assert "not graded" in err and "ex99_mine" in err


def test_grade_of_a_class_that_handed_in_no_exercise_exits_2(course_copy, capsys, monkeypatch):
    (course_copy / "subs" / "ann").mkdir(parents=True)
    (course_copy / "subs" / "ann" / "ex1.ipynb").write_text("{}", encoding="utf-8")
    monkeypatch.chdir(course_copy)
    assert main(["grade", "subs", "-o", "g.csv", "--quiet"]) == 2
    err = capsys.readouterr().err
    assert "named after the course's exercises" in err and "ex01_rotations" in err
    assert not (course_copy / "g.csv").exists()


def test_grade_writes_csv_and_feedback(tmp_path, capsys):
    subs = tmp_path / "subs"
    (subs / "ann").mkdir(parents=True)
    (subs / "ben").mkdir()
    shutil.copy(ROOT / "solutions" / "ex01_rotations.ipynb", subs / "ann")
    out, fb = tmp_path / "grades.csv", tmp_path / "fb"
    code = main(
        [
            "grade",
            str(subs),
            "-o",
            str(out),
            "--feedback",
            str(fb),
            "--jobs",
            "2",
            "--timeout-cell",
            "10",
            "--timeout-total",
            "30",
            "--seed",
            "5",
            "--exercise",
            "ex01_rotations",
        ]
    )
    assert code == 0
    with open(out, newline="", encoding="utf-8") as fh:
        rows = {r["student"]: r for r in csv.DictReader(fh)}
    assert rows["ann"]["score"] == "15" and rows["ann"]["status"] == "ok"
    assert rows["ben"]["score"] == "0" and rows["ben"]["status"] == "missing"
    assert (fb / "ann.md").exists() and (fb / "ben.md").exists()
    assert "graded 2 notebooks of 2 students" in capsys.readouterr().out


def test_grade_rejects_a_missing_folder(tmp_path, capsys):
    assert main(["grade", str(tmp_path / "nope"), "-o", str(tmp_path / "g.csv")]) == 2
    assert "submissions" in capsys.readouterr().err


def test_grade_warns_and_exits_3_when_the_package_changes_during_grading(tmp_path, monkeypatch, capsys):
    from puma_course.grading.run import runner

    digests = iter([{"a.py": b"1"}, {"a.py": b"2"}])
    monkeypatch.setattr(runner, "package_digest", lambda *_: next(digests))
    (tmp_path / "subs" / "ann").mkdir(parents=True)
    code = main(
        ["grade", str(tmp_path / "subs"), "-o", str(tmp_path / "g.csv"), "--exercise", "ex01_rotations", "--quiet"]
    )
    assert code == 3
    assert "changed while grading" in capsys.readouterr().err


def test_missing_notebook_feedback_names_misnamed_files(tmp_path):
    subs = tmp_path / "subs"
    (subs / "cat").mkdir(parents=True)
    shutil.copy(ROOT / "solutions" / "ex01_rotations.ipynb", subs / "cat" / "ex01_rotations (1).ipynb")
    assert main(grade_argv(subs, tmp_path, "--quiet")) == 0
    text = (tmp_path / "fb" / "cat.md").read_text(encoding="utf-8")
    assert "missing" in text and "ex01_rotations (1).ipynb" in text


#: the lines that only inform: printed without --quiet, never with it
INFORM = ("hidden inputs:", "sandbox:", "limits:", "graded ", "merged ", "class summary:", "gradebook (", "shard ")


def _class(tmp_path):
    subs = tmp_path / "subs"
    for who in ("ann", "ben"):
        (subs / who).mkdir(parents=True)
    shutil.copy(ROOT / "solutions" / "ex01_rotations.ipynb", subs / "ann")
    return subs


def test_quiet_grade_and_merge_print_only_warnings_and_errors(tmp_path, capsys):
    subs = _class(tmp_path)
    args = grade_argv(subs, tmp_path, "--seed", "5", "--course", str(ROOT), "--sandbox", "none")
    args += ["--gradebook", "canvas", "--shard", "1/1"]
    assert main(args) == 0
    loud = capsys.readouterr()
    said = (loud.out + loud.err).splitlines()
    assert all(any(line.startswith(w) for line in said) for w in ("hidden inputs:", "graded ", "gradebook ("))
    assert main([*args, "--quiet"]) == 0
    quiet = capsys.readouterr()
    assert quiet.out == ""
    lines = quiet.err.splitlines()
    assert not [line for line in lines if line.startswith(INFORM)]
    assert any(line.startswith("WARNING: grading WITHOUT the operating-system sandbox") for line in lines)
    # a class graded from folders has no Canvas user ids: said once, with the count, not once per student
    (canvas,) = [line for line in lines if "Canvas user id" in line]
    assert "2 students: ann, ben" in canvas and "not from a Canvas download" in canvas

    shard = tmp_path / "g.shard.json"
    merge = ["merge", str(shard), "-o", str(tmp_path / "m.csv"), "--seed", "5", "--course", str(ROOT)]
    assert main([*merge, "--gradebook", "canvas"]) == 0
    assert "merged 1 shard: 2 notebooks of 2 students" in capsys.readouterr().out
    assert main([*merge, "--gradebook", "canvas", "--quiet"]) == 0
    quiet = capsys.readouterr()
    assert quiet.out == "" and len(quiet.err.splitlines()) == 1 and "2 students: ann, ben" in quiet.err


def test_grade_says_what_was_graded_in_the_singular_for_one(tmp_path, capsys):
    subs = tmp_path / "subs"
    (subs / "ann").mkdir(parents=True)
    shutil.copy(ROOT / "solutions" / "ex01_rotations.ipynb", subs / "ann")
    args = grade_argv(subs, tmp_path, "--seed", "5", "--course", str(ROOT), "--sandbox", "none")
    assert main([*args, "--gradebook", "canvas"]) == 0
    said = capsys.readouterr()
    assert "graded 1 notebook of 1 student " in said.out
    assert "no Canvas user id (the ID Canvas's import matches a row by) for 1 student: ann" in said.err
    assert "(s)" not in said.out + said.err
