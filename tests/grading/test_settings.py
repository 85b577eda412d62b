"""GradeSettings: one typed value for a grading run; bad values refused by name; the key and sandbox chosen once.

* a bad layout, gradebook, sandbox or exercise list is a ValueError naming the argument, what was expected and
  what came; ``grade(settings, <keywords>)`` is refused (one way to say a run, not two merged silently);
* ``grade(settings)`` reads and checks the marks before anything runs: a bad marks file writes nothing;
* ``puma-course grade --seed N`` derives the key once and chooses the sandbox once (counted by wrapping the
  functions that do it), and grades with the bank of the course it names.
"""

from __future__ import annotations

import csv
import shutil
import warnings
from pathlib import Path

import pytest

from puma_course.cli import main
from puma_course.grading import grade
from puma_course.grading import secret as secret_module
from puma_course.grading.run import runner
from puma_course.grading.run import sandbox as sandbox_module
from puma_course.grading.settings import GradeSettings
from tests.support import ROOT

EX = "ex01_rotations"


@pytest.mark.parametrize(
    ("given", "said"),
    [
        ({"layout": "blackboard"}, "layout: expected one of folders, canvas, moodle, got 'blackboard'"),
        ({"gradebooks": ["canvas", "excel"]}, "gradebook: expected one of canvas, moodle, wide, got 'excel'"),
        ({"sandbox": "docker"}, "sandbox: expected one of"),
        ({"exercises": EX}, "exercises: expected a list of exercise names, got the string"),
    ],
)
def test_bad_settings_are_refused_by_name(given, said):
    with pytest.raises(ValueError, match=said):
        GradeSettings("hand-in", "grades.csv", **given)


def test_settings_are_typed_and_frozen():
    s = GradeSettings("hand-in", "out/g.csv", feedback="fb", marks=["m.csv"], gradebooks=["wide", "wide"])
    assert s.submissions == Path("hand-in") and s.feedback == Path("fb") and s.marks == (Path("m.csv"),)
    assert s.gradebooks == ("wide",)  # asked twice, written once
    with pytest.raises(AttributeError):
        s.jobs = 4  # type: ignore[misc]


def test_settings_and_keywords_together_are_refused(tmp_path):
    s = GradeSettings(tmp_path, tmp_path / "g.csv", sandbox="none")
    with pytest.raises(ValueError, match="either a GradeSettings alone or the keyword arguments"):
        grade(s, jobs=4)


def test_a_bad_marks_file_given_to_grade_writes_nothing(tmp_path):
    (tmp_path / "hand-in" / "ann").mkdir(parents=True)
    shutil.copy(ROOT / "solutions" / f"{EX}.ipynb", tmp_path / "hand-in" / "ann" / f"{EX}.ipynb")
    bad = tmp_path / "marks.csv"
    with open(bad, "w", newline="", encoding="utf-8") as fh:
        csv.writer(fh).writerows([["student", "exercise", "question", "points"], ["dora", EX, "q9", "1"]])
    out = tmp_path / "out" / "g.csv"
    s = GradeSettings(tmp_path / "hand-in", out, seed=1, sandbox="none", exercises=[EX], marks=[bad], bank=ROOT)
    with pytest.raises(ValueError, match="row 2, column 'student'"):
        grade(s)
    assert not out.parent.exists()  # nothing graded, nothing written


def test_the_command_derives_the_key_once_and_chooses_the_sandbox_once(tmp_path, monkeypatch):
    calls = {"from_seed": 0, "choose": 0}
    real_seed, real_choose = secret_module.from_seed, sandbox_module.choose

    def from_seed(seed):
        calls["from_seed"] += 1
        return real_seed(seed)

    def choose(mode="auto", **kw):
        calls["choose"] += 1
        return real_choose(mode, **kw)

    monkeypatch.setattr(secret_module, "from_seed", from_seed)
    monkeypatch.setattr(sandbox_module, "choose", choose)
    monkeypatch.setattr(runner, "choose", choose)
    (tmp_path / "hand-in" / "ann").mkdir(parents=True)
    shutil.copy(ROOT / "solutions" / f"{EX}.ipynb", tmp_path / "hand-in" / "ann" / f"{EX}.ipynb")
    out = tmp_path / "g.csv"
    args = ["grade", str(tmp_path / "hand-in"), "-o", str(out), "--course", str(ROOT), "--exercise", EX]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert main([*args, "--seed", "5", "--sandbox", "none", "--quiet"]) == 0
    assert calls == {"from_seed": 1, "choose": 1}
    with open(out, newline="", encoding="utf-8") as fh:
        (row,) = list(csv.DictReader(fh))
    assert row["seed"] == "5" and float(row["score"]) == float(row["max_score"]) == 15
