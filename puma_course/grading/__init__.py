"""Exercises: self-checks for students, release of the student versions, grading into a CSV.

One question bank, on the grader's side (:data:`EXERCISES`, :mod:`.bank_loader`, filled from the course
folder's ``bank/``, one file per exercise declaring its questions (:mod:`.spec`), loaded on first use or by
:func:`load_bank`), serves three jobs:

* **Self-check** (student side, :mod:`.selfcheck`): in an exercise notebook,
  ``use_exercise("ex01_rotations")`` then ``check("q2", my_function)`` runs that question's
  *public* cases and prints its result line: passed, FAILED with the reasons and a hint, or
  "not attempted yet". A student edition has no bank: it reads the public cases as data
  (:mod:`.publish.public`).
* **Release** (instructor side, :mod:`.publish.release`): :func:`release` turns ``solutions/NAME.ipynb``
  into ``exercises/NAME.ipynb`` (stubs for solutions, hidden tests removed, points and headings
  written from the bank) and, with ``check_only``, says which exercises are out of date. :mod:`.publish`
  also writes the student edition and the Gradescope autograder.
* **Grade** (instructor side, :mod:`.run.runner` and :mod:`.run.worker`): :func:`grade` reads the
  submissions without trusting them (:mod:`.intake`), runs every submitted notebook in its own fresh
  process, inside an operating-system sandbox where one is available (:mod:`.run.sandbox`), with time
  and resource limits (:mod:`.run.limits`), against a student-side ``puma_course`` that holds only what
  the exercise allows (:mod:`.run.student`: no answer key within reach); it calls the student's
  functions on inputs drawn at grading time, each student's own, from the instructor's secret key
  (:mod:`.secret`), brings back only the numbers they return, and judges them in the grader's process
  against the package's reference (:mod:`.judge`, each a :class:`~.judge.verdict.Verdict`), scoring
  them into a :class:`NotebookResult` (:mod:`.results`); :mod:`.output.report` writes the CSV and the
  feedback, :mod:`.output` the class summary and the gradebooks.

Deleting or editing tests in a submitted notebook changes nothing: the questions live in the
instructor's course folder.
"""

from __future__ import annotations

from .bank_loader import EXERCISES, BankNotFoundError, load_bank
from .output.report import format_check_report
from .publish.release import release, release_notebook
from .results import NotebookResult
from .run.runner import GradingIntegrityWarning, SandboxWarning, grade, grade_notebook
from .selfcheck import check, use_exercise
from .spec import Exercise, Question

__all__ = [
    "EXERCISES",
    "load_bank",
    "BankNotFoundError",
    "Exercise",
    "Question",
    "NotebookResult",
    "GradingIntegrityWarning",
    "SandboxWarning",
    "use_exercise",
    "check",
    "release",
    "release_notebook",
    "grade",
    "grade_notebook",
    "format_check_report",
]
