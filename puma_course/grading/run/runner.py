"""The grader's side: plan the calls, run each notebook in a fresh sandboxed worker, score what comes back.

:func:`grade` grades ``SUBMISSIONS/<student>/<exercise>.ipynb`` for a class. It chooses the
operating-system sandbox (:mod:`.sandbox`: bubblewrap where it runs, else none, loudly), builds the
run's stage (the worker and a student-side ``puma_course`` per exercise holding only what the exercise
allows: :mod:`.stage`), and then grades the students, ``jobs`` at a time, each within a total time limit
of its own. A notebook's expected values are computed in this process just before it runs
(:func:`make_plan`, while other students' notebooks run in their sandboxes) and dropped once it is
judged, so the grader holds the plans of the notebooks in flight, never the class's. Each notebook is
read without following links (:mod:`.submissions`) and handed, as bytes, to a fresh worker
(:mod:`.worker`, run by :mod:`.child`), which parses it, runs its code cells and calls the student's
functions on the planned inputs, with a time limit per cell, per call and per notebook.
Only the numbers the functions return come back; the comparison, and the
wording of every message, happen here (:mod:`.events`). Results go to a CSV and feedback files
(:mod:`.report`).
"""

from __future__ import annotations

import concurrent.futures
import dataclasses
import os
import threading
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

from ... import __version__
from ...course import is_course
from ..bank_loader import EXERCISES
from ..intake.collect import Collected, collect
from ..intake.submissions import MAX_NOTEBOOK_BYTES, StudentFiles, StudentFolder, read_path, read_student, scan
from ..output.copies import Handed, find_copies, handed
from ..output.gradebook import read_roster
from ..output.marks import read_marks
from ..output.writer import RunFacts, Written, write_run
from ..plan import Plan, make_plan
from ..results import NotebookResult
from ..secret import Secret, choose_key
from ..settings import GradeSettings, use_bank
from ..shards import ShardFile, run_facts, shard_path, write_shard
from ..spec import Exercise
from . import limits
from .notebook_run import LIMITS, grade_data  # noqa: F401 - LIMITS: its old home
from .run_checks import check_args, package_digest, stop_note, undumpable
from .sandbox import Sandbox, choose
from .stage import Stage

__all__ = [
    "GradingIntegrityWarning",
    "SandboxWarning",
    "LimitsWarning",
    "make_plan",
    "grade_notebook",
    "grade",
    "grade_run",
    "Graded",
    "MAX_NOTEBOOK_BYTES",
    "PACKAGE_PARENT",
]

#: The folder that holds the ``puma_course`` package (in a course checkout, the course itself).
PACKAGE_PARENT = Path(__file__).resolve().parents[3]
_PACKAGE_DIR = PACKAGE_PARENT / "puma_course"
#: Notebooks of a class read into memory before any student code runs, when there is no OS sandbox.
PRE_READ_BYTES = 512 << 20
#: One plan at a time: the bank's references silence warnings with ``warnings.catch_warnings``, which swaps the
#: process's filters and is not thread-safe (two at once can leave "ignore" behind, and the grader's own
#: warnings, GradingIntegrityWarning among them, with it). Planning is Python under the GIL: nothing is lost.
_PLANNING = threading.Lock()


class GradingIntegrityWarning(UserWarning):
    """The course package's files changed while grading: a submission may have tampered with them."""


class SandboxWarning(UserWarning):
    """The notebooks are graded without the operating-system sandbox."""


class LimitsWarning(UserWarning):
    """The notebooks are graded with per-process limits only: no control group per notebook (:mod:`.limits`)."""


def _checkouts() -> list[Path]:
    """The course folders a worker must never see: the bank's course and the package's own checkout.

    The package's parent is a checkout (an editable install, or ``pip install -e git+...`` cloning the
    course into ``<venv>/src``) when it holds a course or a ``.git``; in a non-editable install it is
    site-packages, which the worker needs, and is not hidden.
    """
    folders = [EXERCISES.course] if EXERCISES.course is not None else []
    if is_course(PACKAGE_PARENT) or (PACKAGE_PARENT / ".git").exists() or (PACKAGE_PARENT / "bank").is_dir():
        folders.append(PACKAGE_PARENT)
    return [f for f in dict.fromkeys(folders) if f is not None]


def _box(sandbox: str | Sandbox) -> Sandbox:
    return sandbox if isinstance(sandbox, Sandbox) else choose(sandbox)


