"""``puma-course release``: the exercises generated from the solutions, or checked against them.

    puma-course release [--course DIR] [--solutions DIR] [--exercises DIR] [--check]

See :mod:`puma_course.grading.release`. Part of the ``cli`` layer: the grader is imported only when the command runs.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from .options import course

__all__ = ["add_parser", "run"]


def add_parser(sub: Any, common: argparse.ArgumentParser) -> None:
    """The ``release`` sub-command (``common``: the shared ``--course`` option)."""
    rel = sub.add_parser("release", parents=[common], help="generate exercises/ from solutions/")
    rel.add_argument(
        "--solutions",
        type=Path,
        default=None,
        metavar="DIR",
        help="solution notebooks (default: the course's solutions/)",
    )
    rel.add_argument(
        "--exercises",
        type=Path,
        default=None,
        metavar="DIR",
        help="where the student versions go (default: the course's exercises/)",
    )
    rel.add_argument("--check", action="store_true", help="write nothing; exit 1 if exercises/ is out of date")


def run(args: argparse.Namespace) -> int:
    """``puma-course release``: 0, or 1 when ``--check`` finds exercises/ out of date."""
    from ..grading import release
    from ..grading.output.text import plural

    if args.solutions is None or args.exercises is None:
        root = course(args)
        solutions = args.solutions if args.solutions is not None else root / "solutions"
        exercises = args.exercises if args.exercises is not None else root / "exercises"
    else:
        solutions, exercises = args.solutions, args.exercises
    if not solutions.is_dir():
        raise ValueError(
            f"solutions: expected a folder of solution notebooks, got {str(solutions)!r}, which "
            + ("is not a folder" if solutions.exists() else "does not exist")
        )
    changed = release(solutions, exercises, check_only=args.check)
    if args.check:
        if changed:
            print("exercises out of date (run `puma-course release`): " + ", ".join(changed), file=sys.stderr)
            return 1
        print(f"exercises are up to date ({exercises})")
        return 0
    wrote = f"wrote {plural(len(changed), 'exercise notebook')} to {exercises}"
    print(wrote + (": " + ", ".join(changed) if changed else ""))
    return 0
