"""The ``puma-course`` command: open the course, release exercises, grade submissions.

    puma-course lab [--course DIR] [--no-browser] [--print-command] [JUPYTER-OPTIONS ...]
    puma-course release [--course DIR] [--solutions DIR] [--exercises DIR] [--check]
    puma-course grade SUBMISSIONS -o grades.csv [--course DIR] [--feedback DIR] [--jobs N]
                      [--timeout-cell S] [--timeout-total S] [--timeout-student S] [--secret FILE | --seed N]
                      [--sandbox auto|bwrap|none] [--exercise NAME ...]
    puma-course check NOTEBOOK [--course DIR] [--exercise NAME]
    puma-course grade ... [--layout folders|canvas|moodle] [--gradebook canvas|moodle|wide ...]
    puma-course gradescope EXERCISE -o autograder.zip [--course DIR]   (also collect-written, limits: see cli_platform)
    puma-course site [--course DIR] [-o DIR] [--repo-url URL]
    puma-course edition DIR [--course DIR]
    puma-course slides [--course DIR] [-o DIR] [--lecture NN ...]   (see :mod:`puma_course.instructor`)
    puma-course keys [--course DIR] [-o DIR]

``grade`` without ``--exercise`` grades the course's exercises that some student handed in.

Every command works on the course it is run in: the nearest folder, at or above the current
one, that holds ``solutions/`` or ``notebooks/`` (:mod:`puma_course.course`), or the folder named
by ``--course DIR``. Run outside a course, a command that needs one says where it looked and
exits with code 2.

Every sub-command returns an exit code from :func:`main` (0 = success, 2 = bad input); ``lab``
on POSIX replaces the process with JupyterLab, so Ctrl-C and signals reach JupyterLab itself.
"""

from __future__ import annotations

import argparse
import contextlib
import dataclasses
import sys
import threading
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from .cli_help import BROKEN_PIPE, command_list, drop_stdout
from .cli_lab import CONTENTS_MANAGER, add_lab_parser, lab, lab_command
from .cli_platform import (
    add_grade_arguments,
    add_gradescope_parser,
    choose_and_collect,
    gradescope,
    open_limits,
    write_gradebooks,
)
from .cli_publish import add_publish_parsers, edition, site
from .cli_written import collect_written
from .course import CourseNotFoundError, course_root, find_course
from .extras import MissingExtraError, require_extra
from .instructor.cli import add_parsers as add_instructor_parsers
from .instructor.cli import run_keys, run_slides

__all__ = ["main", "build_parser", "lab_command", "CONTENTS_MANAGER"]

