"""The options more than one command takes, declared once: ``--course``, ``--layout``, ``--exercise``, the timeouts,
``--quiet`` (and :func:`say`, which honours it), the key (``--secret``/``--seed``) and the class's files that
``grade`` and ``merge`` both write (``-o``, ``--feedback``, ``--marks``, ``--gradebook``, ``--roster``).

Every command's parser is given :func:`course_option` as a parent (``--course DIR``), and its run function
finds the course with :func:`course` (``--course DIR``, else the nearest course at or above the current folder).
Standard library only (cli layer).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ..course import course_root

__all__ = [
    "LAYOUT_SHAPES",
    "course_option",
    "course",
    "add_layout",
    "add_exercises",
    "add_timeouts",
    "add_quiet",
    "add_class_files",
    "add_key",
    "say",
]

COURSE_HELP = (
    "the course folder (default: the nearest folder, at or above the current one, that holds solutions/ or notebooks/)"
)

#: how a hand-in folder may be laid out (``--layout``), and what each layout looks like
LAYOUT_SHAPES = {
    "folders": "<student>/<exercise>.ipynb",
    "canvas": "flat files <name>[_LATE]_<user id>_<file id>_<exercise>.ipynb",
    "moodle": "<Full Name>_<participant id>_assignsubmission_file_/<exercise>.ipynb",
}


def course_option() -> argparse.ArgumentParser:
    """The parent parser of every command: ``--course DIR``."""
    common = argparse.ArgumentParser(add_help=False)
    common.add_argument("--course", type=Path, default=None, metavar="DIR", help=COURSE_HELP)
    return common


def course(args: argparse.Namespace) -> Path:
    """The course the command works on: ``--course DIR``, else found from the current directory."""
    return course_root(args.course)


def add_layout(parser: argparse.ArgumentParser, help: str) -> None:
    """``--layout folders|canvas|moodle``: how SUBMISSIONS is laid out (``grade``, ``collect-written``)."""
    parser.add_argument("--layout", choices=tuple(LAYOUT_SHAPES), default="folders", help=help)


def add_exercises(parser: argparse.ArgumentParser, help: str) -> None:
    """``--exercise NAME`` (repeatable): the exercises a class command works on (``grade``, ``collect-written``)."""
    parser.add_argument("--exercise", action="append", default=None, metavar="NAME", help=help)


def add_timeouts(parser: argparse.ArgumentParser) -> None:
    """``--timeout-cell S`` and ``--timeout-total S``: how long one notebook may run (``grade``, ``check``)."""
    parser.add_argument(
        "--timeout-cell", type=float, default=10.0, metavar="S", help="seconds per cell and per call (default 10)"
    )
    parser.add_argument(
        "--timeout-total", type=float, default=60.0, metavar="S", help="seconds per notebook (default 60)"
    )


def add_quiet(parser: argparse.ArgumentParser) -> None:
    """``--quiet``: only warnings and errors, on stderr (``grade``, ``merge``, ``collect-written``)."""
    parser.add_argument(
        "--quiet", action="store_true", help="print only warnings and errors (on stderr): no progress or report lines"
    )


def say(args: argparse.Namespace, text: str, *, err: bool = False) -> None:
    """Print ``text``, a line that informs (stdout; stderr with ``err``), unless ``--quiet`` was given. Warnings
    and errors are printed with ``print(..., file=sys.stderr)`` instead: ``--quiet`` keeps them."""
    if not getattr(args, "quiet", False):
        print(text, file=sys.stderr if err else sys.stdout)


def add_key(parser: argparse.ArgumentParser, then: str = "") -> None:
    """``--secret FILE`` and ``--seed N``: the key of each student's hidden inputs (``grade``; ``merge``, whose
    ``then`` says it must be the key grade used)."""
    parser.add_argument(
        "--secret", type=Path, default=None, metavar="FILE", help=f"key file (default: .grading-secret){then}"
    )
    parser.add_argument(
        "--seed", type=int, default=None, metavar="N", help=f"a public key instead (demonstrations, tests){then}"
    )


def add_class_files(parser: argparse.ArgumentParser) -> None:
    """The files a graded class is written into, and what goes into them (``grade``, ``merge``): ``-o FILE``,
    ``--feedback DIR``, ``--marks FILE`` (repeatable), ``--gradebook canvas|moodle|wide`` (repeatable) and
    ``--roster CSV``."""
    parser.add_argument("-o", "--output", type=Path, required=True, metavar="FILE", help="CSV file to write")
    parser.add_argument(
        "--feedback", type=Path, default=None, metavar="DIR", help="folder for one Markdown feedback file per student"
    )
    parser.add_argument(
        "--marks",
        type=Path,
        action="append",
        default=None,
        metavar="FILE",
        help="a filled-in marks file of collect-written (repeatable): merged into the CSV (written columns), "
        "the gradebooks and the feedback",
    )
    parser.add_argument(
        "--gradebook",
        choices=("canvas", "moodle", "wide"),
        action="append",
        default=None,
        help="also write, next to the CSV, one row per student in this platform's grade-import format "
        "(repeatable): canvas, moodle or wide (a plain spreadsheet)",
    )
    parser.add_argument(
        "--roster",
        type=Path,
        default=None,
        metavar="CSV",
        help="Moodle's grade export (First name, Last name, ID number, Email address): the identifiers "
        "--gradebook moodle needs",
    )
