"""``puma-course merge``: the shard files of ``grade --shard K/N`` combined into one class's files.

    puma-course merge SHARD.json [SHARD.json ...] -o grades.csv [--course DIR] [--feedback DIR]
                      [--secret FILE | --seed N] [--marks FILE ...] [--gradebook canvas|moodle|wide ...]
                      [--roster MOODLE-EXPORT.csv] [--submissions DIR] [--quiet]

Writes the CSV, the feedback, the class summary and the gradebooks that one ``grade`` over the whole class
writes, row for row (:func:`puma_course.grading.merge.merge_shards`). Refuses (exit code 2, naming the files)
shards graded under different keys or course versions, split differently, overlapping or missing, and a key
other than theirs. Part of the ``cli`` layer: the grader is imported only when the command runs.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from .grade import report_written
from .options import add_class_files, add_key, add_quiet, course, say

__all__ = ["add_parser", "run"]


def add_parser(sub: Any, common: argparse.ArgumentParser) -> None:
    """The ``merge`` sub-command (``common``: the shared ``--course`` option)."""
    mg = sub.add_parser(
        "merge", parents=[common], help="combine the shard files of grade --shard K/N into one class's files"
    )
    mg.add_argument("shards", type=Path, nargs="+", metavar="SHARD", help="the shard files, one per part")
    add_class_files(mg)
    add_key(mg, "; the key grade used")
    mg.add_argument(
        "--submissions",
        type=Path,
        default=None,
        metavar="DIR",
        help="the platform download the shards graded (needed when they were graded with --layout canvas or moodle)",
    )
    add_quiet(mg)


def run(args: argparse.Namespace) -> int:
    """``puma-course merge``: 0, or 2 (shards that do not make one class, a wrong key, bad input)."""
    from ..grading import load_bank
    from ..grading.merge import merge_shards
    from ..grading.output.text import plural
    from ..grading.secret import SECRET_FILE, from_seed, load_secret

    root = course(args)
    load_bank(root)
    if args.seed is not None and args.secret is not None:
        raise ValueError(f"seed: expected either --secret FILE or --seed N, got both (--seed {args.seed})")
    key = from_seed(args.seed) if args.seed is not None else load_secret(args.secret or root / SECRET_FILE, False)
    results, files = merge_shards(
        args.shards,
        args.output,
        key,
        feedback=args.feedback,
        marks=args.marks or (),
        gradebooks=args.gradebook or (),
        roster=args.roster,
        submissions=args.submissions,
    )
    students = len({r.student for r in results})
    graded = f"{plural(len(results), 'notebook')} of {plural(students, 'student')}"
    say(args, f"merged {plural(len(args.shards), 'shard')}: {graded}; wrote {args.output}")
    report_written(args, files, None)  # as grade says it: the summary, the marks merged, each gradebook
    return 0
