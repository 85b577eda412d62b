"""One total per student, everywhere: the CSV, the feedback, the class summary and every gradebook agree.

A small class hands in ex01 and ex02 (ex02 has a written question): ann hands in both exercises, solved,
with a written answer marked by rubric line; bob hands in ex02 blank with a written answer marked by points
only, and no ex01; cy hands in ex02 solved and her written answer is not marked yet; dee hands in ex01 alone, so her
ex02 written question has nothing to mark and scores 0, as its auto-graded questions do. The marks file is the
one ``collect-written`` makes, filled in as a marker would. The class is graded with the marks into the
Canvas, Moodle and wide gradebooks twice: by the command (``puma-course grade ... --marks``) and from Python
(:func:`puma_course.grading.grade` given a :class:`~puma_course.grading.settings.GradeSettings`). Every file
is parsed back on its own terms (the csv module; the Canvas and Moodle columns as their importers read them,
:mod:`puma_course.grading.output.gradebook`; the feedback's and summary's Markdown lines) and each student's
total must be the same number in all of them, and the number worked out here by hand from the marks. cy's answer,
not marked yet, must be shown as such everywhere: her total called provisional in the feedback and the summary, an
empty written cell (no grade on import, never 0) in the CSV and every gradebook, counted in the wide gradebook.
"""

from __future__ import annotations

import csv
import re
import shutil
import warnings
from pathlib import Path

import pytest

from puma_course.cli import main
from puma_course.grading import EXERCISES, grade
from puma_course.grading.output.gradebook import CANVAS_IDS
from puma_course.grading.settings import GradeSettings
from puma_course.grading.written import written_questions
from tests.cli.support import hand_in_written
from tests.support import ROOT

EX1, EX2 = "ex01_rotations", "ex02_dh_frames"
(W,) = written_questions(EX2)
AUTO1, AUTO2, WMAX = EXERCISES[EX1].max_score, EXERCISES[EX2].max_score, W.points
#: by hand: ann solved both (15 + 12) and got 2.5 written; bob 0 auto-graded and 1 written; cy 12 and unmarked
EXPECTED = {"ann": AUTO1 + AUTO2 + 2.5, "bob": 1.0, "cy": AUTO2 + 0.0, "dee": AUTO1 + 0.0}
PROVISIONAL = {"cy"}  # the only student with an answer handed in and not marked yet
FILES = ("csv", "canvas", "moodle", "wide", "wide (count)", "feedback", "summary")
TOP = AUTO1 + AUTO2 + WMAX  # every student's points possible: both exercises and the written question


@pytest.fixture(scope="module")
def handed(tmp_path_factory) -> tuple[Path, Path]:
    base = tmp_path_factory.mktemp("class")
    sub = base / "hand-in"
    hand_in_written(sub / "ann", EX2, True, "$z_1$ up the column, $z_2 = -y_0$.")
    shutil.copy(ROOT / "solutions" / f"{EX1}.ipynb", sub / "ann" / f"{EX1}.ipynb")
    hand_in_written(sub / "bob", EX2, False, "The origin of {1} is where the column and shoulder axes cross.")
    hand_in_written(sub / "cy", EX2, True, None)
    (sub / "dee").mkdir()
    shutil.copy(ROOT / "solutions" / f"{EX1}.ipynb", sub / "dee" / f"{EX1}.ipynb")
    marking = base / "marking"
    assert main(["collect-written", str(sub), "-o", str(marking), "--course", str(ROOT), "--exercise", EX2]) == 0
    sheet = marking / f"{EX2}-{W.qid}-marks.csv"
    rows = _rows(sheet)
    col = {h: i for i, h in enumerate(rows[0])}
    rubric = [c.name for c in W.spec.criteria]
    for row in rows[1:]:
        if row[0] == "ann":  # by rubric line: 1 + 1 + 0.5 + 0 = 2.5
            for name, value in zip(rubric, ["1", "1", "0.5", "0"], strict=True):
                row[col[name]] = value
        elif row[0] == "bob":  # by points only
            row[col["points"]] = "1"
    with open(sheet, "w", newline="", encoding="utf-8") as fh:
        csv.writer(fh).writerows(rows)
    return sub, sheet


def _rows(path: Path) -> list[list[str]]:
    with open(path, newline="", encoding="utf-8") as fh:
        return list(csv.reader(fh))


def _dicts(path: Path) -> list[dict[str, str]]:
    with open(path, newline="", encoding="utf-8") as fh:
        return list(csv.DictReader(fh))


