"""Planning a class: each notebook's expected values drawn when it is graded, in the worker pool, and dropped after.

``make_plan`` is instrumented in the runner (monkeypatch): what it is called with and when, and how many of the
plans it returned are still alive (a list subclass with a finaliser). Before issue 33 every plan of the class
was made before the first notebook ran and all were held until the class was done: with one job, the second
student's plans came before the first student's notebooks, and the live plans were students x exercises.
"""

from __future__ import annotations

import shutil
import threading
import time
import warnings
import weakref
from pathlib import Path

import pytest

from puma_course.grading import EXERCISES, grade
from puma_course.grading.plan import Plan
from puma_course.grading.run import runner
from puma_course.grading.secret import choose_key
from tests.support import ROOT

# CI's second pass (another OpenBLAS kernel) leaves this out: when plans are made, not what they hold
pytestmark = pytest.mark.no_numerics

NAMES = ["ex01_rotations", "ex02_dh_frames"]


class _Tracked(list):  # a plan that can be watched (a plain list takes no weak reference)
    pass


class _Spy:
    """``make_plan`` as the runner calls it, logging each call and counting the plans still referenced."""

    def __init__(self, fail_for: str | None = None) -> None:
        self.log: list[tuple[str, str, str]] = []
        self.live = self.peak = 0
        self.inside = self.most_inside = 0
        self.pause = 0.0
        self.fail_for = fail_for
        self._lock = threading.Lock()
        self._real = runner.make_plan

    def _gone(self) -> None:
        with self._lock:
            self.live -= 1

    def __call__(self, exercise, seed, student=""):
        if student == self.fail_for:
            raise RuntimeError(f"no cases for {student}")
        with self._lock:
            self.inside += 1
            self.most_inside = max(self.most_inside, self.inside)
        time.sleep(self.pause)
        plan = _Tracked(self._real(exercise, seed, student))
        with self._lock:
            self.inside -= 1
        with self._lock:
            self.log.append(("plan", student, exercise.name))
            self.live += 1
            self.peak = max(self.peak, self.live)
        weakref.finalize(plan, self._gone)
        return plan


def _class(tmp_path: Path, students: list[str]) -> Path:
    subs = tmp_path / "subs"
    for s in students:
        (subs / s).mkdir(parents=True)
        for name in NAMES:
            shutil.copy(ROOT / "solutions" / f"{name}.ipynb", subs / s)
    return subs


def _grade(subs: Path, out: Path, spy: _Spy, jobs: int, monkeypatch) -> list:
    monkeypatch.setattr(runner, "make_plan", spy)

    def done(r) -> None:
        with spy._lock:
            spy.log.append(("done", r.student, r.exercise))

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return grade(subs, out, exercises=NAMES, jobs=jobs, seed=5, sandbox="none", progress=done, cgroups=False)


def test_a_students_plans_are_made_when_that_student_is_graded(tmp_path, monkeypatch):
    spy = _Spy()
    results = _grade(_class(tmp_path, ["s1", "s2", "s3"]), tmp_path / "g.csv", spy, 1, monkeypatch)
    assert [r.status for r in results] == ["ok"] * 6 and all(r.score == r.max_score for r in results)
    # one job: each notebook planned, then graded, one after the other, student after student
    expected = [(what, s, n) for s in ("s1", "s2", "s3") for n in NAMES for what in ("plan", "done")]
    assert spy.log == expected
    assert spy.peak == 1 and spy.live == 0  # each plan dropped once its notebook is judged


def test_the_live_plans_are_bounded_by_the_jobs_not_the_class(tmp_path, monkeypatch):
    spy = _Spy()
    spy.pause = 0.2  # a slow plan: two threads would be inside make_plan at once, were it not for the lock
    students = [f"s{k}" for k in range(6)]
    results = _grade(_class(tmp_path, students), tmp_path / "g.csv", spy, 2, monkeypatch)
    assert len(results) == 12 and {r.status for r in results} == {"ok"}
    assert sorted(e[1:] for e in spy.log if e[0] == "plan") == [(s, n) for s in students for n in NAMES]
    assert 1 <= spy.peak <= 2 and spy.live == 0
    # one plan at a time (the bank's warnings.catch_warnings is not thread-safe), the notebooks still in parallel
    assert spy.most_inside == 1
    for s in students:  # a notebook is planned before it is graded, by the thread that grades it
        for n in NAMES:
            assert spy.log.index(("plan", s, n)) < spy.log.index(("done", s, n))


