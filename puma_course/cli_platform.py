"""The ``puma-course`` command's learning-platform parts: ``grade --layout/--gradebook`` and ``gradescope``.

    puma-course grade SUBMISSIONS -o grades.csv [--layout folders|canvas|moodle]
                      [--gradebook canvas|moodle|wide ...] [--roster MOODLE-EXPORT.csv]
    puma-course gradescope EXERCISE -o autograder.zip [--course DIR]
    puma-course collect-written SUBMISSIONS -o DIR [--anonymise]   (see :mod:`puma_course.cli_written`)

Part of the ``cli`` layer (light to import: the grader is imported only when a command runs).
See :mod:`puma_course.grading.intake.collect`, :mod:`puma_course.grading.output.gradebook` and
:mod:`puma_course.grading.publish.gradescope`.
"""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from .cli_limits import add_limits_parser
from .cli_written import add_marks_argument, add_written_parser, check_marks, merge_marks

__all__ = ["add_grade_arguments", "add_gradescope_parser", "collect_or_explain", "write_gradebooks", "gradescope"]

LAYOUT_SHAPES = {
    "folders": "<student>/<exercise>.ipynb",
    "canvas": "flat files <name>[_LATE]_<user id>_<file id>_<exercise>.ipynb",
    "moodle": "<Full Name>_<participant id>_assignsubmission_file_/<exercise>.ipynb",
}


def add_grade_arguments(gr: argparse.ArgumentParser) -> None:
    """``--layout``, ``--gradebook``, ``--roster`` and ``--marks`` of ``puma-course grade``."""
    add_marks_argument(gr)
    gr.add_argument(
        "--layout",
        choices=tuple(LAYOUT_SHAPES),
        default="folders",
        help="how SUBMISSIONS is laid out: folders (<student>/<exercise>.ipynb, the default), canvas (the flat "
        "folder of Canvas's Download Submissions), moodle (Moodle's Download all submissions)",
    )
    gr.add_argument(
        "--gradebook",
        choices=("canvas", "moodle", "wide"),
        action="append",
        default=None,
        help="also write, next to the CSV, one row per student in this platform's grade-import format "
        "(repeatable): canvas, moodle or wide (a plain spreadsheet)",
    )
    gr.add_argument(
        "--roster",
        type=Path,
        default=None,
        metavar="CSV",
        help="Moodle's grade export (First name, Last name, ID number, Email address): the identifiers "
        "--gradebook moodle needs",
    )


def add_gradescope_parser(sub: Any, course: argparse.ArgumentParser) -> None:
    """The ``gradescope`` sub-command (and ``collect-written``, :mod:`puma_course.cli_written`; ``limits``,
    :mod:`puma_course.cli_limits`)."""
    add_written_parser(sub, course)
    add_limits_parser(sub)
    gs = sub.add_parser(
        "gradescope",
        parents=[course],
        help="build a Gradescope autograder zip for one exercise",
        description="Build autograder.zip (setup.sh, run_autograder, this package as a wheel, the course's bank) "
        "following Gradescope's autograder specification; upload it as the assignment's autograder.",
    )
    gs.add_argument("exercise", metavar="EXERCISE", help="the exercise, e.g. ex01_rotations")
    gs.add_argument("-o", "--output", type=Path, required=True, metavar="ZIP", help="the zip file to write")


def _student_folders(folder: Path) -> tuple[int, list[str]]:
    """How many student folders ``folder`` holds (sub-folders, and links, which grading refuses and reports),
    and the names of its entries. A student folder without the notebook is graded "missing", with the
    notebooks found under other names: feedback worth giving."""
    try:
        entries = sorted(e for e in os.listdir(folder) if not e.startswith("."))
    except OSError as exc:
        raise ValueError(f"submissions: expected a readable folder, got {str(folder)!r} ({exc.strerror})") from None
    found = sum(1 for e in entries if (folder / e).is_symlink() or (folder / e).is_dir())
    return found, entries


def collect_or_explain(args: argparse.Namespace, names: Sequence[str]) -> tuple[Any, bool]:
    """The platform download read as ``--layout`` says (None for folders), and False when it holds nothing to
    grade: no student folder (``folders``), no notebook of ``names`` (a platform's layout); said on stderr,
    with what the folder holds. The files of a download that are not graded are printed."""
    if not args.submissions.is_dir():
        raise ValueError(f"submissions: expected a folder, got {str(args.submissions)!r}")
    collected = None
    if args.layout == "folders":
        found, seen = _student_folders(args.submissions)
    else:
        from .grading.intake.collect import collect

        collected = collect(args.submissions, args.layout, list(names))
        found, seen = collected.notebooks(), collected.seen
        for line in collected.problems:
            print(f"not graded: {line}", file=sys.stderr)
    if args.layout == "folders":
        _suggest_layout(seen)
    if not found:
        shown = (", ".join(repr(n) for n in seen[:8]) + (" …" if len(seen) > 8 else "")) if seen else "nothing"
        print(
            f"puma-course grade: no {'student folder' if collected is None else 'notebook of ' + ', '.join(names)} "
            f"found in {str(args.submissions)!r} read as "
            f"--layout {args.layout} ({LAYOUT_SHAPES[args.layout]}); it holds: {shown}",
            file=sys.stderr,
        )
    return collected, bool(found)


