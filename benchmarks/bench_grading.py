"""Benchmark: grade a class with and without the OS sandbox; print seconds per notebook and the sandbox's cost.

    python benchmarks/bench_grading.py [--students 100] [--jobs 2] [--sandbox both|bwrap|none]
                                       [--overhead 20] [--kernel-sample 3] [--repeat 2]
    python benchmarks/bench_grading.py --plans-only 5    # each exercise's plan per student, nothing graded

Each student's folder holds, per exercise, one of: the solution, the solution with a bug
injected (a sign flipped in the first answer line that has a '+'), the untouched exercise
(stubs), or nothing (missing; not counted as submitted), so 100 students hand in 450 notebooks.
The class is graded once per sandbox ("none", then "bwrap" when bubblewrap runs here).

The sandbox's cost per notebook is measured twice: bubblewrap's own start-up (``python -c pass``
inside and outside the sandbox, best of 15), and whole notebooks (``--overhead`` copies of one
solution graded one at a time, with and without it, alternating, best of five runs each). Wall
times on a shared machine vary with its load: runs alternate between the sandboxes and the best
of ``--repeat`` counts.

It also times the grader's own steps that run no student code: the plan (every expected value,
computed from the question bank in the grader's process, :func:`puma_course.grading.run.runner.make_plan`),
building the stage (the worker and each exercise's student-side package) and the release check of
the course. For comparison it times executing a few notebooks in a fresh Jupyter kernel with
nbclient, the way nbgrader's autograde runs them. Figures are printed, never asserted.
"""

from __future__ import annotations

import argparse
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
import warnings
from pathlib import Path

import nbformat

from puma_course.grading import EXERCISES, grade, release
from puma_course.grading.run.runner import make_plan
from puma_course.grading.run.sandbox import Sandbox, child_env, choose
from puma_course.grading.run.stage import Stage
from puma_course.grading.secret import Secret

ROOT = Path(__file__).resolve().parent.parent


def _buggy(nb: nbformat.NotebookNode) -> nbformat.NotebookNode:
    nb = nbformat.from_dict(nb)
    for cell in nb.cells:
        if cell.cell_type == "code" and "### BEGIN SOLUTION" in cell.source:
            lines = cell.source.splitlines()
            for i, line in enumerate(lines):
                if " + " in line and "BEGIN" not in line:
                    lines[i] = line.replace(" + ", " - ", 1)
                    cell.source = "\n".join(lines)
                    return nb
    return nb


def build_class(folder: Path, students: int) -> int:
    """Write the class; return the number of submitted notebooks."""
    names = sorted(EXERCISES)
    submitted = 0
    for k in range(students):
        home = folder / f"student{k:03d}"
        home.mkdir(parents=True)
        for i, name in enumerate(names):
            variant = (k + i) % 4
            if variant == 3:
                continue  # missing
            if variant == 0:
                shutil.copy(ROOT / "solutions" / f"{name}.ipynb", home)
            elif variant == 1:
                nb = _buggy(nbformat.read(ROOT / "solutions" / f"{name}.ipynb", as_version=4))
                nbformat.write(nb, home / f"{name}.ipynb")
            else:
                shutil.copy(ROOT / "exercises" / f"{name}.ipynb", home)
            submitted += 1
    return submitted


def grade_class(students: int, jobs: int, box: Sandbox) -> tuple[float, int, dict[str, int]]:
    """(wall seconds, submitted notebooks, statuses) for one grading of the class under ``box``."""
    with tempfile.TemporaryDirectory() as tmp:
        subs = Path(tmp) / "submissions"
        n = build_class(subs, students)
        start = time.perf_counter()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            results = grade(
                subs, Path(tmp) / "grades.csv", feedback=Path(tmp) / "feedback", jobs=jobs, seed=1, sandbox=box
            )
        wall = time.perf_counter() - start
    statuses: dict[str, int] = {}
    for r in results:
        statuses[r.status] = statuses.get(r.status, 0) + 1
    return wall, n, statuses