def grade_notebook(
    path: str | os.PathLike[str] | None,
    exercise: Exercise,
    student: str = "",
    seed: int | Secret = 0,
    timeout_cell: float = 10.0,
    timeout_total: float = 60.0,
    plan: Plan | None = None,
    data: bytes | None = None,
    *,
    sandbox: str | Sandbox = "none",
) -> NotebookResult:
    """Grade one submitted notebook (``path`` None or absent: status "missing").

    ``plan`` is the exercise's :func:`make_plan` for ``seed`` (computed here when None). The file is
    read once, without following a link (or ``data`` holds its bytes, read earlier); the worker
    gets it through a pipe and runs in a fresh folder, so the submission is never modified and
    nothing written to disk while grading can change what is graded. ``sandbox`` is "none" (the
    default here: ``puma-course check`` runs a student's own notebook), "auto" or "bwrap".
    """
    if data is None:
        if path is None:
            return NotebookResult.blank(student, exercise, "missing", f"no file {exercise.name}.ipynb was submitted")
        nb = read_path(path)
        if nb.state != "read" or nb.data is None:
            return NotebookResult.blank(student, exercise, nb.state, nb.note)
        data = nb.data
    box = _box(sandbox)
    calls = make_plan(exercise, seed, student) if plan is None else plan
    with Stage([exercise], box.scratch.path if box.scratch else None) as stage:
        return grade_data(
            data, exercise, student, calls, stage, box, timeout_cell, timeout_total, stop_note(timeout_total, False)
        )


def _blank(student: str, ex: Exercise, state: str, note: str | None) -> NotebookResult:
    return NotebookResult.blank(student, ex, state if state != "read" else "grader-error", note)


@dataclass
class Graded:
    """A grading run's outcome: the results (sorted by student, exercise), the files written (each student's
    total among them: :class:`~..output.writer.Written`), and the sandbox and key the run used."""

    results: list[NotebookResult]
    files: Written
    box: Sandbox
    key: Secret


@dataclass(frozen=True)
class _Run:
    """What :func:`grade_run` chose once for the run, handed to :func:`_grade_class` with the settings."""

    key: Secret
    box: Sandbox
    names: list[str]
    groups: limits.Run
    students: list[StudentFolder]
    collected: Collected | None


_DEFAULTS = (None, None, 2, 10.0, 60.0, None, None, None, "auto", 120.0, (), True, None, None)


def grade(
    submissions: GradeSettings | str | os.PathLike[str],
    output: str | os.PathLike[str] | None = None,
    feedback: str | os.PathLike[str] | None = None,
    jobs: int = 2,
    timeout_cell: float = 10.0,
    timeout_total: float = 60.0,
    seed: int | None = None,
    exercises: Sequence[str] | None = None,
    progress: Callable[[NotebookResult], None] | None = None,
    *,
    sandbox: str | Sandbox = "auto",
    timeout_student: float = 120.0,
    private: Sequence[str | os.PathLike[str]] = (),
    cgroups: bool | limits.Run = True,
    secret: Secret | str | os.PathLike[str] | None = None,
    collected: Collected | None = None,
) -> list[NotebookResult]:
    """Grade ``submissions/<student>/<exercise>.ipynb`` for every student folder and exercise.

    ``grade(settings)`` takes a :class:`~..settings.GradeSettings` (everything a run needs, the written marks,
    gradebooks and question bank among them); the keyword form ``grade(submissions, output, feedback=..., ...)``
    builds one from its arguments. Either way :func:`grade_run` grades and :func:`~..output.writer.write_run`
    writes every file once, from the same merged results.

    Writes ``output`` (CSV: see :func:`~puma_course.grading.output.report.write_csv`), the class summary next
    to it (:func:`~.summary.write_summary`) and, if ``feedback`` is given, one Markdown file per student.
    ``sandbox`` is "auto" (bubblewrap where it runs, else none with a :class:`SandboxWarning`), "bwrap",
    "none", or a :class:`~.sandbox.Sandbox` chosen earlier; ``timeout_student`` caps the time of all of
    a student's notebooks together;
    ``private`` names more folders the sandbox must hide (the course's ``solutions/``, say).
    ``cgroups`` True puts each notebook in a control group of its own with limits for its whole process
    tree (:mod:`.limits`; where that cannot be done here: a :class:`LimitsWarning` and the CSV's ``limits``
    column say so), False does not try, or a :class:`~.limits.Run` opened earlier is used (and not closed).

    Each student's hidden inputs are their own, drawn from ``secret`` (a key, or the instructor's key
    file; ``seed``: a public key; neither: a one-off key; :func:`~.secret.choose_key`, :func:`make_plan`).

    ``collected`` is a platform's download read by :func:`~.collect.collect` (``submissions`` is then
    its folder): its students are graded instead of the folder's sub-folders, and the CSV gains a
    ``late`` column. Returns the results (sorted by student, exercise).
    """
    given: tuple[object, ...] = (output, feedback, jobs, timeout_cell, timeout_total, seed, exercises, progress)
    given += (sandbox, timeout_student, tuple(private), cgroups, secret, collected)
    if isinstance(submissions, GradeSettings):
        if given != _DEFAULTS:
            raise ValueError("grade: expected either a GradeSettings alone or the keyword arguments, got both")
        return grade_run(submissions).results
    if output is None:
        raise ValueError("output: expected the path of the grades CSV, got None")
    settings = GradeSettings(
        submissions,
        output,
        feedback=feedback,
        jobs=jobs,
        timeout_cell=timeout_cell,
        timeout_total=timeout_total,
        timeout_student=timeout_student,
        seed=seed,
        secret=secret,
        sandbox=sandbox,
        private=private,
        cgroups=cgroups,
        exercises=exercises,
        collected=collected,
        progress=progress,
    )
    return grade_run(settings).results


