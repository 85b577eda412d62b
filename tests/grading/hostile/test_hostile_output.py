"""Hostile class layouts against the grader's own output files (issue 21).

Finding: with the CSV written into the feedback folder, a student folder named ``grades-summary`` had its
feedback replaced by the class summary (written with ``write_text``, not the atomic, link-safe write the CSV
and the feedback use). Here the summary never takes a student's feedback name, and a link planted where the
summary goes is replaced, never followed.
"""

from __future__ import annotations

import shutil
import warnings

import pytest

from puma_course.grading import grade
from puma_course.grading.output.summary import write_summary
from puma_course.grading.run.sandbox import choose
from tests.support import ROOT

pytestmark = pytest.mark.hostile


def _class(tmp_path):
    subs = tmp_path / "submissions"
    for student, folder in (("grades-summary", "solutions"), ("GRADES", "solutions"), ("blank", "exercises")):
        (subs / student).mkdir(parents=True)
        shutil.copy(ROOT / folder / "ex01_rotations.ipynb", subs / student)
    return subs


def test_summary_never_takes_a_students_feedback_name(tmp_path):
    subs, fb = _class(tmp_path), tmp_path / "feedback"
    out = fb / "grades.md"  # the CSV (named .md, even) and so the summary, inside the feedback folder
    outside = tmp_path / "elsewhere.md"
    outside.write_text("not the grader's\n", encoding="utf-8")
    fb.mkdir()
    (fb / "grades-summary.md").symlink_to(outside)  # planted: the summary must replace it, not write through it
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        results = grade(subs, out, feedback=fb, jobs=2, seed=1, exercises=["ex01_rotations"], sandbox=choose("none"))
    path, _ = write_summary(results, out)
    assert path == fb / "grades-summary.md" and not path.is_symlink()
    assert path.read_text(encoding="utf-8").startswith("# Class summary")
    assert outside.read_text(encoding="utf-8") == "not the grader's\n"
    titles = {p.name: p.read_text(encoding="utf-8").splitlines()[0] for p in fb.glob("*.md")}
    mine = [name for name, first in titles.items() if first == "# Feedback for `grades-summary`"]
    assert mine and mine[0] not in ("grades-summary.md", "grades.md"), titles
    theirs = [name for name, first in titles.items() if first == "# Feedback for `GRADES`"]
    assert theirs and theirs[0] != "grades.md", titles  # the CSV's name is reserved too (case-insensitively)
    assert out.read_text(encoding="utf-8").startswith("student,exercise,score")
    assert not list(fb.glob(".*.tmp")), list(fb.iterdir())