def choose_and_collect(args: argparse.Namespace, course: Path, known: list[str]) -> tuple[list[str] | None, Any]:
    """The exercises ``grade`` grades and the platform download collected (None for ``folders``), or
    (None, None) when there is nothing to grade (said on stderr). Without ``--exercise``: the course's
    exercises that some student handed in; the others are named once, never graded as ``missing``."""
    from .grading.intake.submissions import exercises_to_grade

    names, collected = args.exercise, None
    if args.layout == "folders" and not collect_or_explain(args, names or [])[1]:
        return None, None  # no student folder: said, with what the folder holds
    absent: list[str] = []
    if not names:  # a platform's download is narrowed to what was handed in once collected, below
        handed = args.submissions if args.layout == "folders" else Path(os.devnull)
        names, unknown, absent = exercises_to_grade(course / "exercises", handed, known)
        if unknown:
            print(f"not graded (the grader has no questions for them): {', '.join(unknown)}", file=sys.stderr)
    if args.layout != "folders":
        collected, found = collect_or_explain(args, names)
        if not found:
            return None, None
        if not args.exercise:
            absent = [n for n in names if all(n not in s.files for s in collected.students)]
            names = [n for n in names if n not in absent]
    if absent:
        print(f"not graded (nobody handed them in; --exercise grades them): {', '.join(absent)}", file=sys.stderr)
    check_marks(args, names, collected)  # a bad marks file stops the command before anything is graded
    return list(names), collected


def open_limits(box: Any, timeout_cell: float = 10.0) -> Any:
    """A control group per notebook for this run (:func:`puma_course.grading.run.limits.open_run`), said on stderr:
    the limits in force and the clock each call is timed on, or loudly that they hold per process only."""
    from .grading.run import limits

    groups = limits.open_run()
    if groups.enforced:
        print(f"limits: {groups.label}; {limits.call_limit(groups, timeout_cell)}", file=sys.stderr)
        if groups.delegated and box.kind != "bwrap":  # the notebook runs as this user and sees /sys/fs/cgroup
            print(
                "WARNING: delegated groups without the sandbox: a notebook could move itself out of its group.",
                file=sys.stderr,
            )
        return groups
    print(
        f"WARNING: notebook limits are {groups.label}; {limits.call_limit(groups, timeout_cell)}.\n"
        "WARNING: a notebook's processes together may then use more memory, processes and CPU than one "
        "notebook's limits (README.md, Safety); the CSV's limits column says so.",
        file=sys.stderr,
    )
    if hasattr(os, "geteuid") and os.geteuid() != 0:
        print(
            "WARNING: root can give this user per-notebook groups: puma-course limits delegate --user NAME",
            file=sys.stderr,
        )
    if box.kind == "bwrap" and hasattr(os, "geteuid") and os.geteuid() == 0:
        print(
            "WARNING: grading as root without control groups: the per-process process limit is not enforced.",
            file=sys.stderr,
        )
    return groups


def _suggest_layout(seen: Sequence[str]) -> None:
    """Say so when a folder read as ``folders`` looks like a platform's download."""
    import re

    if any("_assignsubmission_" in n for n in seen):
        print("note: SUBMISSIONS looks like Moodle's download: grade it with --layout moodle", file=sys.stderr)
    elif any(re.match(r"^.*_\d+_\d+_.+\.ipynb$", n) for n in seen):
        print("note: SUBMISSIONS looks like Canvas's download: grade it with --layout canvas", file=sys.stderr)


def write_gradebooks(args: argparse.Namespace, results: Sequence[Any], names: Sequence[str], collected: Any) -> None:
    """Write each ``--gradebook`` next to the CSV, and say where, and what an import will lack."""
    from .grading.output.gradebook import read_roster, write_gradebook

    if collected is not None and collected.problems:
        print(f"{len(collected.problems)} file(s) of the download not graded (listed above and in the summary)")
    written = merge_marks(args, results)  # --marks: into the CSV and the feedback; the points for the gradebooks
    roster = read_roster(args.roster) if args.roster is not None else None
    for fmt in dict.fromkeys(args.gradebook or []):
        people = collected.by_key() if collected is not None else None
        path, notes = write_gradebook(fmt, args.output, results, names, people, roster, written)
        print(f"gradebook ({fmt}): {path}")
        for note in notes:
            print(f"  {note}", file=sys.stderr)


def gradescope(args: argparse.Namespace, course: Path) -> int:
    """``puma-course gradescope``: build the zip."""
    from .grading import EXERCISES, load_bank
    from .grading.publish.gradescope import build_autograder

    load_bank(course)  # the questions of the course the zip is built from (its bank/ goes into the zip)
    if args.exercise not in EXERCISES:
        raise ValueError(f"exercise: expected one of {sorted(EXERCISES)}, got {args.exercise!r}")
    report = build_autograder(course, args.exercise, args.output)
    print(report)
    return 0
