"""``puma-course check``: a student's own notebook graded on the public cases.

    puma-course check NOTEBOOK [--course DIR] [--exercise NAME] [--timeout-cell S] [--timeout-total S]

NOTEBOOK is a path, or the name of an exercise in the course's ``exercises/``. The questions come from the
course's bank, else (a student edition) from the edition's public cases (:mod:`puma_course.grading.public`).
Part of the ``cli`` layer: the grader is imported only when the command runs.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from ..course import CourseNotFoundError, find_course
from .options import add_timeouts, course

__all__ = ["add_parser", "run", "notebook_of"]


def add_parser(sub: Any, common: argparse.ArgumentParser) -> None:
    """The ``check`` sub-command (``common``: the shared ``--course`` option)."""
    ck = sub.add_parser("check", parents=[common], help="grade your own notebook on the public cases")
    ck.add_argument(
        "notebook",
        type=Path,
        metavar="NOTEBOOK",
        help="the notebook: a path, or the name of an exercise in the course's exercises/ (e.g. ex01_rotations)",
    )
    ck.add_argument(
        "--exercise", default=None, metavar="NAME", help="exercise name (default: the notebook's file name)"
    )
    add_timeouts(ck)


def notebook_of(args: argparse.Namespace) -> Path:
    """The notebook ``check`` grades: the path as given, else an exercise of the course by name."""
    given: Path = args.notebook
    if given.is_file():
        return given
    if given.exists():
        raise ValueError(f"notebook: expected a notebook file, got {str(given)!r}, which is a folder")
    if len(given.parts) != 1:
        raise ValueError(f"notebook: expected a notebook file, got {str(given)!r}, which does not exist")
    try:
        folder = course(args) / "exercises"
    except CourseNotFoundError as exc:
        raise ValueError(
            f"notebook: expected a notebook file or an exercise of a course, got {str(given)!r}: "
            f"no such file here, and no course to look in ({exc})"
        ) from None
    tried = [folder / given.name] + ([] if given.suffix == ".ipynb" else [folder / f"{given.name}.ipynb"])
    for path in tried:
        if path.is_file():
            return path
    raise ValueError(
        f"notebook: expected a notebook file or an exercise of the course, got {str(given)!r}; "
        f"looked for {', '.join(repr(str(p)) for p in [given, *tried])}"
    )


def run(args: argparse.Namespace) -> int:
    """``puma-course check``: 0 when the notebook ran (its score printed), 1 when it did not, 2 on bad input."""
    from ..grading import BankNotFoundError, format_check_report, grade_notebook, load_bank
    from ..grading.publish import public as public_cases

    notebook = notebook_of(args)
    name = args.exercise or notebook.stem
    try:  # the bank of the course the notebook is in (or --course, or the one run in), else an edition's public cases
        known: Any = load_bank(course(args) if args.course else find_course(notebook.parent, fallback=True))
    except (BankNotFoundError, CourseNotFoundError):
        if not public_cases.available():
            raise
        known = public_cases.exercises()
    if name not in known:
        print(f"check: unknown exercise {name!r}; use --exercise with one of {sorted(known)}", file=sys.stderr)
        return 2
    ex = known[name]
    public = public_cases.public_cases_only(ex)  # every other field (answer-key tripwires, bonus flags) as graded
    r = grade_notebook(notebook, public, seed=0, timeout_cell=args.timeout_cell, timeout_total=args.timeout_total)
    print(format_check_report(r, ex))
    return 0 if r.status in ("ok", "cell-error") else 1