def grade_run(settings: GradeSettings) -> Graded:
    """Grade the class ``settings`` describe and write its files (:func:`~..output.writer.write_run`).

    Before any notebook runs, in this order: the bank (``settings.bank``), the exercises, the students (the
    folder's or the platform download's), the written marks (a bad marks file is a ``ValueError`` naming its
    row and column, and nothing is graded), Moodle's roster, the key (once) and the sandbox (once).
    """
    use_bank(settings.bank)
    sub_dir = settings.submissions
    names = list(settings.exercises) or list(EXERCISES)
    times = {
        "timeout_cell": settings.timeout_cell,
        "timeout_total": settings.timeout_total,
        "timeout_student": settings.timeout_student,
    }
    check_args(sub_dir, names, settings.jobs, times)
    collected = settings.collected
    if collected is None and settings.layout != "folders":
        collected = collect(sub_dir, settings.layout, names)
    try:
        students = scan(sub_dir) if collected is None else collected.folders()
    except OSError as exc:
        raise ValueError(f"submissions: expected a readable folder, got {str(sub_dir)!r} ({exc.strerror})") from None
    marks = read_marks(settings.marks, [s.name for s in students], names) if settings.marks else None
    if settings.shard is not None:  # part K of N: the students whose name hashes to it (marks checked for all)
        students = [s for s in students if settings.shard.owns(s.name)]
    roster = read_roster(settings.roster) if settings.roster is not None else None
    key = choose_key(settings.secret, settings.seed)
    box = _box(settings.sandbox)
    if box.kind != "bwrap":
        warnings.warn(f"grading WITHOUT the operating-system sandbox: {box.reason}", SandboxWarning, stacklevel=3)
    cgroups = settings.cgroups
    groups = cgroups if isinstance(cgroups, limits.Run) else limits.open_run(enabled=bool(cgroups))
    try:
        results, kept = _grade_class(settings, _Run(key, box, names, groups, students, collected))
        limits_label = f"{groups.label}; {limits.call_limit(groups, settings.timeout_cell)}"
    finally:
        if not isinstance(cgroups, limits.Run):
            groups.close()
    facts = RunFacts(tuple(names), key, box, limits_label, collected, find_copies(kept))
    files = write_run(
        results,
        settings.output,
        facts,
        feedback=settings.feedback,
        marks=marks,
        gradebooks=settings.gradebooks,
        roster=roster,
    )
    if settings.shard is not None:
        files.shard = write_shard(
            settings.shard_file or shard_path(settings.output),
            ShardFile(
                settings.shard,
                key.fingerprint,
                __version__,
                tuple(names),
                tuple(s.name for s in students),
                tuple(results),
                run_facts(key, box, limits_label, settings.layout),
                tuple(dataclasses.asdict(h) for h in kept),
            ),
        )
    return Graded(results, files, box, key)


