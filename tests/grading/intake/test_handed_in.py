"""`puma-course grade` grades what was handed in: the issue's class of three students and two exercises.

Ann and Ben handed in ex03 and ex09 (the solutions), Cat only ex03 (the blank exercise). The other
eight exercises of the course appear nowhere: no CSV row, no feedback line, no summary table, one
line in the terminal. Cat's ex09 is `missing`, since her classmates handed it in. The run uses
--jobs 2 in a real process, so its progress lines are the ones a terminal gets: one per record.
"""

from __future__ import annotations

import csv
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from puma_course.grading import EXERCISES
from puma_course.grading.intake.submissions import handed_in
from tests.support import ROOT

HANDED = ("ex03_puma_fk", "ex09_puma_ik")
NOT_HANDED = sorted(set(EXERCISES) - set(HANDED))


@pytest.fixture(scope="module")
def graded(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, subprocess.CompletedProcess[str]]:
    base = tmp_path_factory.mktemp("handed")
    subs = base / "subs"
    for student in ("ann", "ben"):
        (subs / student).mkdir(parents=True)
        for name in HANDED:
            shutil.copy(ROOT / "solutions" / f"{name}.ipynb", subs / student)
    (subs / "cat").mkdir()
    shutil.copy(ROOT / "exercises" / "ex03_puma_fk.ipynb", subs / "cat")
    cmd = [sys.executable, "-m", "puma_course.cli", "grade", str(subs), "-o", str(base / "grades.csv")]
    cmd += ["--feedback", str(base / "feedback"), "--course", str(ROOT), "--jobs", "2", "--seed", "3"]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=300, cwd=base)
    assert proc.returncode == 0, proc.stderr
    return base, proc


def test_handed_in_lists_the_exercises_some_student_has_a_file_for(tmp_path):
    (tmp_path / "ann").mkdir()
    (tmp_path / "ann" / "ex09_puma_ik.ipynb").write_text("{}", encoding="utf-8")
    (tmp_path / "ann" / "ex03_puma_fk.ipynb").mkdir()  # a folder where the notebook should be: handed in, refused
    (tmp_path / "ben").mkdir()
    (tmp_path / "ben" / "ex1.ipynb").write_text("{}", encoding="utf-8")  # not an exercise's name
    (tmp_path / "ex01_rotations.ipynb").write_text("{}", encoding="utf-8")  # not in a student's folder
    assert handed_in(tmp_path, sorted(EXERCISES)) == ["ex03_puma_fk", "ex09_puma_ik"]


def test_rows_are_written_for_the_handed_in_exercises_only(graded):
    base, _ = graded
    with open(base / "grades.csv", newline="", encoding="utf-8") as fh:
        rows = {(r["student"], r["exercise"]): r for r in csv.DictReader(fh)}
    assert sorted(rows) == [(s, e) for s in ("ann", "ben", "cat") for e in HANDED]
    assert rows["ann", "ex03_puma_fk"]["score"] == "9" and rows["ben", "ex09_puma_ik"]["score"] == "15"
    assert rows["cat", "ex03_puma_fk"]["status"] == "ok" and rows["cat", "ex03_puma_fk"]["score"] == "0"
    assert rows["cat", "ex09_puma_ik"]["status"] == "missing"


def test_feedback_and_summary_name_no_exercise_nobody_handed_in(graded):
    base, _ = graded
    for student in ("ann", "ben", "cat"):
        text = (base / "feedback" / f"{student}.md").read_text(encoding="utf-8")
        assert not [name for name in NOT_HANDED if name in text], text
        assert "/ 24** points" in text  # ex03 (9) + ex09 (15), not the course's 111
    cat = (base / "feedback" / "cat.md").read_text(encoding="utf-8")
    assert "no file ex09_puma_ik.ipynb was submitted" in cat
    summary = (base / "grades-summary.md").read_text(encoding="utf-8")
    assert not [name for name in NOT_HANDED if name in summary]
    assert all(f"## {name}" in summary for name in HANDED)


def test_the_terminal_names_each_exercise_nobody_handed_in_once(graded):
    _, proc = graded
    said = proc.stdout + proc.stderr
    for name in NOT_HANDED:
        assert said.count(name) == 1, (name, said)
    assert "--exercise" in proc.stderr


def test_progress_lines_are_one_per_record_with_two_jobs(graded):
    _, proc = graded
    line = re.compile(r"^ *(ann|ben|cat) (ex03_puma_fk|ex09_puma_ik) +\d+/\d+ +[a-z-]+ \([\d.]+ s\)$")
    lines = proc.stdout.splitlines()
    progress = lines[: [i for i, s in enumerate(lines) if s.startswith("graded ")][0]]  # what comes before the total
    assert all(line.match(s) for s in progress), progress
    assert sorted(re.split(r" +", s.strip())[:2] for s in progress) == [
        [s, e] for s in ("ann", "ben", "cat") for e in HANDED
    ]