def startup_cost(box: Sandbox, repeat: int = 15) -> tuple[float, float]:
    """(best seconds of ``python -c pass`` as the worker runs it without a sandbox, the same inside ``box``)."""
    with Stage([EXERCISES["ex01_rotations"]]) as stage:
        lib = stage.libs["ex01_rotations"]
        plain = [box.python, "-I", "-S", "-B", "-c", "pass"]
        boxed = [box.binary, *box.bwrap_args(lib, stage.bin), "--", box.seen(box.python), *plain[1:]]
        best = {"plain": float("inf"), "boxed": float("inf")}
        for _ in range(repeat):
            for key, cmd in (("plain", plain), ("boxed", boxed)):
                start = time.perf_counter()
                subprocess.run(cmd, check=True, env=child_env("/puma/work"), stdin=subprocess.DEVNULL)
                best[key] = min(best[key], time.perf_counter() - start)
    return best["plain"], best["boxed"]


def per_notebook(boxes: list[Sandbox], copies: int, rounds: int = 5) -> dict[str, float]:
    """Best seconds per notebook, one job, for ``copies`` copies of the exercise 1 solution, per sandbox."""
    times: dict[str, list[float]] = {b.kind: [] for b in boxes}
    with tempfile.TemporaryDirectory() as tmp:
        subs = Path(tmp) / "submissions"
        for k in range(copies):
            (subs / f"s{k:03d}").mkdir(parents=True)
            shutil.copy(ROOT / "solutions" / "ex01_rotations.ipynb", subs / f"s{k:03d}")
        for _ in range(rounds):
            for box in boxes:
                start = time.perf_counter()
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    grade(subs, Path(tmp) / "g.csv", jobs=1, seed=1, exercises=["ex01_rotations"], sandbox=box)
                times[box.kind].append((time.perf_counter() - start) / copies)
    return {kind: min(values) for kind, values in times.items()}


def time_kernel(sample: int) -> float:
    """Seconds per notebook when executing solutions in a fresh Jupyter kernel each (nbclient)."""
    from nbclient import NotebookClient

    paths = sorted((ROOT / "solutions").glob("*.ipynb"))[:sample]
    start = time.perf_counter()
    for path in paths:
        nb = nbformat.read(path, as_version=4)
        NotebookClient(nb, timeout=120, kernel_name="python3").execute()
    return (time.perf_counter() - start) / max(1, len(paths))


def time_grader_steps(repeat: int = 3) -> tuple[float, int, float, float]:
    """(seconds to plan every exercise, planned calls, seconds to build the stage, seconds for the release check)."""
    plan_s = stage_s = check_s = float("inf")
    calls = 0
    for _ in range(repeat):
        start = time.perf_counter()
        calls = sum(len(make_plan(ex, seed=1)) for ex in EXERCISES.values())
        plan_s = min(plan_s, time.perf_counter() - start)
        start = time.perf_counter()
        with Stage(EXERCISES.values()):
            stage_s = min(stage_s, time.perf_counter() - start)
        start = time.perf_counter()
        stale = release(ROOT / "solutions", ROOT / "exercises", check_only=True)
        check_s = min(check_s, time.perf_counter() - start)
        if stale:
            raise SystemExit(f"exercises out of date: {stale}")
    return plan_s, calls, stage_s, check_s


def time_plans(students: int = 5) -> dict[str, list[float]]:
    """Seconds to plan each exercise for each of ``students`` students under one key (their own hidden cases).

    The first student of each exercise also draws the public cases a bank draws on first use (ex10's paths)."""
    key = Secret(b"bench-grading-plans" * 2)
    out: dict[str, list[float]] = {}
    for name, ex in EXERCISES.items():
        for k in range(students):
            start = time.perf_counter()
            make_plan(ex, key, f"student-{k:03d}")
            out.setdefault(name, []).append(time.perf_counter() - start)
    return out


