"""The plan of a notebook's grading: every call to make (public and hidden cases) with its expected value.

Computed in the grader's process before any worker runs (:func:`make_plan`); the worker receives the
calls without ``expected`` or ``call_args`` (:func:`~.run.notebook_run._job`), and the grader judges what comes back
against them (:mod:`.events`).
"""

from __future__ import annotations

import copy
import json
import zlib
from dataclasses import dataclass
from typing import Any

import numpy as np

from .secret import Secret
from .spec import Exercise

__all__ = ["Call", "Plan", "make_plan", "wire"]


@dataclass(frozen=True)
class Call:
    """One planned call: question ``qid``'s case ``case`` calls ``function`` on ``args`` (JSON-ready).

    ``expected`` (what the reference returned) and ``call_args`` (the original arguments, for the
    judge) stay in the grader's process: :meth:`job` is what the worker receives.
    """

    qid: str
    case: int
    function: str
    args: list[Any]
    expected: Any
    call_args: tuple[Any, ...]

    def job(self) -> dict[str, Any]:
        """The call as the worker receives it: without ``expected`` or ``call_args``."""
        return {"qid": self.qid, "case": self.case, "function": self.function, "args": self.args}


Plan = list[Call]
"""A notebook's plan: its calls in order (public cases of each question first, then hidden ones)."""


def _jsonable(value: Any) -> Any:
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, (np.floating, np.integer)):
        return value.item()
    return value


def wire(args: tuple[Any, ...] | list[Any]) -> list[Any]:
    """A case's arguments as the worker reads them from its job line: JSON values (an array or tuple a list).

    >>> wire(("-y", np.float64(0.4), np.eye(2), (1.0, 2.0)))
    ['-y', 0.4, [[1.0, 0.0], [0.0, 1.0]], [1.0, 2.0]]
    """
    return list(json.loads(json.dumps([_jsonable(a) for a in args])))


def make_plan(exercise: Exercise, seed: int | Secret, student: str = "") -> Plan:
    """Every call to make (public + hidden cases) with its expected value, computed here.

    Each question draws its hidden inputs from its own generator (adding a question does not change
    the others'): with a :class:`~.secret.Secret` (:func:`grade`), seeded with HMAC-SHA256 of
    (``student``, exercise, question) under the key, so each student's are their own and nobody
    without the key can compute them; with an integer, everyone's, from ``seed`` and the question.

    >>> from puma_course.grading import EXERCISES
    >>> calls = make_plan(EXERCISES["ex01_rotations"], seed=1)
    >>> calls[0].qid, calls[0].function, calls[0].args, calls[0].expected.shape
    ('q1', 'elementary_rotation', ['-y', 0.4], (3, 3))

    ``expected`` is whatever the question's reference returns (an array for most questions; a
    question judged by equivalence may return what its judge needs) and ``call_args`` keeps the
    original arguments for the judge; neither ever reaches the student's process.
    """
    calls: Plan = []
    for q in exercise.questions:
        if isinstance(seed, Secret):
            rng = np.random.default_rng(seed.case_seed(student, exercise.name, q.qid))
        else:
            rng = np.random.default_rng([seed, zlib.crc32(f"{exercise.name}:{q.qid}".encode())])
        for case, args in enumerate(q.cases(rng)):
            expected = q.reference(*copy.deepcopy(args))
            if not callable(expected):
                expected = np.asarray(expected, dtype=float) if not isinstance(expected, dict) else expected
            calls.append(Call(q.qid, case, q.function, wire(args), expected, tuple(args)))
    return calls
