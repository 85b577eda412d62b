"""The ``puma-course`` command's written questions: ``collect-written`` and ``grade --marks``.

    puma-course collect-written SUBMISSIONS -o DIR [--layout folders|canvas|moodle] [--exercise NAME ...]
                                [--anonymise] [--course DIR]
    puma-course grade SUBMISSIONS -o grades.csv --marks FILE [--marks FILE ...] [--feedback DIR] ...

``collect-written`` writes, per written question, a marking document and a marks template into DIR
(:mod:`puma_course.grading.output.marking`); ``grade --marks`` checks the filled-in files before grading
(exit code 2, naming the file, row and column of the first problem) and merges them into the grades CSV,
the gradebooks and the feedback once grading is done (:mod:`puma_course.grading.output.marks`).
Part of the ``cli`` layer: the grader is imported only when a command runs.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

__all__ = ["add_written_parser", "add_marks_argument", "collect_written", "check_marks", "merge_marks"]


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


def _students(args: argparse.Namespace, collected: Any) -> list[str]:
    if collected is not None:
        return [s.key for s in collected.students]
    from .grading.intake.submissions import scan

    return [s.name for s in scan(args.submissions)]


def check_marks(args: argparse.Namespace, names: Sequence[str], collected: Any) -> None:
    """Read and check ``--marks`` before grading (ValueError naming file, row and column); kept on ``args``."""
    args.written_marks = None
    if getattr(args, "marks", None):
        from .grading.output.marks import read_marks

        args.written_marks = read_marks(args.marks, _students(args, collected), list(names))


def merge_marks(args: argparse.Namespace, results: Sequence[Any]) -> Any:
    """Merge the checked marks into the CSV and the feedback; the written points for the gradebooks (or None)."""
    marks = getattr(args, "written_marks", None)
    if marks is None:
        return None
    from .grading.output.marks import merge_csv, merge_feedback, written_by_student
    from .grading.run.run_checks import reserved_stems

    merge_csv(args.output, marks, results)
    if args.feedback is not None:
        merge_feedback(args.feedback, results, marks, reserved=reserved_stems(args.output, args.feedback))
    marked = sum(1 for m in marks.marks.values() if m.points is not None)
    print(f"written marks: {marked} answer(s) marked, merged into {args.output}" + (
        f" and the feedback in {args.feedback}" if args.feedback is not None else ""))  # fmt: skip
    return written_by_student(marks, results)
