"""Benchmark: what a hostile notebook costs the grader and can take from the machine, with and without limits.

    python benchmarks/bench_hostile.py [--memory-gib 1.2] [--seconds 10] [--sandbox auto|bwrap|none]

Three attacks from issue 21, each graded beside a classmate, figures printed (never asserted):

1. **Forged results**: the notebook writes straight into the result pipe one answer per IK case holding
   4,000 copies of a row (ex09 q1/q2) after a 1.9 MB line. Printed: the attacker's and an honest
   classmate's grading time, the grader's peak memory (resident, the whole process) and the time the
   grader spends judging the forged events (:func:`puma_course.grading.run.events.apply`), with the peak
   memory Python allocated in it.
2. **Memory**: three forks and the worker each fill ``--memory-gib`` GiB and hold it. Printed: the
   notebook's peak memory (its control group's ``max_usage``) with per-process limits only ("before": a
   group that only measures) and with the per-notebook limit (4 GiB), and whether the kernel ended a
   process of the notebook.
3. **CPU**: sixty busy children, each in its own session (``os.setsid()``), for ``--seconds`` seconds,
   beside a right but slowish classmate (each call burns 0.05 s of CPU). Printed: the CPU cores the
   attacker's tree took (CPU seconds of its group / wall seconds), and the classmate's score and time,
   without control groups (before: the kernel's per-session autogroups), with them but calls timed on the wall
   clock (the earlier design), and with calls timed on the group's CPU time (after); ``--timeout-cell`` sets
   the per-call limit (10 s by default; 0.2 s shows the clocks apart on a loaded machine).

Needs control groups (root, or a delegated subtree) for the "after" and for the measurements; says so and
skips those parts where it cannot.
"""

from __future__ import annotations

import argparse
import os
import resource
import sys
import tempfile
import time
import tracemalloc
import warnings
from pathlib import Path

import nbformat

from puma_course.grading import EXERCISES, grade
from puma_course.grading.results import NotebookResult
from puma_course.grading.run import limits as lim
from puma_course.grading.run.child import ChildResult
from puma_course.grading.run.events import apply
from puma_course.grading.run.runner import make_plan
from puma_course.grading.run.sandbox import choose

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from tests.grading.hostile.harness import SLOWISH  # noqa: E402  (the slowish classmate of the hostile tests, one cell)

FORGE = """
import json, os, time
lines = [json.dumps({"kind": "call", "qid": "q3", "case": 0, "value": [[0.5, 0.5]] * 160_000})]
for qid, width in (("q1", 3), ("q2", 6)):
    for case in range(8):
        rows = [[0.123456789012345] * width] * 4000
        lines.append(json.dumps({"kind": "call", "qid": qid, "case": case, "value": rows}))
data = memoryview("".join(l + "\\n" for l in lines).encode()[:15_000_000])
for fd in range(3, 64):
    try:
        if os.readlink(f"/proc/self/fd/{fd}").startswith("pipe:"):
            view = data
            while view:
                try:
                    view = view[os.write(fd, view):]
                except BlockingIOError:
                    time.sleep(0.001)
    except OSError:
        pass
"""

MEMORY = """
import os, time
r, w = os.pipe()
for _ in range(3):
    if os.fork() == 0:
        hog = b"\\x01" * int({gib} * (1 << 30))
        os.write(w, b"+")
        time.sleep(10)
        os._exit(0)
hog = b"\\x01" * int({gib} * (1 << 30))
time.sleep(10)
"""

CPU = """
import os, sys, time
for _ in range(60):
    try:
        if os.fork() == 0:
            os.setsid()
            os.execv(sys.executable, [sys.executable, "-c", "while True: pass"])
    except OSError:
        break
"""


def _notebook(base: str, exercise: str, cells: list[str], folder: Path) -> None:
    nb = nbformat.read(ROOT / base / f"{exercise}.ipynb", as_version=4)
    nb.cells += [nbformat.v4.new_code_cell(c) for c in cells]
    folder.mkdir(parents=True, exist_ok=True)
    nbformat.write(nb, folder / f"{exercise}.ipynb")


def _grade(subs: Path, exercise: str, box, groups, **times):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return grade(
            subs, subs.parent / "g.csv", jobs=2, seed=1, exercises=[exercise], sandbox=box, cgroups=groups, **times
        )


def _maxrss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def forged(box) -> None:
    print("\n1. forged results (ex09: 4,000 copies of a row per IK case, written into the result pipe)")
    with tempfile.TemporaryDirectory() as tmp:
        subs = Path(tmp, "subs")
        _notebook("exercises", "ex09_puma_ik", [FORGE], subs / "forger")
        _notebook("solutions", "ex09_puma_ik", [], subs / "honest")
        before = _maxrss_mb()
        results = _grade(subs, "ex09_puma_ik", box, True, timeout_cell=10, timeout_total=60)
        for r in results:
            print(f"   {r.student:>8}: {r.score:g}/{r.max_score:g} {r.status}, graded in {r.seconds:.2f} s")
        print(f"   grader peak resident memory: {_maxrss_mb():.0f} MB (before the run {before:.0f} MB)")
    ex = EXERCISES["ex09_puma_ik"]
    plan = make_plan(ex, 1)
    events = [{"kind": "ready"}]
    for qid, width in (("q1", 3), ("q2", 6)):
        for case in range(8):
            events.append({"kind": "call", "qid": qid, "case": case, "value": [[0.123456789012345] * width] * 4000})
    tracemalloc.start()
    t0 = time.perf_counter()
    apply(NotebookResult.blank("f", ex), ex, plan, ChildResult(events=events, done=True), timeout_cell=10, stop_note="")
    dt = time.perf_counter() - t0
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    print(f"   judging the forged events in the grader: {dt * 1000:.1f} ms, {peak / 1e6:.2f} MB allocated at peak")
    print("   (issue 21, before: 90-376 s per notebook, the grader's memory peaking at 3.16 GB)")


