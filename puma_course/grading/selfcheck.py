"""The student's side: ``use_exercise(NAME)`` once, then ``check("qN", my_function)`` under each answer.

:func:`check` runs the question's *public* cases in the notebook's own process and prints the
same per-question line the grader's feedback and ``puma-course check`` print
(:func:`puma_course.grading.output.report.format_question`). Calling the package's own answer (the
question's answer key) fails a case here exactly as it does when graded.
"""

from __future__ import annotations

import copy
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from ..course import CourseNotFoundError
from .bank_loader import EXERCISES, BankNotFoundError
from .judge.verdict import Verdict, reconcile
from .output.report import format_question
from .plan import wire
from .results import score_question
from .run.events import call_verdict
from .run.worker import MAX_SIZE, as_numbers, describe, forbidden_codes, guarded_call, received, type_name
from .spec import Exercise, Question

__all__ = ["use_exercise", "check", "public_outcomes", "registry"]

_current_exercise: list[str] = []

#: What the self-check's points count: the public cases only (the grader adds hidden ones, and scores all alike).
PUBLIC_SCOPE = "on the public cases"

#: No time limit here: the words for one are never needed.
LIMITS = "10 s"


def registry() -> Mapping[str, Exercise]:
    """The exercises the self-check knows: the course's question bank, else a student edition's public cases.

    In the instructor's course the bank (``COURSE/bank/``) is found from the current folder; a student
    edition has none, and its package carries the public cases instead (:mod:`.publish.public`).
    """
    try:
        len(EXERCISES)
        return EXERCISES
    except (BankNotFoundError, CourseNotFoundError):
        from .publish import public

        if not public.available():
            raise
        return public.exercises()


def use_exercise(name: str) -> None:
    """Tell :func:`check` which exercise this notebook is (call once, in the first cell)."""
    known = registry()
    if name not in known:
        raise ValueError(f"name: expected one of {sorted(known)}, got {name!r}")
    _current_exercise[:] = [name]


def _find_question(question: str) -> tuple[Exercise, Question]:
    if not isinstance(question, str):
        raise ValueError(f"question: expected a question id such as 'q1', got {question!r}")
    exercises = registry()
    if ":" in question:
        ex_name, qid = question.split(":", 1)
    elif _current_exercise:
        ex_name, qid = _current_exercise[0], question
    else:
        hits = [(ex, q) for ex in exercises.values() for q in ex.questions if q.qid == question]
        if len(hits) != 1:
            raise ValueError(f"question: call use_exercise(NAME) first, or write 'NAME:{question}'")
        return hits[0]
    if ex_name not in exercises:
        raise ValueError(f"question: expected an exercise among {sorted(exercises)}, got {ex_name!r}")
    ex = exercises[ex_name]
    return ex, ex.question(qid)


def _short_repr(value: Any) -> str:
    """A short display of one argument: small arrays in full, larger ones by shape.

    >>> _short_repr([0.0, 1.0]), _short_repr(np.eye(3)), _short_repr(0.123456), _short_repr("x")
    ('[0., 1.]', '<array (3, 3)>', '0.1235', "'x'")
    """
    if isinstance(value, (np.ndarray, list)):
        arr = np.asarray(value, dtype=float)
        if arr.size <= 6:
            return np.array2string(arr, precision=3, separator=", ", suppress_small=True)
        return f"<array {arr.shape}>"
    if isinstance(value, float):
        return f"{value:.4g}"
    return repr(value)


def _event(answer: Callable[..., Any], args: tuple[Any, ...], codes: Any) -> dict[str, Any]:
    """What the grader's worker reports for one call of ``answer`` (see :mod:`.run.worker`), made here.

    The function receives the arguments as the worker hands them over (:func:`.plan.wire`, then
    :func:`.run.worker.received`: every list an array of floats), and what it returns is turned into
    numbers as the worker turns it (:func:`.run.worker.as_numbers`), so the grader's own wording
    (:func:`.run.events.call_verdict`) applies to both.
    """
    event: dict[str, Any] = {"kind": "call"}
    try:
        value, hit = guarded_call(answer, received(wire(args), np.asarray, float), codes)
    except NotImplementedError:
        event["error"] = "not-attempted"
    except Exception as exc:  # noqa: BLE001 - summarised for the student
        event["error"] = "raised"
        event["detail"], event["line"] = describe(exc)
    else:
        try:
            arr = as_numbers(value, np.asarray, float)
        except Exception as exc:  # noqa: BLE001 - a value that is not numbers
            event["error"], event["detail"] = "not-numbers", type_name(value)
            event["why"] = describe(exc)[0]
        else:
            if hit is not None:
                event["error"], event["detail"] = "answer-key", hit
            elif arr.size > MAX_SIZE:
                event["error"], event["size"] = "too-many", int(arr.size)
            else:
                event["value"] = arr.tolist()
    return event


def public_outcomes(q: Question, answer: Callable[..., Any]) -> list[tuple[str, str | None]]:
    """(label, reason or None when it passed) for each public case of ``q`` run on ``answer`` here.

    Each case is called and judged as the grader calls and judges it (:func:`_event`).
    """
    codes = forbidden_codes(q.forbidden)
    outcomes: list[tuple[str, Verdict]] = []
    for i, args in enumerate(q.public, start=1):
        label = f"case {i} ({q.function}({', '.join(_short_repr(a) for a in args)}))"
        expected = q.reference(*copy.deepcopy(args))
        if not callable(expected) and not isinstance(expected, dict):
            expected = np.asarray(expected, dtype=float)
        event = _event(answer, tuple(copy.deepcopy(args)), codes)
        outcomes.append((label, call_verdict(q, event, expected, tuple(args), LIMITS)))
    verdicts = reconcile([v for _, v in outcomes])  # a mistake named only if every failing case is that mistake
    return [(label, v.reason) for (label, _), v in zip(outcomes, verdicts, strict=True)]


def check(question: str, answer: Callable[..., Any]) -> None:
    """Run the public cases of ``question`` on the function ``answer`` and print its result line.

    ``question`` is ``"q2"`` (after :func:`use_exercise`) or ``"ex01_rotations:q2"``.
    Hidden cases used at grading time draw other inputs, so an answer that only
    memorises these cases will not earn the points. The points printed are the grader's rule (points × cases
    passed / cases) on the public cases, and say so.

    >>> check("ex01_rotations:q1", lambda axis, angle: np.eye(3))  # doctest: +ELLIPSIS
    q1 elementary_rotation: 0 / 2 points on the public cases - FAILED (0/5 cases pass; case 1 (...('-y', 0.4)): ...)
      Hint: Point your right thumb ...
    """
    ex, q = _find_question(question)
    if not callable(answer):
        got = type(answer).__name__
        print(format_question(q, 0.0, [f"expected your function {q.function}, got a {got}"], scope=PUBLIC_SCOPE))
        return
    earned, notes = score_question(q.points, public_outcomes(q, answer))  # the grader's rule, on these cases
    print(format_question(q, earned, notes, scope=PUBLIC_SCOPE))