_COURSE_HELP = (
    "the course folder (default: the nearest folder, at or above the current one, that holds solutions/ or notebooks/)"
)


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of ``puma-course`` (sub-commands lab, release, grade, check, site).

    ``lab`` takes any further option for JupyterLab: parse with ``parse_known_args`` (as
    :func:`main` does) to collect them.

    >>> build_parser().parse_args(["release", "--check"]).command
    'release'
    """
    parser = argparse.ArgumentParser(
        prog="puma-course", usage="%(prog)s [-h] COMMAND ...", formatter_class=argparse.RawDescriptionHelpFormatter
    )
    # the commands are listed by _command_list (students' first), not in argparse's one list
    # prog given: each command's usage reads "puma-course check ...", not the top usage line with "check" after it
    sub = parser.add_subparsers(
        dest="command", required=True, metavar="COMMAND", help=argparse.SUPPRESS, prog="puma-course"
    )

    course = argparse.ArgumentParser(add_help=False)
    course.add_argument("--course", type=Path, default=None, metavar="DIR", help=_COURSE_HELP)

    add_lab_parser(sub, course)

    rel = sub.add_parser("release", parents=[course], help="generate exercises/ from solutions/")
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

    gr = sub.add_parser("grade", parents=[course], help="grade SUBMISSIONS/<student>/<exercise>.ipynb")
    gr.add_argument(
        "submissions",
        type=Path,
        metavar="SUBMISSIONS",
        help="folder with one sub-folder per student, holding <exercise>.ipynb files",
    )
    gr.add_argument("-o", "--output", type=Path, required=True, metavar="FILE", help="CSV file to write")
    gr.add_argument(
        "--feedback", type=Path, default=None, metavar="DIR", help="folder for one Markdown feedback file per student"
    )
    gr.add_argument("--jobs", type=int, default=2, metavar="N", help="notebooks graded at the same time (default 2)")
    gr.add_argument(
        "--timeout-cell", type=float, default=10.0, metavar="S", help="seconds per cell and per call (default 10)"
    )
    gr.add_argument("--timeout-total", type=float, default=60.0, metavar="S", help="seconds per notebook (default 60)")
    gr.add_argument(
        "--timeout-student",
        type=float,
        default=120.0,
        metavar="S",
        help="seconds for all of one student's notebooks together (default 120)",
    )
    gr.add_argument("--secret", type=Path, default=None, metavar="FILE", help="key file (default: .grading-secret)")
    gr.add_argument("--seed", type=int, default=None, metavar="N", help="a public key instead (demonstrations, tests)")
    gr.add_argument(
        "--sandbox",
        choices=("auto", "bwrap", "none"),
        default="auto",
        help="run each notebook inside bubblewrap (bwrap: required; auto, the default: when it works here, "
        "else warn loudly; none: never)",
    )
    gr.add_argument(
        "--exercise",
        action="append",
        default=None,
        metavar="NAME",
        help="grade this exercise (repeatable; default: the course's exercises that some student handed in)",
    )
    gr.add_argument("--quiet", action="store_true", help="no progress lines")
    add_grade_arguments(gr)
    add_gradescope_parser(sub, course)

    ck = sub.add_parser("check", parents=[course], help="grade your own notebook on the public cases")
    ck.add_argument(
        "notebook",
        type=Path,
        metavar="NOTEBOOK",
        help="the notebook: a path, or the name of an exercise in the course's exercises/ (e.g. ex01_rotations)",
    )
    ck.add_argument(
        "--exercise", default=None, metavar="NAME", help="exercise name (default: the notebook's file name)"
    )
    ck.add_argument(
        "--timeout-cell", type=float, default=10.0, metavar="S", help="seconds per cell and per call (default 10)"
    )
    ck.add_argument("--timeout-total", type=float, default=60.0, metavar="S", help="seconds per notebook (default 60)")
    add_publish_parsers(sub, course)
    add_instructor_parsers(sub, course)  # slides, keys (the instructor's kit)
    parser.description = command_list([(a.dest, a.help or "") for a in sub._choices_actions])
    return parser


def _course(args: argparse.Namespace) -> Path:
    """The course the command works on: ``--course DIR``, else found from the current directory."""
    return course_root(args.course)


def _release(args: argparse.Namespace) -> int:
    from .grading import release

    if args.solutions is None or args.exercises is None:
        root = _course(args)
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
    print(f"wrote {len(changed)} exercise notebook(s) to {exercises}" + (": " + ", ".join(changed) if changed else ""))
    return 0


def _grade(args: argparse.Namespace) -> int:
    import warnings

    from .grading import EXERCISES, GradingIntegrityWarning, SandboxWarning, grade, load_bank
    from .grading.output.summary import run_outcome, summary_note
    from .grading.run.runner import LimitsWarning
    from .grading.run.sandbox import choose
    from .grading.secret import command_key

    root = _course(args)
    load_bank(root)  # the questions of the course being graded (its bank/, beside solutions/)
    names, collected = choose_and_collect(args, root, list(EXERCISES))
    if names is None:
        return 2
    # the whole course folder (bank/, solutions/, .git) stays out of the sandbox wherever the course is
    private = [root]
    key, said = command_key(args.secret, args.seed, root)  # each student's hidden inputs
    print(said, file=sys.stderr)
    box = choose(args.sandbox)
    if box.kind == "bwrap":
        print(f"sandbox: bubblewrap ({box.binary}); {box.mounts}", file=sys.stderr)
    else:
        print(
            f"WARNING: grading WITHOUT the operating-system sandbox: {box.reason}.\n"
            "WARNING: a hostile notebook can read and change what this user can (solutions/, classmates' "
            "files, the grades) and outlive its notebook; every feedback file says so. Install bubblewrap "
            "(apt install bubblewrap, or the grader's extra: pip install 'puma-course[grader]') "
            "or see README.md, Safety.",
            file=sys.stderr,
        )
    groups = open_limits(box, args.timeout_cell)  # a control group per notebook: limits for its whole process tree

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
        results = grade(
            args.submissions,
            args.output,
            feedback=args.feedback,
            jobs=args.jobs,
            timeout_cell=args.timeout_cell,
            timeout_total=args.timeout_total,
            secret=key,
            exercises=names,
            progress=progress,
            sandbox=box,
            timeout_student=args.timeout_student,
            private=private,
            cgroups=groups,
            collected=collected,
        )
    students = len({r.student for r in results})
    print(f"graded {len(results)} notebook(s) of {students} student(s) (sandbox: {box.kind}); wrote {args.output}")
    print(summary_note(results, args.output))  # grade() wrote the CSV, the feedback and this summary
    write_gradebooks(args, results, names, collected)
    tampered = [w for w in caught if issubclass(w.category, GradingIntegrityWarning)]
    for w in tampered:
        print(f"WARNING: {w.message}", file=sys.stderr)
    if tampered:
        return 3
    code, message = run_outcome(results, args.submissions, names)
    if message:
        print(f"ERROR: {message}", file=sys.stderr)
    return code


def _notebook(args: argparse.Namespace) -> Path:
    """The notebook ``check`` grades: the path as given, else an exercise of the course by name."""
    given: Path = args.notebook
    if given.is_file():
        return given
    if given.exists():
        raise ValueError(f"notebook: expected a notebook file, got {str(given)!r}, which is a folder")
    if len(given.parts) != 1:
        raise ValueError(f"notebook: expected a notebook file, got {str(given)!r}, which does not exist")
    try:
        folder = _course(args) / "exercises"
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


def _check(args: argparse.Namespace) -> int:
    from .grading import format_check_report, grade_notebook
    from .grading.bank_loader import BankNotFoundError, load_bank

    notebook = _notebook(args)
    name = args.exercise or notebook.stem
    try:  # the bank of the course the notebook is in (or --course, or the one run in), else an edition's public cases
        known: Any = load_bank(_course(args) if args.course else find_course(notebook.parent, fallback=True))
    except (BankNotFoundError, CourseNotFoundError):
        from .grading.publish import public as public_cases

        if not public_cases.available():
            raise
        known = public_cases.exercises()
    if name not in known:
        print(f"check: unknown exercise {name!r}; use --exercise with one of {sorted(known)}", file=sys.stderr)
        return 2
    ex = known[name]
    # The public cases only: every other field (answer-key tripwires, bonus flags) stays as graded.
    public = dataclasses.replace(
        ex, questions=tuple(dataclasses.replace(q, hidden=lambda rng: []) for q in ex.questions)
    )
    r = grade_notebook(notebook, public, seed=0, timeout_cell=args.timeout_cell, timeout_total=args.timeout_total)
    print(format_check_report(r, ex))
    return 0 if r.status in ("ok", "cell-error") else 1


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of ``puma-course``; returns the exit code (2: bad input, such as no course found).

    Output read by a program that stops early (``puma-course check ... | head``) ends the command quietly with
    exit code 141, as a shell tool killed by SIGPIPE, never with a traceback.

    >>> main(["release", "--course", "/no/such/course"])
    2
    """
    try:
        try:
            return _main(argv)
        finally:
            sys.stdout.flush()  # a closed pipe shows here (also after --help), not at the interpreter's exit
    except BrokenPipeError:
        drop_stdout()
        return BROKEN_PIPE


