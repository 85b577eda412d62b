"""``puma-course gradescope``: a Gradescope autograder zip for one exercise.

    puma-course gradescope EXERCISE -o autograder.zip [--course DIR]

See :mod:`puma_course.grading.gradescope`. Part of the ``cli`` layer: the grader is imported only when the
command runs.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from .options import course

__all__ = ["add_parser", "run"]


def add_parser(sub: Any, common: argparse.ArgumentParser) -> None:
    """The ``gradescope`` sub-command (``common``: the shared ``--course`` option)."""
    gs = sub.add_parser(
        "gradescope",
        parents=[common],
        help="build a Gradescope autograder zip for one exercise",
        description="Build autograder.zip (setup.sh, run_autograder, this package as a wheel, the course's bank) "
        "following Gradescope's autograder specification; upload it as the assignment's autograder.",
    )
    gs.add_argument("exercise", metavar="EXERCISE", help="the exercise, e.g. ex01_rotations")
    gs.add_argument("-o", "--output", type=Path, required=True, metavar="ZIP", help="the zip file to write")


def run(args: argparse.Namespace) -> int:
    """``puma-course gradescope``: build the zip."""
    from ..grading import EXERCISES, load_bank
    from ..grading.publish.gradescope import build_autograder

    root = course(args)
    load_bank(root)  # the questions of the course the zip is built from (its bank/ goes into the zip)
    if args.exercise not in EXERCISES:
        raise ValueError(f"exercise: expected one of {sorted(EXERCISES)}, got {args.exercise!r}")
    report = build_autograder(root, args.exercise, args.output)
    print(report)
    return 0