def test_a_plan_that_cannot_be_made_is_a_grader_error_on_that_students_notebooks_only(tmp_path, monkeypatch):
    spy = _Spy(fail_for="s2")
    results = _grade(_class(tmp_path, ["s1", "s2", "s3"]), tmp_path / "g.csv", spy, 2, monkeypatch)
    by = {(r.student, r.exercise): r for r in results}
    for n in NAMES:
        bad = by["s2", n]
        assert bad.status == "grader-error" and bad.score == 0
        assert bad.notes == ["the grader could not draw this notebook's cases: RuntimeError: no cases for s2"]
        for s in ("s1", "s3"):
            assert by[s, n].status == "ok" and by[s, n].score == by[s, n].max_score
    assert "grader-error" in (tmp_path / "g.csv").read_text(encoding="utf-8")


def test_a_missing_or_unread_notebook_is_not_planned(tmp_path, monkeypatch):
    subs = _class(tmp_path, ["s1"])
    (subs / "s1" / "ex02_dh_frames.ipynb").unlink()
    spy = _Spy()
    results = _grade(subs, tmp_path / "g.csv", spy, 1, monkeypatch)
    assert [r.status for r in results] == ["ok", "missing"]
    assert [e for e in spy.log if e[0] == "plan"] == [("plan", "s1", "ex01_rotations")]


def test_the_plans_are_the_ones_make_plan_gives_for_the_key_student_and_exercise(tmp_path, monkeypatch):
    seen: dict[tuple[str, str], Plan] = {}
    real = runner.make_plan

    def keep(exercise, seed, student=""):
        plan = real(exercise, seed, student)
        seen[student, exercise.name] = plan
        return plan

    monkeypatch.setattr(runner, "make_plan", keep)
    subs = _class(tmp_path, ["s1", "s2"])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        grade(subs, tmp_path / "g.csv", exercises=NAMES, jobs=2, seed=5, sandbox="none", cgroups=False)
    key = choose_key(None, 5)
    for (s, n), plan in seen.items():  # the same draws whichever thread made them, in whichever order
        assert [c.args for c in plan] == [c.args for c in real(EXERCISES[n], key, s)]
    assert [c.args for c in seen["s1", NAMES[0]]] != [c.args for c in seen["s2", NAMES[0]]]


def test_without_the_sandbox_only_pre_read_bytes_are_read_ahead(tmp_path, monkeypatch):
    # no OS sandbox: notebooks are read before any student code runs, up to PRE_READ_BYTES; the rest as graded
    subs = _class(tmp_path, [f"s{k}" for k in range(5)])
    one = sum(p.stat().st_size for p in (subs / "s0").iterdir())
    monkeypatch.setattr(runner, "PRE_READ_BYTES", 2 * one)  # two students' notebooks fit, a third does not
    spy, real_read = _Spy(), runner.read_student

    def read(*args, **kwargs):
        spy.log.append(("read", args[1].name, ""))
        return real_read(*args, **kwargs)

    monkeypatch.setattr(runner, "read_student", read)
    results = _grade(subs, tmp_path / "g.csv", spy, 1, monkeypatch)
    assert [r.status for r in results] == ["ok"] * 10
    first_plan = next(i for i, e in enumerate(spy.log) if e[0] == "plan")
    # s0 and s1 kept; s2 read, found beyond the budget and dropped; then s2, s3, s4 each read when graded
    assert [e[1] for e in spy.log[:first_plan]] == ["s0", "s1", "s2"]
    assert [e[1] for e in spy.log[first_plan:] if e[0] == "read"] == ["s2", "s3", "s4"]
