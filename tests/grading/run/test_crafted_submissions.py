"""Grading is robust and fair: each crafted submission in tests/fixtures/submissions gets what it earned.

One grading run over a copy of the fixture class (17 students, exercise 1 only) with short
limits (3 s per cell and per call, 30 s per notebook), under the sandbox the machine has ("auto"),
plus a student built here who tampers with files whose paths it is given. With a control group a cell or call
is timed on CPU time, with a wall-clock backstop of 3 x 3 s: the notebook's 30 s leave room for the two loops
of endless_loop however loaded the machine (on the wall clock alone, 8 s did). Expected scores are
worked out from what each crafted notebook does (see tests/fixtures/submissions/*/ex01_rotations.ipynb).
The many more hostile submissions of tests/fixtures/hostile/ are graded by the test_hostile_* files.
"""

from __future__ import annotations

import csv
import hashlib
import shutil
import warnings
from pathlib import Path

import nbformat
import pytest

from puma_course.grading import EXERCISES, SandboxWarning, grade
from tests.support import ROOT

# CI's second pass (another OpenBLAS kernel) leaves this out: crafted submissions (loops, crashes, floods,
# tampering) under short time limits: the grader's robustness; an honest answer's numerics under this kernel are
# test_exercises' full marks.
pytestmark = pytest.mark.no_numerics

FIXTURES = ROOT / "tests" / "fixtures" / "submissions"
EX = "ex01_rotations"

# student -> (score, status, {question: points})
EXPECTED = {
    "good": (13, "ok", {}),
    "malformed_json": (0, "malformed", {}),
    "not_a_notebook": (0, "malformed", {}),
    "raises": (7, "cell-error", {"q3": 0}),
    "endless_loop": (7, "cell-error", {"q3": 0}),
    "stubborn_loop": (0, "timeout", {}),
    "huge_print": (10, "ok", {}),
    "missing_function": (7, "ok", {"q2": 0}),
    "wrong_type": (2, "ok", {"q4": 2}),
    "cheat_monkeypatch": (0, "cell-error", {}),  # the question bank is not there to patch
    "exit_sys": (10, "cell-error", {}),
    "exit_os": (0, "crashed", {}),
    "answer_key": (2, "cell-error", {"q4": 2}),  # the package's answers are not there to import
    "read_expected": (2, "ok", {"q1": 0, "q4": 2}),
    "tamper_files": (13, "ok", {}),  # the good notebook plus a cell that tampers
    "memory_hog": (10, "cell-error", {}),
    "evil_values": (5, "ok", {"q1": 0, "q2": 0}),
    "memorizer": (2.33, "ok", {"q1": 2, "q4": 0.33}),  # q4: 1 of its 6 cases (2 public since issue 22)
}


def _digest(folder: Path) -> dict[str, str]:
    return {
        str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
        for p in sorted(folder.rglob("*"))
        if p.is_file()
    }


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    root = tmp_path_factory.mktemp("class")
    subs = root / "submissions"
    shutil.copytree(FIXTURES, subs)
    out = root / "grades.csv"
    # a student who knows every path: the grades file, a classmate's notebook, its own notebook
    good_nb = subs / "good" / f"{EX}.ipynb"
    tamper = nbformat.read(good_nb, as_version=4)
    own_nb = subs / "tamper_files" / f"{EX}.ipynb"
    tamper.cells.append(
        nbformat.v4.new_code_cell(
            "import os\n"
            f"for target in [{str(out)!r}, {str(good_nb)!r}, 'grades.csv', {str(own_nb)!r}]:\n"
            "    try:\n"
            "        with open(target, 'w') as fh:\n"
            "            fh.write('student,exercise,score\\ntamper_files,ex01_rotations,1000\\n')\n"
            "    except OSError:\n"
            "        pass\n"
        )
    )
    (subs / "tamper_files").mkdir()
    nbformat.write(tamper, own_nb)
    before = _digest(subs)
    fb = root / "feedback"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SandboxWarning)
        results = grade(subs, out, feedback=fb, jobs=2, timeout_cell=3, timeout_total=30, seed=11, exercises=[EX])
    with open(out, newline="", encoding="utf-8") as fh:
        rows = {row["student"]: row for row in csv.DictReader(fh)}
    return {
        "results": {r.student: r for r in results},
        "rows": rows,
        "before": before,
        "subs": subs,
        "feedback": fb,
        "out": out,
        "sandbox": rows["good"]["sandbox"],
    }


