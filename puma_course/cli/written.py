"""``puma-course collect-written``: the written answers gathered for marking by hand.

    puma-course collect-written SUBMISSIONS -o DIR [--layout folders|canvas|moodle] [--exercise NAME ...]
                                [--anonymise] [--course DIR] [--quiet]

It writes, per written question, a marking document and a marks template into DIR
(:mod:`puma_course.grading.output.marking`); the filled-in templates go to ``grade --marks``
(:mod:`puma_course.cli.grade`). Part of the ``cli`` layer: the grader is imported only when the command runs.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from .options import add_exercises, add_layout, add_quiet, course, say

__all__ = ["add_parser", "run"]


def add_parser(sub: Any, common: argparse.ArgumentParser) -> None:
    """The ``collect-written`` sub-command (``common``: the shared ``--course`` option)."""
    cw = sub.add_parser(
        "collect-written",
        parents=[common],
        help="gather the written answers into one marking file per question, with a marks template",
        description="Read the handed-in notebooks (as grade reads them) and write, per written question, a "
        "Markdown marking document (rubric, worked answer, every student's answer and sketches) and a marks "
        "template CSV to fill in and give to grade --marks.",
    )
    cw.add_argument("submissions", type=Path, metavar="SUBMISSIONS", help="the hand-in folder, as for grade")
    cw.add_argument("-o", "--output", type=Path, required=True, metavar="DIR", help="folder for the marking files")
    add_layout(cw, "how SUBMISSIONS is laid out (as for grade; default folders)")
    add_exercises(cw, "collect this exercise (repeatable; default: every exercise with written questions)")
    cw.add_argument(
        "--anonymise",
        action="store_true",
        help="name students by a stable code (S-xxxxxxxx) instead of their names, for blind marking",
    )
    add_quiet(cw)


def run(args: argparse.Namespace) -> int:
    """``puma-course collect-written``."""
    from ..grading import load_bank
    from ..grading.output.marking import collect_written as write
    from ..grading.output.text import plural

    load_bank(course(args))
    done = write(args.submissions, args.output, args.layout, args.exercise, args.anonymise)
    for line in done.problems:
        print(f"not read: {line}", file=sys.stderr)
    for (name, qid), rows in done.rows.items():
        answered = done.answers[name, qid]
        sheet, doc = args.output / f"{name}-{qid}-marks.csv", args.output / f"{name}-{qid}.md"
        who = f"{plural(rows, 'student')} who handed {name} in: {answered} answered, {rows - answered} blank"
        say(args, f"{name} {qid}: {plural(rows, 'row')} in {sheet} ({who}); their answers in {doc}")
    files = f"{plural(len(done.rows), 'marking document')} and {plural(len(done.rows), 'marks template')}"
    to_fill = plural(sum(done.rows.values()), "row")
    say(args, f"wrote {files} to {args.output}; fill in the {to_fill} of the *-marks.csv files, then grade ... --marks")
    return 0
