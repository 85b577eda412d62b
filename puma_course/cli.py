"""The ``puma-course`` command: open the lectures, release exercises, grade submissions.

    puma-course lab [--no-browser] [--print-command]
    puma-course release [--solutions DIR] [--exercises DIR] [--check]
    puma-course grade SUBMISSIONS -o grades.csv [--feedback DIR] [--jobs N]
                      [--timeout-cell S] [--timeout-total S] [--seed N] [--exercise NAME ...]
    puma-course check NOTEBOOK [--exercise NAME]

Every sub-command returns an exit code from :func:`main` (0 = success).
"""

from __future__ import annotations

import argparse
import dataclasses
import shlex
import subprocess
import sys
from collections.abc import Sequence
from pathlib import Path

__all__ = ["main", "build_parser", "lab_command"]

REPO_ROOT = Path(__file__).resolve().parent.parent


def _course_dir(name: str) -> Path:
    """``<repo>/name`` for a checkout (editable install), else ``./name`` (run from the course folder)."""
    here = REPO_ROOT / name
    return here if here.is_dir() else Path.cwd() / name


def lab_command(no_browser: bool = False, notebooks: Path | None = None) -> list[str]:
    """The command line that opens JupyterLab on the course's lecture notebooks.

    >>> lab_command(no_browser=True)[1:3]
    ['-m', 'jupyterlab']
    """
    folder = notebooks if notebooks is not None else _course_dir("notebooks")
    cmd = [sys.executable, "-m", "jupyterlab", str(folder)]
    if no_browser:
        cmd.append("--no-browser")
    return cmd


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of ``puma-course`` (sub-commands lab, release, grade, check)."""
    parser = argparse.ArgumentParser(prog="puma-course", description="Manipulator-kinematics course tools.")
    sub = parser.add_subparsers(dest="command", required=True)

    lab = sub.add_parser("lab", help="open JupyterLab on the lecture notebooks")
    lab.add_argument("--no-browser", action="store_true", help="start the server without opening a browser")
    lab.add_argument("--notebooks", type=Path, default=None, help="folder to open (default: the course's notebooks/)")
    lab.add_argument("--print-command", action="store_true", help="print the command instead of running it")

    rel = sub.add_parser("release", help="generate exercises/ from solutions/")
    rel.add_argument("--solutions", type=Path, default=_course_dir("solutions"))
    rel.add_argument("--exercises", type=Path, default=_course_dir("exercises"))
    rel.add_argument("--check", action="store_true", help="write nothing; exit 1 if exercises/ is out of date")

    gr = sub.add_parser("grade", help="grade SUBMISSIONS/<student>/<exercise>.ipynb")
    gr.add_argument("submissions", type=Path)
    gr.add_argument("-o", "--output", type=Path, required=True, help="CSV file to write")
    gr.add_argument("--feedback", type=Path, default=None, help="folder for one Markdown feedback file per student")
    gr.add_argument("--jobs", type=int, default=2, help="notebooks graded at the same time (default 2)")
    gr.add_argument("--timeout-cell", type=float, default=10.0, help="seconds per cell and per call (default 10)")
    gr.add_argument("--timeout-total", type=float, default=60.0, help="seconds per notebook (default 60)")
    gr.add_argument("--seed", type=int, default=None, help="seed of the hidden inputs (default: a fresh random one)")
    gr.add_argument("--exercise", action="append", default=None, help="grade only this exercise (repeatable)")
    gr.add_argument("--quiet", action="store_true", help="no progress lines")

    ck = sub.add_parser("check", help="grade your own notebook on the public cases")
    ck.add_argument("notebook", type=Path)
    ck.add_argument("--exercise", default=None, help="exercise name (default: the notebook's file name)")
    ck.add_argument("--timeout-cell", type=float, default=10.0)
    ck.add_argument("--timeout-total", type=float, default=60.0)
    return parser


def _lab(args: argparse.Namespace) -> int:
    cmd = lab_command(args.no_browser, args.notebooks)
    if args.print_command:
        print(shlex.join(cmd))
        return 0
    return subprocess.call(cmd)


def _release(args: argparse.Namespace) -> int:
    from .grading import release

    try:
        changed = release(args.solutions, args.exercises, check_only=args.check)
    except ValueError as exc:
        print(f"release failed: {exc}", file=sys.stderr)
        return 2
    if args.check:
        if changed:
            print("exercises out of date (run `puma-course release`): " + ", ".join(changed), file=sys.stderr)
            return 1
        print("exercises are up to date")
        return 0
    print(f"wrote {len(changed)} exercise notebook(s)" + (": " + ", ".join(changed) if changed else ""))
    return 0


def _grade(args: argparse.Namespace) -> int:
    import warnings

    from .grading import GradingIntegrityWarning, grade

    def progress(r):  # type: ignore[no-untyped-def]
        if not args.quiet:
            print(
                f"{r.student:>20} {r.exercise:<18} {r.score:>6g}/{r.max_score:<4g} {r.status} ({r.seconds:.1f} s)",
                flush=True,
            )

    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", GradingIntegrityWarning)
            results = grade(
                args.submissions,
                args.output,
                feedback=args.feedback,
                jobs=args.jobs,
                timeout_cell=args.timeout_cell,
                timeout_total=args.timeout_total,
                seed=args.seed,
                exercises=args.exercise,
                progress=progress,
            )
    except ValueError as exc:
        print(f"grade failed: {exc}", file=sys.stderr)
        return 2
    students = len({r.student for r in results})
    print(f"graded {len(results)} notebook(s) of {students} student(s); wrote {args.output}")
    tampered = [w for w in caught if issubclass(w.category, GradingIntegrityWarning)]
    for w in tampered:
        print(f"WARNING: {w.message}", file=sys.stderr)
    return 3 if tampered else 0


def _check(args: argparse.Namespace) -> int:
    from .grading import EXERCISES, format_check_report, grade_notebook

    name = args.exercise or args.notebook.stem
    if name not in EXERCISES:
        print(f"check: unknown exercise {name!r}; use --exercise with one of {sorted(EXERCISES)}", file=sys.stderr)
        return 2
    ex = EXERCISES[name]
    # The public cases only: every other field (answer-key tripwires, bonus flags) stays as graded.
    public = dataclasses.replace(
        ex, questions=tuple(dataclasses.replace(q, hidden=lambda rng: []) for q in ex.questions)
    )
    r = grade_notebook(args.notebook, public, seed=0, timeout_cell=args.timeout_cell, timeout_total=args.timeout_total)
    print(format_check_report(r, ex))
    return 0 if r.status in ("ok", "cell-error") else 1


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of ``puma-course``; returns the exit code."""
    args = build_parser().parse_args(argv)
    handlers = {"lab": _lab, "release": _release, "grade": _grade, "check": _check}
    return handlers[args.command](args)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
