"""Exercises: self-checks for students, release of the student versions, grading into a CSV.

One question bank, on the grader's side (:data:`EXERCISES`, filled from the course folder's
``bank/``, one file per exercise, loaded on first use or by :func:`load_bank`), serves three jobs:

* **Self-check** (student side, :mod:`.selfcheck`): in an exercise notebook,
  ``use_exercise("ex01_rotations")`` then ``check("q2", my_function)`` runs that question's
  *public* cases and prints its result line: passed, FAILED with the reasons and a hint, or
  "not attempted yet".
* **Release** (instructor side, :mod:`.release`): :func:`release` turns ``solutions/NAME.ipynb``
  into ``exercises/NAME.ipynb`` (stubs for solutions, hidden tests removed, points and headings
  written from the bank) and, with ``check_only``, says which exercises are out of date.
* **Grade** (instructor side, :mod:`.runner` and :mod:`.worker`): :func:`grade` runs every
  submitted notebook in its own fresh process, inside an operating-system sandbox where one is
  available (:mod:`.sandbox`), with time and resource limits, against a student-side
  ``puma_course`` that holds only what the exercise allows (:mod:`.student`: no answer key
  within reach); it calls the student's functions on inputs drawn at grading time, each
  student's own, from the instructor's secret key (:mod:`.secret`), brings
  back only the numbers they return, and compares them in the grader's process with the
  package's reference (:mod:`.compare`); :mod:`.report` writes the CSV and the feedback.

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
