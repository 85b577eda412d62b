"""The puma-course command line (never starts a Jupyter server)."""

from __future__ import annotations

import csv
import shutil
import sys
from pathlib import Path

import pytest

from puma_course.cli import main

ROOT = Path(__file__).resolve().parent.parent


def test_lab_prints_the_command_without_running_it(capsys):
    assert main(["lab", "--no-browser", "--print-command"]) == 0
    out = capsys.readouterr().out.strip()
    assert out.startswith(sys.executable) or out.startswith("'" + sys.executable)
    assert "-m jupyterlab" in out and str(ROOT / "notebooks") in out and out.endswith("--no-browser")


def test_release_check_passes_on_the_committed_exercises(capsys):
    assert main(["release", "--check"]) == 0
    assert "up to date" in capsys.readouterr().out


def test_release_writes_and_check_detects_a_stale_exercise(tmp_path, capsys):
    sol, ex = tmp_path / "solutions", tmp_path / "exercises"
    sol.mkdir()
    shutil.copy(ROOT / "solutions" / "ex01_rotations.ipynb", sol)
    assert main(["release", "--solutions", str(sol), "--exercises", str(ex), "--check"]) == 1
    assert main(["release", "--solutions", str(sol), "--exercises", str(ex)]) == 0
    assert (ex / "ex01_rotations.ipynb").read_bytes() == (ROOT / "exercises" / "ex01_rotations.ipynb").read_bytes()
    assert main(["release", "--solutions", str(sol), "--exercises", str(ex), "--check"]) == 0
    with open(ex / "ex01_rotations.ipynb", "a", encoding="utf-8") as fh:
        fh.write(" ")
    # the file's layout is not what the check compares (JupyterLab rewrites it on every save) ...
    assert main(["release", "--solutions", str(sol), "--exercises", str(ex), "--check"]) == 0
    # ... a cell's source is
    path = ex / "ex01_rotations.ipynb"
    path.write_text(path.read_text(encoding="utf-8").replace("(axis, angle):", "(axis, angle=0):", 1), encoding="utf-8")
    assert main(["release", "--solutions", str(sol), "--exercises", str(ex), "--check"]) == 1
    assert "ex01_rotations" in capsys.readouterr().err


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
            "--quiet",
        ]
    )
    assert code == 0
    with open(out, newline="", encoding="utf-8") as fh:
        rows = {r["student"]: r for r in csv.DictReader(fh)}
    assert rows["ann"]["score"] == "10" and rows["ann"]["status"] == "ok"
    assert rows["ben"]["score"] == "0" and rows["ben"]["status"] == "missing"
    assert (fb / "ann.md").exists() and (fb / "ben.md").exists()
    assert "graded 2 notebook(s)" in capsys.readouterr().out


def test_grade_rejects_a_missing_folder(tmp_path, capsys):
    assert main(["grade", str(tmp_path / "nope"), "-o", str(tmp_path / "g.csv")]) == 2
    assert "submissions" in capsys.readouterr().err


def test_check_grades_a_notebook_on_public_cases(capsys):
    assert main(["check", str(ROOT / "solutions" / "ex01_rotations.ipynb")]) == 0
    out = capsys.readouterr().out
    assert "10 / 10 on the public cases" in out
    assert main(["check", str(ROOT / "exercises" / "ex01_rotations.ipynb")]) == 0
    assert "0 / 10" in capsys.readouterr().out


def test_check_rejects_an_unknown_exercise(tmp_path, capsys):
    nb = tmp_path / "mine.ipynb"
    nb.write_text("{}", encoding="utf-8")
    assert main(["check", str(nb)]) == 2
    assert "unknown exercise" in capsys.readouterr().err


def test_unknown_subcommand_exits_with_usage():
    with pytest.raises(SystemExit):
        main(["frobnicate"])


def test_grade_warns_and_exits_3_when_the_package_changes_during_grading(tmp_path, monkeypatch, capsys):
    from puma_course.grading import runner

    digests = iter([{"a.py": b"1"}, {"a.py": b"2"}])
    monkeypatch.setattr(runner, "_package_digest", lambda: next(digests))
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
    assert (
        main(
            [
                "grade",
                str(subs),
                "-o",
                str(tmp_path / "g.csv"),
                "--feedback",
                str(tmp_path / "fb"),
                "--exercise",
                "ex01_rotations",
                "--quiet",
            ]
        )
        == 0
    )
    text = (tmp_path / "fb" / "cat.md").read_text(encoding="utf-8")
    assert "missing" in text and "ex01_rotations (1).ipynb" in text


def test_check_keeps_bonus_and_answer_key_rules_of_the_grader(tmp_path, capsys):
    """`puma-course check` must judge the public cases exactly as grading does.

    The ex05 solution answers the bonus too: 8 points plus a 3-point bonus, not 11 / 11.
    """
    nb = tmp_path / "ex05_porter_ik.ipynb"
    shutil.copy(ROOT / "solutions" / "ex05_porter_ik.ipynb", nb)
    assert main(["check", str(nb)]) == 0
    out = capsys.readouterr().out
    assert "11 / 8" in out and "(bonus)" in out