def print_plans(students: int) -> None:
    plans = time_plans(students)
    print(f"plan per student ({students} students under one key; ms, median and largest):")
    for name, times in plans.items():
        print(f"  {name:<22} {statistics.median(times) * 1e3:8.1f} {max(times) * 1e3:8.1f}")
    total = sum(statistics.median(t) for t in plans.values())
    print(f"  {'all exercises':<22} {total * 1e3:8.1f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--students", type=int, default=100)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--sandbox", choices=("both", "bwrap", "none"), default="both")
    parser.add_argument("--overhead", type=int, default=20, help="notebooks for the per-notebook cost (0: skip)")
    parser.add_argument("--kernel-sample", type=int, default=3, help="notebooks to time with nbclient (0: skip)")
    parser.add_argument("--repeat", type=int, default=2, help="gradings of the class per sandbox (the best counts)")
    parser.add_argument(
        "--plans-only", type=int, default=0, metavar="N", help="only time each exercise's plan for N students"
    )
    args = parser.parse_args()
    if args.plans_only:
        print_plans(args.plans_only)
        return
    bwrap = choose("auto")
    boxes = [choose("none")] if args.sandbox in ("both", "none") else []
    if args.sandbox in ("both", "bwrap"):
        if bwrap.kind == "bwrap":
            boxes.append(bwrap)
        else:
            print(f"bubblewrap cannot run here ({bwrap.reason}): graded without the sandbox only")
    print(f"python {sys.version.split()[0]}; sandbox: {bwrap.binary or bwrap.reason}")
    if bwrap.kind == "bwrap":
        plain, boxed = startup_cost(bwrap)
        print(
            f"sandbox start-up: `python -c pass` {plain * 1e3:.1f} ms bare, {boxed * 1e3:.1f} ms inside bubblewrap "
            f"(+{(boxed - plain) * 1e3:.1f} ms per notebook)"
        )
    if args.overhead and len(boxes) == 2:
        cost = per_notebook(boxes, args.overhead)
        print(
            f"per notebook (exercise 1 solution, 1 job, best of 5 x {args.overhead}): "
            f"{cost['none'] * 1e3:.0f} ms without the sandbox, {cost['bwrap'] * 1e3:.0f} ms with it "
            f"({(cost['bwrap'] - cost['none']) * 1e3:+.0f} ms, {cost['bwrap'] / cost['none']:.2f}x)"
        )
    per = {}
    for round_ in range(args.repeat):
        for box in boxes:  # alternating, so that a change of the machine's load hits both
            wall, n, statuses = grade_class(args.students, args.jobs, box)
            per[box.kind] = min(per.get(box.kind, float("inf")), wall / n)
            print(
                f"class of {args.students} students x {len(EXERCISES)} exercises, sandbox {box.kind} "
                f"(round {round_ + 1}): {n} submitted notebooks in {wall:.1f} s with {args.jobs} job(s), "
                f"{wall / n:.3f} s per notebook; statuses {statuses}"
            )
    if len(per) == 2:
        print(
            f"best per notebook: {per['none']:.3f} s without the sandbox, {per['bwrap']:.3f} s with it "
            f"({per['bwrap'] / per['none']:.2f}x); a class of 1,350 notebooks: about "
            f"{1350 * per['none']:.0f} s and {1350 * per['bwrap']:.0f} s with {args.jobs} job(s)"
        )
    plan_s, calls, stage_s, check_s = time_grader_steps()
    print(
        f"grader-side steps: plan of all {len(EXERCISES)} exercises ({calls} calls with expected values) "
        f"{plan_s * 1e3:.0f} ms; stage (worker + student-side packages) {stage_s * 1e3:.0f} ms; "
        f"release check of the course {check_s * 1e3:.0f} ms"
    )
    if args.kernel_sample and per:
        k = time_kernel(args.kernel_sample)
        best = per.get("bwrap", per.get("none", 0.0))
        print(
            f"for comparison, executing one notebook in a fresh Jupyter kernel (nbclient, serial, as nbgrader's "
            f"autograde does): {k:.2f} s per notebook, {k / best:.1f}x the grader's per-notebook cost with the sandbox"
        )


if __name__ == "__main__":
    main()
