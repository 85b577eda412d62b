"""One notebook through one worker: its job line, its sandbox and control group, its events scored.

:func:`grade_data` grades a notebook's bytes (the runner's :func:`~.runner.grade_notebook` and
:func:`~.runner.grade` call it): :func:`run_worker` starts a fresh worker (:mod:`.child`) under the
sandbox (:mod:`.sandbox`), in a control group of its own when the run has them (:mod:`.limits`),
feeds it :func:`job_line` (what to call, never what is expected) and the notebook, and :mod:`.events`
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

from ..output.text import quoted
from ..plan import Plan
from ..results import NotebookResult
from ..spec import Exercise
from . import child, events, limits, monitor, worker
from . import limits as limits_mod
from .sandbox import Sandbox, child_env
from .stage import Stage

__all__ = ["LIMITS", "grade_data", "job_line", "run_worker"]

#: Limits the worker sets on itself (see :func:`puma_course.grading.run.worker.limit_resources`).
LIMITS = {"memory": 4 << 30, "file_size": 64 << 20, "open_files": 256, "processes": 64}


def job_line(
    exercise: Exercise,
    plan: Plan,
    timeout_cell: float,
    timeout: float,
    paths: list[str],
    nproc: bool,
    clock: tuple[int, str] = (-1, ""),
    size: int = 0,
) -> bytes:
    """The worker's first line: its limits, its import path, the size of the notebook that follows (the calls
    follow one at a time, :func:`calls`: what to call, never what is expected).

    The process limit is set only inside the sandbox's user namespace, where it counts the worker's
    own processes; outside, it would count every process of the grading user. ``clock`` is the
    descriptor and format of the notebook group's CPU time counter (:meth:`.limits.Group.cpu_clock`):
    each cell and call is then limited to ``timeout_cell`` s of CPU time, with a wall-clock backstop.
    """
    limits: dict[str, Any] = {**LIMITS, "cpu_seconds": int(timeout) + 2}
    if not nproc:
        limits.pop("processes")
    job: dict[str, Any] = {
        "notebook_bytes": size,
        "timeout_cell": timeout_cell,
        "wall": limits_mod.WALL_FACTOR * timeout_cell,
        "max_size": worker.MAX_SIZE,
        "forbidden": {q.qid: list(q.forbidden) for q in exercise.questions if q.forbidden},
        "path": paths,
        "limits": limits,
        "filename": f"{exercise.name}.ipynb",
    }
    if clock[0] >= 0:
        job["cpu_clock"] = {"fd": clock[0], "format": clock[1], "wall": limits_mod.WALL_FACTOR * timeout_cell}
    return json.dumps(job).encode() + b"\n"


def calls(plan: Plan) -> list[bytes]:
    """The worker's calls, one JSON line each (sent one at a time: :func:`.child.run`)."""
    return [json.dumps(item.job()).encode() + b"\n" for item in plan]


def run_worker(
    data: bytes,
    exercise: Exercise,
    plan: Plan,
    stage: Stage,
    box: Sandbox,
    timeout_cell: float,
    timeout: float,
    private: Sequence[Path],
    groups: limits.Run | None = None,
    wall: float | None = None,
) -> child.ChildResult:
    """One worker on one notebook: under bubblewrap its work folder is the sandbox's own, else a fresh temporary one.

    With ``groups`` (the run's control groups, :mod:`.limits`) the worker starts inside a fresh group of its
    own, and whatever of its process tree is left when it ends is killed with the group. The grader keeps the
    limits (:mod:`.monitor`): ``timeout_cell`` s of CPU time per cell and call, ``timeout`` s per notebook, and
    ``wall`` s of its own wall-clock time (default ``timeout``; the time it waited for a CPU others held does
    not count), and :data:`.limits.WALL_FACTOR` times that on the wall clock, lengthened by its waits for a CPU
    during the grader's calls (:attr:`.monitor.Watch.credit`; at most :func:`.limits.hard_deadline` in all).
    """
    wall_total = timeout if wall is None else wall

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
                nproc = box.kind == "bwrap"
                job = job_line(exercise, plan, timeout_cell, timeout, paths, nproc, (clock, fmt), len(data))
                passed = tuple(f for f in (fd, clock) if f >= 0)
                fds: dict[str, Any] = {"pass_fds": passed} if passed else {}
                watch = monitor.Watch(lambda pid: monitor.meter_for(group, pid), timeout_cell, timeout, wall_total)
                return child.run(
                    cmd, job + data, cwd=work or "/", env=child_env(seen_work),
                    timeout=limits_mod.hard_deadline(wall_total, timeout),
                    calls=calls(plan), watch=watch, **fds,
                )  # fmt: skip
        finally:
            for f in (fd, clock):
                if f >= 0:
                    os.close(f)

    if box.kind == "bwrap":
        return launch(None)
    with tempfile.TemporaryDirectory(prefix="puma-grade-", ignore_cleanup_errors=True) as work:
        return launch(work)