def _main(argv: Sequence[str] | None) -> int:
    parser = build_parser()
    if not (sys.argv[1:] if argv is None else list(argv)):
        parser.print_help(sys.stderr)  # no command: the list of commands before argparse's one-line complaint
    args, extra = parser.parse_known_args(argv)
    if extra and args.command != "lab":
        parser.error(f"unrecognized arguments: {' '.join(extra)}")
    args.jupyter_args = extra
    handlers: dict[str, Any] = {"lab": lab, "release": _release, "grade": _grade, "check": _check}
    handlers["gradescope"] = lambda a: gradescope(a, _course(a))
    handlers["collect-written"] = lambda a: collect_written(a, _course(a))
    handlers["site"] = lambda a: site(a, _course(a))
    handlers["edition"] = lambda a: edition(a, _course(a))
    handlers["slides"] = lambda a: run_slides(a, _course(a))
    handlers["keys"] = lambda a: run_keys(a, _course(a))
    try:
        require_extra(args.command)
        return (handlers.get(args.command) or args.run)(args)
    except MissingExtraError as exc:
        print(str(exc), file=sys.stderr)
        return 2
    except CourseNotFoundError as exc:
        print(f"puma-course {args.command}: no course found: {exc}", file=sys.stderr)
        if args.course is None:
            print(
                "Run it inside a course folder (or any folder below one), or name the course with --course DIR.",
                file=sys.stderr,
            )
        return 2
    except ValueError as exc:
        print(f"puma-course {args.command}: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
