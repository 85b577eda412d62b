"""One notebook through one worker: its job line, its sandbox and control group, its events scored.

:func:`_grade_data` grades a notebook's bytes (the runner's :func:`~.runner.grade_notebook` and
:func:`~.runner.grade` call it): :func:`_run_worker` starts a fresh worker (:mod:`.child`) under the
sandbox (:mod:`.sandbox`), in a control group of its own when the run has them (:mod:`.limits`),
feeds it :func:`_job` (what to call, never what is expected) and the notebook, and :mod:`.events`
scores what comes back.
"""

from __future__ import annotations

import contextlib
import json
import os
import tempfile
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from ..model import Exercise, NotebookResult
from ..output.text import quoted
from ..plan import Plan
from . import child, events, limits, worker
from . import limits as limits_mod
from .sandbox import Sandbox, child_env
from .stage import Stage

__all__ = ["LIMITS"]

#: Limits the worker sets on itself (see :func:`puma_course.grading.run.worker.limit_resources`).
LIMITS = {"memory": 4 << 30, "file_size": 64 << 20, "open_files": 256, "processes": 64}


def _job(
    exercise: Exercise,
    plan: Plan,
    timeout_cell: float,
    timeout: float,
    paths: list[str],
    nproc: bool,
    clock: tuple[int, str] = (-1, ""),
) -> bytes:
    """The worker's first line: what to call (never what is expected), its limits, its import path.

    The process limit is set only inside the sandbox's user namespace, where it counts the worker's
    own processes; outside, it would count every process of the grading user. ``clock`` is the
    descriptor and format of the notebook group's CPU time counter (:meth:`.limits.Group.cpu_clock`):
    each cell and call is then limited to ``timeout_cell`` s of CPU time, with a wall-clock backstop.
    """
    limits: dict[str, Any] = {**LIMITS, "cpu_seconds": int(timeout) + 2}
    if not nproc:
        limits.pop("processes")
    job: dict[str, Any] = {
        "calls": [item.job() for item in plan],
        "timeout_cell": timeout_cell,
        "max_size": worker.MAX_SIZE,
        "forbidden": {q.qid: list(q.forbidden) for q in exercise.questions if q.forbidden},
        "path": paths,
        "limits": limits,
        "filename": f"{exercise.name}.ipynb",
    }
    if clock[0] >= 0:
        job["cpu_clock"] = {"fd": clock[0], "format": clock[1], "wall": limits_mod.WALL_FACTOR * timeout_cell}
    return json.dumps(job).encode() + b"\n"


def _run_worker(
    data: bytes,
    exercise: Exercise,
    plan: Plan,
    stage: Stage,
    box: Sandbox,
    timeout_cell: float,
    timeout: float,
    private: Sequence[Path],
    groups: limits.Run | None = None,
) -> child.ChildResult:
    """One worker on one notebook: under bubblewrap its work folder is the sandbox's own, else a fresh temporary one.

    With ``groups`` (the run's control groups, :mod:`.limits`) the worker starts inside a fresh group of its
    own, and whatever of its process tree is left when it ends is killed with the group.
    """

    def launch(work: str | None) -> child.ChildResult:
        lib, _, seen_work = box.paths(stage.libs[exercise.name], stage.bin, Path(work or "."))
        # fd: bubblewrap's --args file; cwd "/": the launcher's shell would export the grader's folder as PWD
        cmd, fd = box.launch(stage.libs[exercise.name], stage.bin, private)
        clock = -1
        try:
            with groups.notebook() if groups is not None else contextlib.nullcontext() as group:
                cmd = group.wrap(cmd) if group is not None else cmd
                clock, fmt = group.cpu_clock() if group is not None else (-1, "")  # calls timed on CPU time
                paths = [lib, *box.seen_sites]
                job = _job(exercise, plan, timeout_cell, timeout, paths, box.kind == "bwrap", (clock, fmt))
                passed = tuple(f for f in (fd, clock) if f >= 0)
                fds: dict[str, Any] = {"pass_fds": passed} if passed else {}
                return child.run(cmd, job + data, cwd=work or "/", env=child_env(seen_work), timeout=timeout, **fds)
        finally:
            for f in (fd, clock):
                if f >= 0:
                    os.close(f)

    if box.kind == "bwrap":
        return launch(None)
    with tempfile.TemporaryDirectory(prefix="puma-grade-", ignore_cleanup_errors=True) as work:
        return launch(work)


def _grade_data(
    data: bytes,
    exercise: Exercise,
    student: str,
    plan: Plan,
    stage: Stage,
    box: Sandbox,
    timeout_cell: float,
    timeout: float,
    stop_note: str,
    private: Sequence[Path] = (),
    groups: limits.Run | None = None,
) -> NotebookResult:
    start = time.perf_counter()
    result = NotebookResult.blank(student, exercise)
    outcome = _run_worker(data, exercise, plan, stage, box, timeout_cell, timeout, private, groups)
    if not outcome.timed_out and not any(e.get("kind") == "ready" for e in outcome.events):
        # the worker never started (the sandbox could not be set up, say): not the student's doing; once more
        outcome = _run_worker(data, exercise, plan, stage, box, timeout_cell, timeout, private, groups)
        if not outcome.timed_out and not any(e.get("kind") == "ready" for e in outcome.events):
            said = outcome.stderr.decode("utf-8", "replace").strip().splitlines()
            result.status = "grader-error"
            result.notes.append(
                f"the grading process could not start (exit code {outcome.returncode})"
                + (f": {quoted(said[-1])}" if said else "")
            )
            result.seconds = time.perf_counter() - start
            return result
    events.apply(result, exercise, plan, outcome, timeout_cell=timeout_cell, stop_note=stop_note)
    result.seconds = time.perf_counter() - start
    return result
