"""The grader's checks and guards around a run: its arguments, the names it keeps for itself, the words for a stop,
and its memory kept out of its workers' reach (split from :mod:`.runner`, which uses them).
"""

from __future__ import annotations

import contextlib
import sys
from collections.abc import Iterator, Sequence
from pathlib import Path

from ..bank_loader import EXERCISES

__all__ = ["check_args", "stop_note", "undumpable", "package_digest"]


def _positive(name: str, value: float) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not value > 0 or value == float("inf"):
        raise ValueError(f"{name}: expected a positive number of seconds, got {value!r}")
    return float(value)


def stop_note(seconds: float, by_student: bool) -> str:
    if by_student:
        return (
            f"stopped after {seconds:g} s: the total time for all of this student's notebooks ran out; "
            "answers that came back before that were graded"
        )
    return (
        f"the notebook ran longer than {seconds:g} s in total and was stopped; "
        "answers that came back before that were graded"
    )


@contextlib.contextmanager
def undumpable(on: bool) -> Iterator[None]:
    """Linux, without the OS sandbox: make the grader's memory unreachable through /proc and ptrace for its workers."""
    libc = None
    if on and sys.platform.startswith("linux"):
        try:
            import ctypes

            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(4, 0, 0, 0, 0)  # PR_SET_DUMPABLE = 4
        except (OSError, AttributeError):
            libc = None
    try:
        yield
    finally:
        if libc is not None:
            libc.prctl(4, 1, 0, 0, 0)


def check_args(submissions: Path, names: Sequence[str], jobs: int, times: dict[str, float]) -> None:
    if not submissions.is_dir():
        raise ValueError(f"submissions: expected a folder with one sub-folder per student, got {str(submissions)!r}")
    for name in names:
        if name not in EXERCISES:
            raise ValueError(f"exercises: expected names among {sorted(EXERCISES)}, got {name!r}")
    if isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
        raise ValueError(f"jobs: expected a whole number of notebooks at a time, at least 1, got {jobs!r}")
    for key, value in times.items():
        _positive(key, value)


def package_digest(package: Path, course: Path | None = None) -> dict[str, bytes]:
    """The bytes of every module of the package at ``package``, by path inside it, and of ``course``'s bank
    (``bank/...``)."""
    out = {p.relative_to(package).as_posix(): p.read_bytes() for p in sorted(package.rglob("*.py"))}
    if course is not None:
        out.update({p.relative_to(course).as_posix(): p.read_bytes() for p in sorted((course / "bank").rglob("*.py"))})
    return out
