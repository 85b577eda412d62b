"""What one grading run needs, in one typed value: :class:`GradeSettings`, given to :func:`~puma_course.grading.grade`.

The command line (``puma-course grade``) and a Python caller build the same value, so a run does the same
thing however it is started: the same submissions read, the same key and sandbox, the same written marks
merged before anything is written, the same files written (:mod:`.output.writer`).

>>> s = GradeSettings("hand-in", "out/grades.csv", seed=3, exercises=["ex01_rotations"], sandbox="none")
>>> s.submissions.as_posix(), s.exercises, s.gradebooks
('hand-in', ('ex01_rotations',), ())
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .bank_loader import EXERCISES, Bank
from .intake.collect import Collected
from .results import NotebookResult
from .run import limits
from .run.sandbox import MODES, Sandbox
from .secret import Secret
from .shards import Shard

__all__ = ["GradeSettings", "LAYOUTS", "GRADEBOOKS", "use_bank"]

LAYOUTS = ("folders", "canvas", "moodle")
GRADEBOOKS = ("canvas", "moodle", "wide")

PathLike = str | os.PathLike[str]


def _paths(values: Sequence[PathLike] | PathLike | None, what: str) -> tuple[Path, ...]:
    if values is None:
        return ()
    if isinstance(values, (str, os.PathLike)):
        return (Path(values),)
    try:
        return tuple(Path(v) for v in values)
    except TypeError:
        raise ValueError(f"{what}: expected file paths, got {values!r}") from None


@dataclass(frozen=True, init=False)
class GradeSettings:
    """Everything a grading run needs (paths are turned into :class:`~pathlib.Path`, sequences into tuples).

    * ``submissions``: ``<student>/<exercise>.ipynb`` folders, or a platform's download (``layout`` canvas or
      moodle, or ``collected``: the download read earlier by :func:`~.run.collect.collect`);
    * ``output``: the grades CSV; the class summary and the gradebooks go next to it; ``feedback``: a folder
      for one Markdown file per student (None: no feedback);
    * ``jobs``, ``timeout_cell``, ``timeout_total``, ``timeout_student``: how many notebooks at once and their
      time limits (seconds);
    * ``secret`` (a :class:`~.secret.Secret`, or the instructor's key file) or ``seed`` (a public key), neither
      for a one-off key: each student's hidden inputs (:func:`~.secret.choose_key`, called once per run);
    * ``sandbox``: "auto", "bwrap", "none", or a :class:`~.run.sandbox.Sandbox` chosen earlier (used as is);
      ``private``: more folders the sandbox hides; ``cgroups``: a control group per notebook (True), not
      (False), or a :class:`~.run.limits.Run` opened earlier (used as is, not closed);
    * ``exercises``: the exercises graded (empty: every exercise of the bank);
    * ``gradebooks``: platform gradebooks written next to the CSV (canvas, moodle, wide); ``roster``: Moodle's
      grade export for ``moodle``;
    * ``marks``: filled-in marks files of ``collect-written`` (read and checked before anything is graded,
      merged into every file written);
    * ``bank``: the question bank graded with: a :class:`~.model.Bank`, or the course folder holding ``bank/``
      (None: the bank already loaded, else the course found from the current folder);
    * ``shard``: grade only part K of N of the class (:class:`~.shards.Shard`, a stable split by student) and
      write a shard file (``shard_file``; default ``<output stem>.shard.json`` next to the CSV) that
      ``puma-course merge`` combines with the other parts (:mod:`.shards`);
    * ``progress``: called with each notebook's result as it is graded.
    """

    submissions: Path
    output: Path
    feedback: Path | None = None
    jobs: int = 2
    timeout_cell: float = 10.0
    timeout_total: float = 60.0
    timeout_student: float = 120.0
    seed: int | None = None
    secret: Secret | Path | None = None
    sandbox: str | Sandbox = "auto"
    private: tuple[Path, ...] = ()
    cgroups: bool | limits.Run = True
    exercises: tuple[str, ...] = ()
    layout: str = "folders"
    collected: Collected | None = None
    gradebooks: tuple[str, ...] = ()
    roster: Path | None = None
    marks: tuple[Path, ...] = ()
    bank: Bank | Path | None = None
    shard: Shard | None = None
    shard_file: Path | None = None
    progress: Callable[[NotebookResult], None] | None = field(default=None, compare=False)

    def __init__(
        self,
        submissions: PathLike,
        output: PathLike,
        feedback: PathLike | None = None,
        jobs: int = 2,
        timeout_cell: float = 10.0,
        timeout_total: float = 60.0,
        timeout_student: float = 120.0,
        seed: int | None = None,
        secret: Secret | PathLike | None = None,
        sandbox: str | Sandbox = "auto",
        private: Sequence[PathLike] = (),
        cgroups: bool | limits.Run = True,
        exercises: Sequence[str] | None = None,
        layout: str = "folders",
        collected: Collected | None = None,
        gradebooks: Sequence[str] | None = None,
        roster: PathLike | None = None,
        marks: Sequence[PathLike] | None = None,
        bank: Bank | PathLike | None = None,
        shard: Shard | str | None = None,
        shard_file: PathLike | None = None,
        progress: Callable[[NotebookResult], None] | None = None,
    ) -> None:
        if layout not in LAYOUTS:
            raise ValueError(f"layout: expected one of {', '.join(LAYOUTS)}, got {layout!r}")
        if isinstance(sandbox, str) and sandbox not in MODES:
            raise ValueError(f"sandbox: expected one of {', '.join(MODES)}, got {sandbox!r}")
        books = tuple(dict.fromkeys(gradebooks or ()))
        for fmt in books:
            if fmt not in GRADEBOOKS:
                raise ValueError(f"gradebook: expected one of {', '.join(GRADEBOOKS)}, got {fmt!r}")
        if shard_file is not None and shard is None:
            raise ValueError(f"shard_file: expected only together with a shard (K/N), got {str(shard_file)!r} alone")
        if isinstance(exercises, str):
            raise ValueError(f"exercises: expected a list of exercise names, got the string {exercises!r}")
        values: dict[str, Any] = {
            "submissions": Path(submissions),
            "output": Path(output),
            "feedback": None if feedback is None else Path(feedback),
            "jobs": jobs,
            "timeout_cell": timeout_cell,
            "timeout_total": timeout_total,
            "timeout_student": timeout_student,
            "seed": seed,
            "secret": secret if secret is None or isinstance(secret, Secret) else Path(secret),
            "sandbox": sandbox,
            "private": _paths(private, "private"),
            "cgroups": cgroups,
            "exercises": tuple(exercises or ()),
            "layout": layout,
            "collected": collected,
            "gradebooks": books,
            "roster": None if roster is None else Path(roster),
            "marks": _paths(marks, "marks"),
            "bank": bank if bank is None or isinstance(bank, Bank) else Path(bank),
            "shard": shard if shard is None or isinstance(shard, Shard) else Shard.parse(shard),
            "shard_file": None if shard_file is None else Path(shard_file),
            "progress": progress,
        }
        for name, value in values.items():
            object.__setattr__(self, name, value)


def use_bank(bank: Bank | PathLike | None) -> Bank:
    """The question bank a run grades with, loaded into the grader's registry (:data:`~.model.EXERCISES`) when it
    is not the one loaded: ``bank`` a :class:`~.model.Bank` or a course folder; None: the registry as it is
    (loaded on first use from the course found from the current folder)."""
    if bank is None or bank is EXERCISES:
        return EXERCISES
    if isinstance(bank, Bank):
        if bank.course is None:
            raise ValueError("bank: expected a bank loaded from a course folder, got one never loaded")
        bank = bank.course
    root = Path(bank).resolve()
    if EXERCISES.course is None or Path(EXERCISES.course).resolve() != root:
        EXERCISES.load(root)
    return EXERCISES