@pytest.mark.parametrize("student", sorted(EXPECTED))
def test_each_crafted_submission_gets_what_it_earned(graded, student):
    score, status, per_question = EXPECTED[student]
    row = graded["rows"][student]
    assert float(row["score"]) == score, (student, row)
    assert row["status"] == status, (student, row)
    assert float(row["max_score"]) == EXERCISES[EX].max_score
    for qid, points in per_question.items():
        assert float(row[qid]) == points, (student, qid, row)


def test_csv_has_one_row_per_student_and_the_documented_columns(graded):
    rows = graded["rows"]
    assert set(rows) == set(EXPECTED)
    columns = list(next(iter(rows.values())))
    assert columns[:4] == ["student", "exercise", "score", "max_score"]
    assert {"q1", "q2", "q3", "q4", "status"} <= set(columns)


def test_the_grades_file_is_written_by_the_grader_last(graded):
    text = graded["out"].read_text(encoding="utf-8")
    assert "1000" not in text


def test_the_tamperer_damaged_no_grade_and_in_the_sandbox_no_file(graded):
    after = _digest(graded["subs"])
    changed = {k for k in after if after[k] != graded["before"].get(k)}
    if graded["sandbox"] == "bwrap":
        assert changed == set()  # nothing outside the worker's folder is writable, or even visible
    else:
        # without the sandbox the tamperer overwrites what it can reach on disk ...
        assert changed <= {f"good/{EX}.ipynb", f"tamper_files/{EX}.ipynb"}
    # ... but every notebook was read before any student code ran, so "good" still has full marks
    assert float(graded["rows"]["good"]["score"]) == 13


def test_the_csv_records_the_sandbox_and_the_seed(graded):
    rows = graded["rows"].values()
    assert {r["sandbox"] for r in rows} == {graded["sandbox"]} and graded["sandbox"] in ("bwrap", "none")
    assert {r["seed"] for r in rows} == {"11"} and {r["bonus"] for r in rows} == {"0"}
    warned = "graded without the operating-system sandbox" in (graded["feedback"] / "good.md").read_text("utf-8")
    assert warned == (graded["sandbox"] == "none")


def test_other_submissions_are_never_modified(graded):
    after = _digest(graded["subs"])
    for key, digest in graded["before"].items():
        if not key.startswith(("good/", "tamper_files/")):
            assert after[key] == digest, key


def test_feedback_explains_what_passed_and_failed(graded):
    fb = graded["feedback"]
    assert sorted(p.stem for p in fb.glob("*.md")) == sorted(EXPECTED)
    text = (fb / "missing_function.md").read_text(encoding="utf-8")
    assert "no function named rotation_between() was defined" in text
    assert "7 / 15" in text  # q5 and q6 are not answered either (these submissions predate it)
    text = (fb / "answer_key.md").read_text(encoding="utf-8")
    assert "puma_course.rodrigues is not available in this exercise" in text
    text = (fb / "endless_loop.md").read_text(encoding="utf-8")
    # the clock that held: the wall clock (no control group), CPU time, or CPU time's wall-clock backstop
    assert any(s in text for s in ("ran longer than 3 s", "used more than 3 s of CPU", "longer than 9 s on the wall"))
    text = (fb / "malformed_json.md").read_text(encoding="utf-8")
    assert "not a readable notebook" in text
    text = (fb / "huge_print.md").read_text(encoding="utf-8")
    assert "10 / 15" in text


def test_timeouts_are_reported_per_notebook(graded):
    res = graded["results"]
    assert res["stubborn_loop"].status == "timeout"
    assert any("ran longer than 30 s" in n for n in res["stubborn_loop"].notes)
    assert res["huge_print"].status == "ok"