def memory(box, gib: float) -> None:
    print(f"\n2. memory: three forks and the worker each fill {gib:g} GiB ({4 * gib:g} GiB in all)")
    for label, limit in (("before (per-process limits only)", 1 << 42), ("after (per-notebook limit)", lim.MEMORY)):
        groups = lim.open_run(memory=limit, processes=lim.PROCESSES if limit == lim.MEMORY else 4096)
        if not groups.enforced:
            print(f"   {label}: NOT MEASURED, no control groups here ({groups.reason})")
            return
        with tempfile.TemporaryDirectory() as tmp:
            subs = Path(tmp, "subs")
            _notebook("exercises", "ex01_rotations", [MEMORY.format(gib=gib)], subs / "hog")
            try:
                _grade(subs, "ex01_rotations", box, groups, timeout_cell=20, timeout_total=30)
            finally:
                groups.close()
        u = max(groups.usages, key=lambda u: u.peak_memory)
        print(
            f"   {label}: the notebook's processes held {u.peak_memory / (1 << 30):.2f} GiB at peak; "
            f"processes ended by the kernel's OOM killer: {u.oom_kills}"
        )


def cpu(box, seconds: float, timeout_cell: float = 10.0) -> None:
    print(f"\n3. CPU: sixty setsid busy children for {seconds:g} s beside a slowish right classmate (ex01)")
    print(f"   each call of the classmate burns 0.05 s of CPU; the per-call limit is {timeout_cell:g} s")
    sleeps = [f"import time\ntime.sleep({min(2.5, seconds):g})"] * max(1, int(seconds / 2.5))
    functions = list(dict.fromkeys(q.function for q in EXERCISES["ex01_rotations"].questions))
    variants = (
        ("before (no control groups, calls on the wall clock)", False, False),
        ("groups, calls on the wall clock (the earlier design)", True, False),
        ("after (a group per notebook, calls on its CPU time)", True, True),
    )
    for label, enforce, cpu_clock in variants:
        measure = lim.open_run(
            memory=lim.MEMORY, processes=lim.PROCESSES if enforce else 4096, cpus=lim.CPUS if enforce else 64.0
        )
        real_clock = lim.Group.cpu_clock
        if not cpu_clock:
            lim.Group.cpu_clock = lambda self: (-1, "")  # type: ignore[method-assign]
        with tempfile.TemporaryDirectory() as tmp:
            subs = Path(tmp, "subs")
            _notebook("exercises", "ex01_rotations", [CPU, *sleeps], subs / "a_busy")
            _notebook("solutions", "ex01_rotations", [SLOWISH.format(functions=functions)], subs / "b_slowish")
            groups = measure if (enforce and measure.enforced) else False
            t0 = time.perf_counter()
            try:
                results = _grade(
                    subs,
                    "ex01_rotations",
                    box,
                    groups,
                    timeout_cell=timeout_cell,
                    timeout_total=seconds + 20,
                    timeout_student=seconds + 40,
                )
            finally:
                measure.close()
                lim.Group.cpu_clock = real_clock  # type: ignore[method-assign]
            wall = time.perf_counter() - t0
        slow = next(r for r in results if r.student == "b_slowish")
        busy = next(r for r in results if r.student == "a_busy")
        line = f"   {label}: slowish classmate {slow.score:g}/{slow.max_score:g} ({slow.status}, {slow.seconds:.1f} s)"
        if enforce and measure.usages:
            top = max(measure.usages, key=lambda u: u.cpu_seconds)
            line += (
                f"; the attacker's tree took {top.cpu_seconds / busy.seconds:.2f} CPU cores over {busy.seconds:.1f} s"
            )
        print(line + f" [run {wall:.1f} s]")


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--memory-gib", type=float, default=1.2)
    ap.add_argument("--seconds", type=float, default=10.0)
    ap.add_argument("--sandbox", default="auto")
    ap.add_argument("--only", choices=("forged", "memory", "cpu"), default=None)
    ap.add_argument("--timeout-cell", type=float, default=10.0, help="the per-call limit in part 3")
    args = ap.parse_args(argv)
    box = choose(args.sandbox)
    groups = lim.open_run()
    groups.close()
    print(f"sandbox: {box.kind}; limits: {groups.label}; CPUs: {os.cpu_count()}")
    if args.only in (None, "forged"):
        forged(box)
    if args.only in (None, "memory"):
        memory(box, args.memory_gib)
    if args.only in (None, "cpu"):
        cpu(box, args.seconds, args.timeout_cell)


if __name__ == "__main__":
    sys.exit(main())
