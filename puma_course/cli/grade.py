"""``puma-course grade``: a class graded into a CSV, feedback, a summary and the platforms' gradebooks.

    puma-course grade SUBMISSIONS -o grades.csv [--course DIR] [--feedback DIR] [--jobs N]
                      [--timeout-cell S] [--timeout-total S] [--timeout-student S] [--secret FILE | --seed N]
                      [--sandbox auto|bwrap|none] [--exercise NAME ...] [--quiet]
                      [--marks FILE ...] [--layout folders|canvas|moodle]
                      [--gradebook canvas|moodle|wide ...] [--roster MOODLE-EXPORT.csv]
                      [--shard K/N [--shard-file FILE]]

Without ``--exercise`` it grades the course's exercises that some student handed in. ``--marks`` (the filled-in
files of ``collect-written``) are checked before grading (exit code 2, naming the file, row and column of the
first problem) and merged into the results before anything is written, so the CSV, the feedback, the summary
and every gradebook give the same totals (:class:`puma_course.grading.settings.GradeSettings`,
:mod:`puma_course.grading.output.writer`). Exit code 3 when the package changed during grading.
Part of the ``cli`` layer (light to import: the grader is imported only when the command runs).
See :mod:`puma_course.grading.run.collect`, :mod:`puma_course.grading.output.gradebook`.
"""

from __future__ import annotations

import argparse
import contextlib
import dataclasses
import os
import sys
import threading
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from .help import drop_stdout
from .options import (
    LAYOUT_SHAPES,
    add_class_files,
    add_exercises,
    add_key,
    add_layout,
    add_quiet,
    add_timeouts,
    course,
    say,
)

__all__ = [
    "add_parser",
    "run",
    "collect_or_explain",
    "choose_and_collect",
    "open_limits",
    "grade_settings",
    "report_written",
]


def add_parser(sub: Any, common: argparse.ArgumentParser) -> None:
    """The ``grade`` sub-command and every one of its options (``common``: the shared ``--course`` option)."""
    gr = sub.add_parser("grade", parents=[common], help="grade SUBMISSIONS/<student>/<exercise>.ipynb")
    gr.add_argument(
        "submissions",
        type=Path,
        metavar="SUBMISSIONS",
        help="folder with one sub-folder per student holding <exercise>.ipynb (or a platform download: --layout)",
    )
    add_class_files(gr)
    gr.add_argument("--jobs", type=int, default=2, metavar="N", help="notebooks graded at the same time (default 2)")
    add_timeouts(gr)
    gr.add_argument(
        "--timeout-student",
        type=float,
        default=120.0,
        metavar="S",
        help="seconds for all of one student's notebooks together (default 120)",
    )
    add_key(gr)
    gr.add_argument(
        "--sandbox",
        choices=("auto", "bwrap", "none"),
        default="auto",
        help="run each notebook inside bubblewrap (bwrap: required; auto, the default: when it works here, "
        "else warn loudly; none: never)",
    )
    add_exercises(gr, "grade this exercise (repeatable; default: the course's exercises that some student handed in)")
    add_quiet(gr)
    add_layout(
        gr,
        "how SUBMISSIONS is laid out: folders (<student>/<exercise>.ipynb, the default), canvas (the flat "
        "folder of Canvas's Download Submissions), moodle (Moodle's Download all submissions)",
    )
    gr.add_argument(
        "--shard",
        default=None,
        metavar="K/N",
        help="grade only part K of N of the class (a stable split by student name) and write a shard file for "
        "puma-course merge (Slurm job arrays, Kubernetes Indexed Jobs: docs/scaling.md)",
    )
    gr.add_argument(
        "--shard-file",
        type=Path,
        default=None,
        metavar="FILE",
        help="where --shard writes its shard file (default: <CSV stem>.shard.json beside the CSV)",
    )


def run(args: argparse.Namespace) -> int:
    """``puma-course grade``: 0, 1 (a notebook could not be graded), 2 (bad input) or 3 (the package changed)."""
    import warnings

    from ..grading import EXERCISES, GradingIntegrityWarning, SandboxWarning, load_bank
    from ..grading.output.summary import run_outcome
    from ..grading.output.text import plural
    from ..grading.run.runner import LimitsWarning, grade_run

    root = course(args)
    load_bank(root)  # the questions of the course being graded (its bank/, beside solutions/)
    names, collected = choose_and_collect(args, root, list(EXERCISES))
    if names is None:
        return 2
    settings, box, groups = grade_settings(args, root, names, collected)

    lock = threading.Lock()

    def progress(r: Any) -> None:
        # called from --jobs threads at once: one line per record, written whole (print writes the text
        # and its newline separately, so two records could share a line) and flushed under a lock
        if not args.quiet:
            line = f"{r.student:>20} {r.exercise:<18} {r.score:>6g}/{r.max_score:<4g} {r.status} ({r.seconds:.1f} s)"
            with lock:
                try:
                    sys.stdout.write(line.replace("\n", " ") + "\n")
                    sys.stdout.flush()
                except BrokenPipeError:  # `grade ... | head`: grading goes on, its output goes nowhere
                    args.quiet = True
                    drop_stdout()

    with warnings.catch_warnings(record=True) as caught, contextlib.closing(groups):
        warnings.simplefilter("always", GradingIntegrityWarning)
        warnings.simplefilter("ignore", SandboxWarning)  # said above, once
        warnings.simplefilter("ignore", LimitsWarning)  # said above, once
        graded = grade_run(dataclasses.replace(settings, progress=progress))
    results = graded.results
    students = len({r.student for r in results})
    said = f"graded {plural(len(results), 'notebook')} of {plural(students, 'student')} (sandbox: {box.kind})"
    say(args, f"{said}; wrote {args.output}")
    report_written(args, graded.files, collected)  # the summary, the marks, the gradebooks: all written by grade
    tampered = [w for w in caught if issubclass(w.category, GradingIntegrityWarning)]
    for w in tampered:
        print(f"WARNING: {w.message}", file=sys.stderr)
    if tampered:
        return 3
    code, message = run_outcome(results, args.submissions, names)
    if message:
        print(f"ERROR: {message}", file=sys.stderr)
    return code


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
        from ..grading.intake.collect import collect

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
    from ..grading.intake.submissions import exercises_to_grade

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
        say(args, f"not graded (nobody handed them in; --exercise grades them): {', '.join(absent)}", err=True)
    return list(names), collected


