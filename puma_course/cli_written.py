"""The ``puma-course`` command's written questions: ``collect-written`` and ``grade --marks``.

    puma-course collect-written SUBMISSIONS -o DIR [--layout folders|canvas|moodle] [--exercise NAME ...]
                                [--anonymise] [--course DIR]
    puma-course grade SUBMISSIONS -o grades.csv --marks FILE [--marks FILE ...] [--feedback DIR] ...

``collect-written`` writes, per written question, a marking document and a marks template into DIR
(:mod:`puma_course.grading.output.marking`); ``grade --marks`` hands the filled-in files to the grading
run (:class:`puma_course.grading.settings.GradeSettings`), which checks them before grading (exit code 2,
naming the file, row and column of the first problem) and merges them into the results before it writes
the grades CSV, the feedback, the summary and the gradebooks (:mod:`puma_course.grading.output.writer`).
Part of the ``cli`` layer: the grader is imported only when a command runs.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

__all__ = ["add_written_parser", "add_marks_argument", "collect_written", "say_marks"]


def add_written_parser(sub: Any, course: argparse.ArgumentParser) -> None:
    """The ``collect-written`` sub-command."""
    cw = sub.add_parser(
        "collect-written",
        parents=[course],
        help="gather the written answers into one marking file per question, with a marks template",
        description="Read the handed-in notebooks (as grade reads them) and write, per written question, a "
        "Markdown marking document (rubric, worked answer, every student's answer and sketches) and a marks "
        "template CSV to fill in and give to grade --marks.",
    )
    cw.add_argument("submissions", type=Path, metavar="SUBMISSIONS", help="the hand-in folder, as for grade")
    cw.add_argument("-o", "--output", type=Path, required=True, metavar="DIR", help="folder for the marking files")
    cw.add_argument(
        "--layout",
        choices=("folders", "canvas", "moodle"),
        default="folders",
        help="how SUBMISSIONS is laid out (as for grade; default folders)",
    )
    cw.add_argument(
        "--exercise",
        action="append",
        default=None,
        metavar="NAME",
        help="collect this exercise (repeatable; default: every exercise with written questions)",
    )
    cw.add_argument(
        "--anonymise",
        action="store_true",
        help="name students by a stable code (S-xxxxxxxx) instead of their names, for blind marking",
    )


def add_marks_argument(gr: argparse.ArgumentParser) -> None:
    """``--marks`` of ``puma-course grade``."""
    gr.add_argument(
        "--marks",
        type=Path,
        action="append",
        default=None,
        metavar="FILE",
        help="a filled-in marks file of collect-written (repeatable): merged into the CSV (written columns), "
        "the gradebooks and the feedback",
    )


def collect_written(args: argparse.Namespace, course: Path) -> int:
    """``puma-course collect-written``."""
    from .grading import load_bank
    from .grading.output.marking import collect_written as write

    load_bank(course)
    done = write(args.submissions, args.output, args.layout, args.exercise, args.anonymise)
    for line in done.problems:
        print(f"not read: {line}", file=sys.stderr)
    for (name, qid), count in done.answers.items():
        print(f"{name} {qid}: {count} written answer(s) (blank ones listed too) -> {args.output / f'{name}-{qid}.md'}")
    print(f"wrote {len(done.files)} file(s) to {args.output}; fill in the *-marks.csv files, then grade ... --marks")
    return 0


def say_marks(args: argparse.Namespace, files: Any) -> None:
    """Say how many written answers grade() merged (``--marks``), and where (the grading wrote them)."""
    if files.marked is None:
        return
    where = f" and the feedback in {args.feedback}" if args.feedback is not None else ""
    print(f"written marks: {files.marked} answer(s) marked, merged into {args.output}{where}")
