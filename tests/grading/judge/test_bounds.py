"""The grader's own work is bounded: forged or oversized answers fail their case in milliseconds (issue 21).

Findings: a notebook writing straight into the result pipe sent one answer per IK case holding 4,000 copies
of a right row; the solution-set judge built N x N x k arrays (90-376 s, 3.16 GB); a 2.25 MB line asked for
a 40 GiB array. And "each solution once" was checked to 1e-7 while solutions match to 1e-6, so the eight
PUMA solutions each listed twice, the copy moved 2e-7, passed ex09 q2.
"""

from __future__ import annotations

import json
import time
import tracemalloc

import numpy as np
import pytest

from puma_course.grading import EXERCISES
from puma_course.grading.judge.bounds import MAX_NUMBERS, check_answer, number_bound, shape_of
from puma_course.grading.results import NotebookResult
from puma_course.grading.run.child import ChildResult
from puma_course.grading.run.events import apply, call_verdict
from puma_course.grading.run.runner import make_plan

EX09 = EXERCISES["ex09_puma_ik"]


def _ik_plan() -> list[dict]:
    return [c for c in make_plan(EX09, seed=3) if c.qid == "q2"]


def _right(call: dict) -> np.ndarray:
    return np.array(EX09.question("q2").right_answer(*call.call_args), dtype=float)


def test_right_answers_still_pass():
    q = EX09.question("q2")
    for call in _ik_plan():
        event = {"value": _right(call).tolist()}
        assert call_verdict(q, event, call.expected, call.call_args, "10 s").passed


def test_each_solution_listed_twice_with_the_copy_moved_2e7_fails():
    q = EX09.question("q2")
    for call in _ik_plan():
        sols = _right(call)
        doubled = np.concatenate([sols, sols + 2e-7])
        verdict = call_verdict(q, {"value": doubled.tolist()}, call.expected, call.call_args, "10 s")
        assert not verdict.passed and verdict.mistake == "duplicates", verdict


def test_a_duplicate_within_the_match_tolerance_is_a_duplicate():
    """Duplicate and match tolerances agree: a row replaced by a copy of another moved 5e-7 is one solution twice."""
    q = EX09.question("q2")
    call = _ik_plan()[0]
    sols = _right(call).copy()
    sols[1] = sols[0] + np.array([5e-7, 0, 0, 0, 0, 0])
    verdict = call_verdict(q, {"value": sols.tolist()}, call.expected, call.call_args, "10 s")
    assert not verdict.passed and "same configuration" in verdict.reason, verdict


def test_forged_answers_with_4000_copies_fail_every_case_in_milliseconds():
    """The finding's notebook: one answer per IK case holding 4,000 copies of a right row, through the pipe."""
    plan = make_plan(EX09, seed=3)
    events = [{"kind": "ready"}]
    for call in plan:
        if call.qid == "q2":
            row = _right(call)[0].tolist()
            events.append({"kind": "call", "qid": "q2", "case": call.case, "value": [row] * 4000})
    # the events as the pipe carries them: each line within the 2 MB line cap
    assert all(len(json.dumps(e)) < 2_000_000 for e in events)
    result = NotebookResult.blank("forger", EX09)
    tracemalloc.start()
    t0 = time.perf_counter()
    apply(result, EX09, plan, ChildResult(events=events, done=True), timeout_cell=10, stop_note="")
    seconds = time.perf_counter() - t0
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    assert result.scores["q2"] == 0
    assert any("more numbers than the answer can have" in n for n in result.question_notes["q2"])
    assert seconds < 2.0, seconds  # generous: the bound, not the machine, is what is tested (ms in practice)
    assert peak < 50 << 20, peak


def test_a_line_asking_for_a_huge_array_is_refused_without_building_it():
    """2.25 MB of rows of 6 numbers: refused by counting, with no array built."""
    call = _ik_plan()[0]
    value = [[0.125] * 6] * 50_000
    t0 = time.perf_counter()
    why = check_answer(value, call.expected)
    assert why is not None and "more than" in why
    assert time.perf_counter() - t0 < 0.5


@pytest.mark.parametrize(
    ("value", "expected"),
    [
        ([[1.0, 2.0], [3.0]], "a ragged list (rows of different lengths)"),
        ([1.0, [2.0]], "a ragged list (rows of different lengths)"),
        ([[[[[1.0]]]]], "nested more than 4 levels deep"),
        ([1.0] * 65, "more than 64 numbers"),
        ([[1.0] * 8] * 8, (8, 8)),
        (3.5, ()),
        ("text", "not numbers"),
        ([True], "not numbers"),
    ],
)
def test_shape_of(value, expected):
    assert shape_of(value, 64) == expected


def test_number_bound_follows_the_reference_and_never_exceeds_the_worker_cap():
    assert number_bound(np.zeros((3, 3))) == 64
    assert number_bound(np.zeros((100, 100))) == MAX_NUMBERS
    call = _ik_plan()[0]
    k, n = np.asarray(call.expected["solutions"]).shape
    assert number_bound(call.expected) >= k * n
    # every question's right answer to every planned case is within its bound
    for ex in EXERCISES.values():
        for c in make_plan(ex, seed=5):
            q = ex.question(c.qid)
            right = q.right_answer(*c.call_args)
            value = np.asarray(right, dtype=float).tolist() if not callable(right) else None
            if value is not None:
                assert check_answer(value, c.expected) is None, (ex.name, q.qid, np.shape(right))


def test_judging_a_notebook_has_a_time_limit(monkeypatch):
    """Past the judging budget the remaining cases are not judged (failed), whatever the judges cost."""
    import puma_course.grading.run.events as ev

    monkeypatch.setattr(ev, "JUDGING_SECONDS", 0.0)
    plan = make_plan(EX09, seed=3)
    events = [{"kind": "call", "qid": c.qid, "case": c.case, "value": 0.0} for c in plan]
    result = NotebookResult.blank("slow", EX09)
    apply(result, EX09, plan, ChildResult(events=events, done=True), timeout_cell=10, stop_note="")
    assert result.score == 0
    assert all("not judged: judging this notebook" in notes[1] for notes in result.question_notes.values())
