"""The grading run's own folder: the worker's code and one student-side package per exercise, read-only.

A :class:`Stage` is built once per run (and removed at its end): ``bin/puma_worker`` is a copy of
:mod:`puma_course.grading.run.worker` (standard library only, so it runs without the package), and
``lib/<exercise>/puma_course`` is the student-side package of each exercise
(:mod:`puma_course.grading.run.student`). Under bubblewrap a worker sees ``bin`` and its own exercise's
``lib`` folder only; without it, the files are made read-only and :meth:`Stage.changed` tells
whether a student's process wrote to them anyway.
"""

from __future__ import annotations

import hashlib
import shutil
import tempfile
from collections.abc import Iterable
from pathlib import Path

from ..spec import Exercise
from . import student

__all__ = ["Stage", "WORKER_DIR"]

#: The worker package, copied into each run's stage.
WORKER_DIR = Path(__file__).resolve().parent / "worker"


class Stage:
    """A run's read-only folder (see the module docstring); use as a context manager, or call :meth:`close`."""

    def __init__(self, exercises: Iterable[Exercise], parent: str | None = None) -> None:
        """``parent``: the folder to build it in (the run's in-memory scratch, :mod:`.scratch`; default: /tmp)."""
        self.root = Path(tempfile.mkdtemp(prefix="stage-" if parent else "puma-stage-", dir=parent))
        try:
            self.bin = self.root / "bin"
            shutil.copytree(WORKER_DIR, self.bin / "puma_worker", ignore=shutil.ignore_patterns("__pycache__"))
            self.libs: dict[str, Path] = {}
            for ex in exercises:
                self.libs[ex.name] = student.build(ex.name, ex.allowed, self.root / "lib" / ex.name, ex.answer_keys)
            student.lock(self.root)
            self._digest = self.digest()
        except BaseException:
            self.close()
            raise

    def digest(self) -> dict[str, str]:
        """SHA-256 of every file in the stage, by path inside it."""
        return {
            p.relative_to(self.root).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(self.root.rglob("*"))
            if p.is_file() and not p.is_symlink()
        }

    def changed(self) -> list[str]:
        """The stage's files that differ from when it was built (a tampering student's work)."""
        now = self.digest()
        return sorted(k for k in set(now) | set(self._digest) if now.get(k) != self._digest.get(k))

    def close(self) -> None:
        """Remove the stage."""
        if self.root.exists():
            student.lock(self.root, writable=True)
            shutil.rmtree(self.root, ignore_errors=True)

    def __enter__(self) -> Stage:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
