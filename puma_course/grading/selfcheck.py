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
from .model import EXERCISES, BankNotFoundError, Exercise, Question, Verdict, key_words, reconcile, score_question
from .output.report import format_question
from .run.worker import NOT_ATTEMPTED, forbidden_codes, guarded_call

__all__ = ["use_exercise", "check", "public_outcomes", "registry"]

_current_exercise: list[str] = []


def registry() -> Mapping[str, Exercise]:
    """The exercises the self-check knows: the course's question bank, else a student edition's public cases.

    In the instructor's course the bank (``COURSE/bank/``) is found from the current folder; a student
    edition has none, and its package carries the public cases instead (:mod:`.public`).
    """
    try:
        len(EXERCISES)
        return EXERCISES
    except (BankNotFoundError, CourseNotFoundError):
        from . import public

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


def public_outcomes(q: Question, answer: Callable[..., Any]) -> list[tuple[str, str | None]]:
    """(label, reason or None when it passed) for each public case of ``q`` run on ``answer`` here."""
    codes = forbidden_codes(q.forbidden)
    outcomes: list[tuple[str, Verdict]] = []
    for i, args in enumerate(q.public, start=1):
        label = f"case {i} ({q.function}({', '.join(_short_repr(a) for a in args)}))"
        expected = q.reference(*copy.deepcopy(args))
        if not callable(expected) and not isinstance(expected, dict):
            expected = np.asarray(expected, dtype=float)
        reason: str | None = None
        verdict: Verdict | None = None
        try:
            got, hit = guarded_call(answer, copy.deepcopy(args), codes)
        except NotImplementedError:
            reason = f"{NOT_ATTEMPTED} (NotImplementedError)"
        except Exception as exc:  # noqa: BLE001 - summarised for the student
            reason = f"raised {type(exc).__name__}: {str(exc)[:200]}"
        else:
            if hit is not None:
                reason = key_words(hit)
            else:
                try:
                    verdict = q.judge(got, expected, tuple(args))
                except Exception as exc:  # noqa: BLE001 - a bizarre value must not stop the check
                    reason = f"could not compare the value ({type(exc).__name__})"
        outcomes.append((label, verdict if verdict is not None else Verdict(reason)))
    verdicts = reconcile([v for _, v in outcomes])  # a mistake named only if every failing case is that mistake
    return [(label, v.reason) for (label, _), v in zip(outcomes, verdicts, strict=True)]


def check(question: str, answer: Callable[..., Any]) -> None:
    """Run the public cases of ``question`` on the function ``answer`` and print its result line.

    ``question`` is ``"q2"`` (after :func:`use_exercise`) or ``"ex01_rotations:q2"``.
    Hidden cases used at grading time draw other inputs, so an answer that only
    memorises these cases will not earn the points.

    >>> check("ex01_rotations:q1", lambda axis, angle: np.eye(3))  # doctest: +ELLIPSIS
    q1 elementary_rotation: 0 / 2 points - FAILED (0/4 cases pass; case 1 (elementary_rotation('-y', 0.4)): ...)
      Hint: Point your right thumb ...
    """
    ex, q = _find_question(question)
    if not callable(answer):
        got = type(answer).__name__
        print(format_question(q, 0.0, [f"expected your function {q.function}, got a {got}"]))
        return
    earned, notes = score_question(q.points, public_outcomes(q, answer))
    print(format_question(q, earned, notes))