def open_limits(box: Any, timeout_cell: float = 10.0, quiet: bool = False) -> Any:
    """A control group per notebook for this run (:func:`puma_course.grading.run.limits.open_run`), said on stderr:
    the limits in force and the clock each call is timed on (not when ``quiet``), or loudly that they hold per
    process only."""
    from ..grading.run import limits

    groups = limits.open_run()
    if groups.enforced:
        if not quiet:
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
        "notebook's limits (docs/safety.md); the CSV's limits column says so.",
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


def grade_settings(args: argparse.Namespace, root: Path, names: Sequence[str], collected: Any) -> tuple[Any, Any, Any]:
    """``puma-course grade``'s :class:`~puma_course.grading.settings.GradeSettings`, with the sandbox and the
    control groups it chose (each once, said on stderr, as is the key): grade() uses them as they are."""
    from ..grading.run.sandbox import choose
    from ..grading.secret import SECRET_FILE, command_key
    from ..grading.settings import GradeSettings

    created = args.seed is None and not (args.secret or root / SECRET_FILE).exists()
    key, said = command_key(args.secret, args.seed, root)  # each student's hidden inputs
    if created or not args.quiet:  # a key file just made is to be kept: said even with --quiet
        print(said, file=sys.stderr)
    box = choose(args.sandbox)
    if box.kind == "bwrap":
        say(args, f"sandbox: bubblewrap ({box.binary}); {box.mounts}", err=True)
    else:
        print(
            f"WARNING: grading WITHOUT the operating-system sandbox: {box.reason}.\n"
            "WARNING: a hostile notebook can read and change what this user can (solutions/, classmates' "
            "files, the grades) and outlive its notebook; every feedback file says so. Install bubblewrap "
            "(apt install bubblewrap, or the grader's extra: pip install 'puma-course[grader]') "
            "or see docs/safety.md.",
            file=sys.stderr,
        )
    groups = open_limits(
        box, args.timeout_cell, args.quiet
    )  # a control group per notebook: limits for its whole process tree
    settings = GradeSettings(
        args.submissions,
        args.output,
        feedback=args.feedback,
        jobs=args.jobs,
        timeout_cell=args.timeout_cell,
        timeout_total=args.timeout_total,
        timeout_student=args.timeout_student,
        secret=key,
        sandbox=box,
        # the whole course folder (bank/, solutions/, .git) stays out of the sandbox wherever the course is
        private=[root],
        cgroups=groups,
        exercises=names,
        layout=args.layout,
        collected=collected,
        gradebooks=args.gradebook or (),
        roster=args.roster,
        marks=args.marks or (),
        bank=root,
        shard=args.shard,
        shard_file=args.shard_file,
    )
    return settings, box, groups


def report_written(args: argparse.Namespace, files: Any, collected: Any) -> None:
    """Say what grade() wrote besides the CSV: the summary, the written marks merged (and the answers still to
    mark), each gradebook (and what an import of it will lack). With ``--quiet``, only what is missing."""
    from ..grading.output.text import plural

    say(args, files.summary_note)
    if collected is not None and collected.problems:
        said = plural(len(collected.problems), "file")
        say(args, f"{said} of the download not graded (listed above and in the summary)")
    if files.marked is not None:
        where = f" and the feedback in {args.feedback}" if args.feedback is not None else ""
        say(args, f"written marks: {plural(files.marked, 'answer')} marked, merged into {args.output}{where}")
    if files.unmarked:
        print(
            f"note: {plural(files.unmarked, 'written answer')} not marked yet: counted as nothing in a total said "
            "to be provisional (feedback, summary), an empty cell in the CSV and the gradebooks (no grade on import)",
            file=sys.stderr,
        )
    for fmt, path, notes in files.gradebooks:
        say(args, f"gradebook ({fmt}): {path}")
        for note in notes:
            print(f"  {note}", file=sys.stderr)
    if files.shard is not None:
        say(args, f"shard {args.shard}: {files.shard} (puma-course merge combines it with the other parts)")
