"""The ``puma-course`` command: open the course, check a notebook; release exercises, grade a class.

    puma-course lab [--course DIR] [--no-browser] [--print-command] [JUPYTER-OPTIONS ...]   (lab.py)
    puma-course check NOTEBOOK [--course DIR] [--exercise NAME]                             (check.py)
    puma-course release [--course DIR] [--solutions DIR] [--exercises DIR] [--check]       (release.py)
    puma-course grade SUBMISSIONS -o grades.csv [--course DIR] [--feedback DIR] [--jobs N]  (grade.py)
                      [--timeout-cell S] [--timeout-total S] [--timeout-student S] [--secret FILE | --seed N]
                      [--sandbox auto|bwrap|none] [--exercise NAME ...] [--marks FILE ...]
                      [--layout folders|canvas|moodle] [--gradebook canvas|moodle|wide ...]
    puma-course merge SHARD.json ... -o grades.csv [--secret FILE | --seed N] [...]          (merge.py)
    puma-course collect-written SUBMISSIONS -o DIR [--anonymise] ...                        (written.py)
    puma-course limits show | delegate --user NAME [--undo]                                 (limits.py)
    puma-course gradescope EXERCISE -o autograder.zip [--course DIR]                        (gradescope.py)
    puma-course site [--course DIR] [-o DIR] [--repo-url URL]                               (publish.py)
    puma-course edition DIR [--course DIR]                                                  (publish.py)
    puma-course slides [--course DIR] [-o DIR] [--lecture NN ...]                           (teach.py)
    puma-course keys [--course DIR] [-o DIR]                                                (teach.py)

Each module adds its command's parser (``add_parser(sub, common)``, ``common`` giving the shared ``--course``;
the options several commands share are declared once in :mod:`.options`) and holds its run function
(``run(args) -> int``); :data:`COMMANDS` maps every command to its run function, the one dispatch of
:func:`main`. ``--help`` lists a student's commands first, then the instructor's (:mod:`.help`).

Every command works on the course it is run in: the nearest folder, at or above the current
one, that holds ``solutions/`` or ``notebooks/`` (:mod:`puma_course.course`), or the folder named
by ``--course DIR``. Run outside a course, a command that needs one says where it looked and
exits with code 2.

Every sub-command returns an exit code from :func:`main` (0 = success, 2 = bad input); ``lab``
on POSIX replaces the process with JupyterLab, so Ctrl-C and signals reach JupyterLab itself.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable, Sequence
from typing import Any

from ..course import CourseNotFoundError
from ..extras import MissingExtraError, require_extra
from . import check, grade, gradescope, lab, limits, merge, publish, release, teach, written
from .help import BROKEN_PIPE, command_list, drop_stdout
from .lab import CONTENTS_MANAGER, lab_command
from .options import course_option

__all__ = ["main", "build_parser", "COMMANDS", "lab_command", "CONTENTS_MANAGER"]

#: what adds each command's parser, in the order argparse lists them (a student's commands first)
PARSERS: tuple[Callable[[Any, argparse.ArgumentParser], None], ...] = (
    lab.add_parser,  # lab
    check.add_parser,  # check
    release.add_parser,  # release
    grade.add_parser,  # grade
    merge.add_parser,  # merge
    written.add_parser,  # collect-written
    limits.add_parser,  # limits
    gradescope.add_parser,  # gradescope
    publish.add_parser,  # site, edition
    teach.add_parser,  # slides, keys
)

#: every command and the function that runs it: the one dispatch of :func:`main`
COMMANDS: dict[str, Callable[[argparse.Namespace], int]] = {
    "lab": lab.run,
    "check": check.run,
    "release": release.run,
    "grade": grade.run,
    "merge": merge.run,
    "collect-written": written.run,
    "limits": limits.run,
    "gradescope": gradescope.run,
    "site": publish.run_site,
    "edition": publish.run_edition,
    "slides": teach.run_slides,
    "keys": teach.run_keys,
}


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of ``puma-course`` (one sub-command per entry of :data:`COMMANDS`).

    ``lab`` takes any further option for JupyterLab: parse with ``parse_known_args`` (as
    :func:`main` does) to collect them.

    >>> build_parser().parse_args(["release", "--check"]).command
    'release'
    """
    parser = argparse.ArgumentParser(
        prog="puma-course", usage="%(prog)s [-h] COMMAND ...", formatter_class=argparse.RawDescriptionHelpFormatter
    )
    # the commands are listed by command_list (students' first), not in argparse's one list
    # prog given: each command's usage reads "puma-course check ...", not the top usage line with "check" after it
    sub = parser.add_subparsers(
        dest="command", required=True, metavar="COMMAND", help=argparse.SUPPRESS, prog="puma-course"
    )
    common = course_option()
    for add_parser in PARSERS:
        add_parser(sub, common)
    parser.description = command_list([(a.dest, a.help or "") for a in sub._choices_actions])
    return parser


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
    try:
        require_extra(args.command)
        return COMMANDS[args.command](args)
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
