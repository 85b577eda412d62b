"""Benchmark: grade a class of 20 students (6 exercises each) and print seconds per submitted notebook.

    python benchmarks/bench_grading.py [--students 20] [--jobs 2] [--kernel-sample 3]

Each student's folder holds, per exercise, one of: the solution, the solution with a bug
injected (a sign flipped in the first answer line that has a '+'), the untouched exercise
(stubs), or nothing (missing; not counted as submitted). It also times the grader's own
steps that run no student code: the plan (every expected value, computed from the question
bank in the grader's process, :func:`puma_course.grading.runner.make_plan`) and the release
check of the course (:func:`puma_course.grading.release`). For comparison it times executing
a few notebooks in a fresh Jupyter kernel with nbclient, the obvious alternative to the plain
`python` worker (:mod:`puma_course.grading.worker`) the grader uses. Figures are printed,
never asserted.
"""

from __future__ import annotations

import argparse
import shutil
import tempfile
import time
from pathlib import Path

import nbformat

from puma_course.grading import EXERCISES, grade, release
from puma_course.grading.runner import make_plan

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
        home = folder / f"student{k:02d}"
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


def time_kernel(sample: int) -> float:
    """Seconds per notebook when executing solutions in a fresh Jupyter kernel each (nbclient)."""
    from nbclient import NotebookClient

    paths = sorted((ROOT / "solutions").glob("*.ipynb"))[:sample]
    start = time.perf_counter()
    for path in paths:
        nb = nbformat.read(path, as_version=4)
        NotebookClient(nb, timeout=120, kernel_name="python3").execute()
    return (time.perf_counter() - start) / max(1, len(paths))


def time_grader_steps(repeat: int = 3) -> tuple[float, int, float]:
    """(seconds to plan every exercise, number of planned calls, seconds for the release check), best of ``repeat``."""
    plan_s = check_s = float("inf")
    calls = 0
    for _ in range(repeat):
        start = time.perf_counter()
        calls = sum(len(make_plan(ex, seed=1)) for ex in EXERCISES.values())
        plan_s = min(plan_s, time.perf_counter() - start)
        start = time.perf_counter()
        stale = release(ROOT / "solutions", ROOT / "exercises", check_only=True)
        check_s = min(check_s, time.perf_counter() - start)
        if stale:
            raise SystemExit(f"exercises out of date: {stale}")
    return plan_s, calls, check_s


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--students", type=int, default=20)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--kernel-sample", type=int, default=3, help="notebooks to time with nbclient (0: skip)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        subs = Path(tmp) / "submissions"
        n = build_class(subs, args.students)
        start = time.perf_counter()
        results = grade(subs, Path(tmp) / "grades.csv", feedback=Path(tmp) / "feedback", jobs=args.jobs, seed=1)
        wall = time.perf_counter() - start
    statuses: dict[str, int] = {}
    for r in results:
        statuses[r.status] = statuses.get(r.status, 0) + 1
    per = wall / n
    print(f"{args.students} students x {len(EXERCISES)} exercises: {n} submitted notebooks, statuses {statuses}")
    print(f"grading wall time {wall:.2f} s with {args.jobs} job(s): {per:.3f} s per submitted notebook")
    plan_s, calls, check_s = time_grader_steps()
    print(
        f"grader-side steps: plan of all {len(EXERCISES)} exercises ({calls} calls with expected values) "
        f"{plan_s * 1e3:.0f} ms; release check of the course {check_s * 1e3:.0f} ms"
    )
    if args.kernel_sample:
        k = time_kernel(args.kernel_sample)
        print(
            f"for comparison, executing one notebook in a fresh Jupyter kernel (nbclient, serial): {k:.2f} s "
            f"per notebook, {k / per:.1f}x the grader's per-notebook cost"
        )


if __name__ == "__main__":
    main()