def _run_to_the_end(data: bytes, plan: Plan, timeout: float, wall: float, run: Any) -> child.ChildResult:
    """The worker on ``plan``; when the grader had to end a call that did not stop (:mod:`.monitor`), that case
    fails on time, the question's other cases are skipped, and a fresh worker runs the notebook again for the
    questions after it, within what is left of the notebook's limits (``run(plan, cpu, wall)`` runs one)."""
    out = run(plan, timeout, wall)
    last = out
    while last.stopped is not None and last.stopped.what == "call" and 0 <= last.stopped.index < len(plan):
        item = plan[last.stopped.index]
        out.events.append({"kind": "call", "qid": item.qid, "case": item.case, "error": "timeout",
                           "clock": last.stopped.clock})  # fmt: skip
        rest = plan[last.stopped.index + 1 :]
        out.events += [{"kind": "call", "qid": c.qid, "case": c.case, "error": "skipped"} for c in rest
                       if c.qid == item.qid]  # fmt: skip
        plan = [c for c in rest if c.qid != item.qid]
        timeout, wall = timeout - last.cpu, wall - last.own
        out.notes.append(f"{item.qid}: the call kept running past its limit, and the grader ended it")
        if not plan:
            out.done = True
            break
        if min(timeout, wall) < 0.5:
            out.timed_out = True
            break
        last = run(plan, timeout, wall)
        out.events += [e for e in last.events if e.get("kind") in ("call", "done")]
        out.foreign += last.foreign
        out.overflow = out.overflow or last.overflow
        out.timed_out, out.done, out.returncode = last.timed_out, last.done, last.returncode
        out.cpu, out.own, out.seconds = out.cpu + last.cpu, out.own + last.own, out.seconds + last.seconds
        out.stopped = last.stopped if last.stopped is not None and last.stopped.what != "call" else None
    return out


def _stop_words(outcome: child.ChildResult, stop_note: str, timeout: float, wall: float) -> str:
    """Why the notebook was stopped, on the clock that ended it (``stop_note``: the runner's words)."""
    stopped = outcome.stopped
    if stopped is None or stopped.what != "notebook" or "this student's notebooks" in stop_note:
        return stop_note
    if stopped.clock == "cpu":
        return (
            f"the notebook ran longer than {timeout:g} s of CPU time in total and was stopped; "
            "answers that came back before that were graded"
        )
    if stopped.clock == "backstop":
        return (
            f"the notebook ran longer than {wall:g} s in total (its own time on the wall clock, waiting rather "
            "than computing) and was stopped; answers that came back before that were graded"
        )
    return stop_note


def grade_data(
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
    wall: float | None = None,
    spent: list[float] | None = None,
) -> NotebookResult:
    """Grade one notebook: ``timeout`` s of CPU time and ``wall`` s of its own wall-clock time at most (default
    ``timeout``; :mod:`.monitor`); the own wall-clock seconds it used are appended to ``spent``."""
    start = time.perf_counter()
    wall = timeout if wall is None else wall
    result = NotebookResult.blank(student, exercise)

    def run(part: Plan, cpu: float, clock: float) -> child.ChildResult:
        return run_worker(data, exercise, part, stage, box, timeout_cell, cpu, private, groups, clock)

    outcome = _run_to_the_end(data, plan, timeout, wall, run)
    if not outcome.timed_out and not any(e.get("kind") == "ready" for e in outcome.events):
        # the worker never started (the sandbox could not be set up, say): not the student's doing; once more
        outcome = _run_to_the_end(data, plan, timeout, wall, run)
        if not outcome.timed_out and not any(e.get("kind") == "ready" for e in outcome.events):
            said = outcome.stderr.decode("utf-8", "replace").strip().splitlines()
            result.status = "grader-error"
            result.notes.append(
                f"the grading process could not start (exit code {outcome.returncode})"
                + (f": {quoted(said[-1])}" if said else "")
            )
            result.seconds = time.perf_counter() - start
            return result
    note = _stop_words(outcome, stop_note, timeout, wall)
    events.apply(result, exercise, plan, outcome, timeout_cell=timeout_cell, stop_note=note)
    result.notes += outcome.notes
    if spent is not None:
        spent.append(max(outcome.own, outcome.cpu) if outcome.own or outcome.cpu else outcome.seconds)
    result.seconds = time.perf_counter() - start
    return result