def totals_everywhere(out: Path, feedback: Path) -> dict[str, dict[str, tuple[float, float | None]]]:
    """Each file's (total, points possible or None where the file does not say) per student, by file."""
    found: dict[str, dict[str, tuple[float, float | None]]] = {}
    grades: dict[str, list[float]] = {}
    for r in _dicts(out):  # the grades CSV: auto-graded score per row, plus the row's written points
        auto, top = float(r["score"]), float(r["max_score"])
        written, wtop = float(r.get("written") or 0), float(r.get("written_max") or 0)
        got = grades.setdefault(r["student"], [0.0, 0.0])
        got[0] += auto + written
        got[1] += top + wtop
    found["csv"] = {s: (t, m) for s, (t, m) in grades.items()}
    canvas = _rows(out.with_name(f"{out.stem}-canvas.csv"))
    head = canvas[0]
    assert head[: len(CANVAS_IDS)] == CANVAS_IDS and head[-1] == "Final Points"
    assert canvas[1][0].strip() == "Points Possible"
    possible = sum(float(x) for x in canvas[1][len(CANVAS_IDS) : -1])
    found["canvas"] = {r[0]: (float(r[-1]), possible) for r in canvas[2:]}
    moodle = _dicts(out.with_name(f"{out.stem}-moodle.csv"))
    found["moodle"] = {r["Full name"]: (float(r["Total"]), None) for r in moodle}
    wide = _dicts(out.with_name(f"{out.stem}-wide.csv"))
    found["wide"] = {r["student"]: (float(r["total"]), None) for r in wide}
    found["feedback"] = {}
    for path in sorted(feedback.glob("*.md")):
        (m,) = re.findall(r"^Total: \*\*([0-9.]+) / ([0-9.]+)\*\* points", path.read_text(encoding="utf-8"), re.M)
        found["feedback"][path.stem] = (float(m[0]), float(m[1]))
    summary = out.with_name(f"{out.stem}-summary.md").read_text(encoding="utf-8")
    rows = re.findall(
        r"^\| `([^`]+)` \| [^|]+ \| [^|]+ \| \*\*([0-9.]+) / ([0-9.]+)\*\*(?: provisional)? \|$", summary, re.M
    )
    found["summary"] = {s: (float(t), float(m)) for s, t, m in rows}
    return found


def provisional_everywhere(out: Path, feedback: Path) -> dict[str, set[str]]:
    """The students each file shows with a written answer not marked yet (or a total said to be provisional)."""
    found = {"csv": {r["student"] for r in _dicts(out) if r["written_max"] and not r["written"]}}
    column = f"{EX2} written"
    canvas = _rows(out.with_name(f"{out.stem}-canvas.csv"))
    at = canvas[0].index(column)
    found["canvas"] = {r[0] for r in canvas[2:] if r[at] == ""}
    found["moodle"] = {r["Full name"] for r in _dicts(out.with_name(f"{out.stem}-moodle.csv")) if r[column] == ""}
    wide = _dicts(out.with_name(f"{out.stem}-wide.csv"))
    found["wide"] = {r["student"] for r in wide if r[column] == ""}
    found["wide (count)"] = {r["student"] for r in wide if int(r["written not marked"]) > 0}
    found["feedback"] = set()
    for path in sorted(feedback.glob("*.md")):
        (line,) = re.findall(r"^Total: .*$", path.read_text(encoding="utf-8"), re.M)
        if "provisional" in line:
            found["feedback"].add(path.stem)
    summary = out.with_name(f"{out.stem}-summary.md").read_text(encoding="utf-8")
    found["summary"] = set(re.findall(r"^\| `([^`]+)` \|.*\*\* provisional \|$", summary, re.M))
    return found


def _check(found: dict[str, dict[str, tuple[float, float | None]]]) -> None:
    shown = {where: {s: t for s, (t, _) in per.items()} for where, per in found.items()}
    for where, per in shown.items():
        assert per == pytest.approx(EXPECTED), f"{where}: {per} (everywhere: {shown})"
    for where, per in found.items():
        for student, (_, top) in per.items():
            assert top is None or top == pytest.approx(TOP), f"{where} {student}: points possible {top}"


def test_the_command_writes_one_total_per_student_everywhere(handed, tmp_path, capsys):
    sub, sheet = handed
    out, feedback = tmp_path / "out" / "grades.csv", tmp_path / "feedback"
    args = ["grade", str(sub), "-o", str(out), "--course", str(ROOT), "--exercise", EX1, "--exercise", EX2]
    args += ["--seed", "3", "--feedback", str(feedback), "--marks", str(sheet), "--sandbox", "none"]
    args += ["--gradebook", "canvas", "--gradebook", "moodle", "--gradebook", "wide", "--jobs", "1"]
    assert main(args) == 0
    said = capsys.readouterr()
    assert "written marks: 2 answers marked" in said.out
    assert "note: 1 written answer not marked yet" in said.err
    _check(totals_everywhere(out, feedback))
    assert provisional_everywhere(out, feedback) == dict.fromkeys(FILES, PROVISIONAL)


def test_python_grade_with_settings_writes_the_same_totals(handed, tmp_path):
    sub, sheet = handed
    out, feedback = tmp_path / "py" / "grades.csv", tmp_path / "py-feedback"
    settings = GradeSettings(
        submissions=sub,
        output=out,
        feedback=feedback,
        jobs=1,
        seed=3,
        sandbox="none",
        exercises=(EX1, EX2),
        gradebooks=("canvas", "moodle", "wide"),
        marks=(sheet,),
        bank=ROOT,
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        results = grade(settings)
    assert len(results) == 8
    _check(totals_everywhere(out, feedback))
    assert provisional_everywhere(out, feedback) == dict.fromkeys(FILES, PROVISIONAL)