def _grade_class(settings: GradeSettings, run: _Run) -> tuple[list[NotebookResult], list[Handed]]:
    """Grade every student's notebooks (``settings.jobs`` students at a time); the results, sorted, and each
    notebook's own code for the copy report."""
    sub_dir, key, box, names, groups, collected = (
        settings.submissions, run.key, run.box, run.names, run.groups, run.collected
    )  # fmt: skip
    jobs, timeout_cell, timeout_total = settings.jobs, settings.timeout_cell, settings.timeout_total
    timeout_student, progress, feedback = settings.timeout_student, settings.progress, settings.feedback
    if not groups.enforced:
        warnings.warn(
            f"notebook limits: {groups.label}; {limits.call_limit(groups, timeout_cell)}", LimitsWarning, stacklevel=4
        )
    groups.share(jobs)

    def read(s: StudentFolder) -> StudentFiles:
        return read_student(sub_dir, s, names) if collected is None else collected.read(s, names)

    students = run.students
    package_before = package_digest(_PACKAGE_DIR, EXERCISES.course)
    hidden = [_PACKAGE_DIR, *_checkouts(), sub_dir, settings.output, *settings.private]
    hidden += [Path(feedback)] if feedback is not None else []
    hidden += [Path(key.source)] if key.seed is None and key.source not in ("", "one-off") else []
    stage_in = box.scratch.path if box.scratch else None
    with Stage([EXERCISES[n] for n in names], stage_in) as stage, undumpable(box.kind != "bwrap"):
        hidden.append(stage.root)
        pre: dict[str, StudentFiles] = {}
        kept: list[Handed] = []  # each notebook's own code, for the copy report (read from the bytes graded)
        if box.kind != "bwrap":
            # no sandbox: read what fits in memory before any student code runs, so that a student's
            # process cannot alter what is graded for a classmate it runs before
            used = 0
            for s in students:
                files = read(s)
                used += sum(len(nb.data or b"") for nb in files.notebooks.values())
                if used > PRE_READ_BYTES:
                    break
                pre[s.raw] = files

        def work(s: StudentFolder) -> list[NotebookResult]:
            files = pre.pop(s.raw, None) or read(s)
            # the student's notebooks together: timeout_student s of their own time (CPU time, and wall-clock
            # time less the waits for a CPU others held: monitor.Watch), so a busy machine costs them nothing
            spent: list[float] = []
            out = []
            for name in names:
                ex, nb = EXERCISES[name], files.notebooks[name]
                try:
                    left = timeout_student - sum(spent)
                    if nb.state != "read" or nb.data is None:
                        res = _blank(s.name, ex, nb.state, nb.note)
                        if nb.state == "missing" and files.others:
                            res.notes.append(
                                f"notebooks found under other names: {', '.join(files.others)} "
                                f"(name the file exactly {name}.ipynb)"
                            )
                    elif left < 0.5:
                        note = (
                            f"not run: this student's notebooks already used their total time ({timeout_student:g} s)"
                        )
                        res = _blank(s.name, ex, "timeout", note)
                    else:
                        # this notebook's expected values, the student's own, drawn now (by this thread, while
                        # other students' notebooks run) and dropped once it is judged; a plan that cannot be
                        # made is the grader's error on this notebook, and the class goes on
                        try:
                            with _PLANNING:
                                plan = make_plan(ex, key, s.name)
                        except Exception as exc:  # noqa: BLE001 - a bank bug must not stop the class
                            why = f"{type(exc).__name__}: {exc}"[:300]
                            plan, note = None, f"the grader could not draw this notebook's cases: {why}"
                        if plan is None:
                            res = _blank(s.name, ex, "grader-error", note)
                        else:
                            limit = min(timeout_total, left)
                            note = stop_note(limit, limit < timeout_total)
                            res = grade_data(
                                nb.data, ex, s.name, plan, stage, box, timeout_cell, limit, note, hidden, groups,
                                limit, spent,
                            )  # fmt: skip
                        del plan
                except Exception as exc:  # noqa: BLE001 - one broken submission must not stop the class
                    why = f"{type(exc).__name__}: {exc}"[:300]
                    res = _blank(s.name, ex, "grader-error", f"the grader failed on this notebook: {why}")
                if nb.data is not None:
                    kept.append(handed(nb.data, ex, s.name))
                nb.data = None
                res.run_id = key.run_id(s.name, name)
                out.append(res)
                if progress is not None:
                    progress(res)
            return out

        with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
            results = [r for batch in pool.map(work, students) for r in batch]
        changed = [f"grading stage: {p}" for p in stage.changed()]
    results.sort(key=lambda r: (r.student, r.exercise))
    package_after = package_digest(_PACKAGE_DIR, EXERCISES.course)
    changed += sorted(
        k for k in set(package_before) | set(package_after) if package_before.get(k) != package_after.get(k)
    )
    if changed:
        warnings.warn(
            f"the puma_course package files changed while grading ({', '.join(changed)}); a submission "
            "may have tampered with them, so the grades of notebooks graded afterwards are not reliable. "
            "Grade with the sandbox, as a user who cannot write the package.",
            GradingIntegrityWarning,
            stacklevel=4,
        )
    return results, kept
