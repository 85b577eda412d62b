"""An honest, slowish notebook keeps its marks on a busy machine (issue 30): the limits count its own time.

Four busy processes run beside the grader (started here, ended by their process ids). The notebook is ex01's
solution whose graded functions each burn 0.05 s of CPU first (the hostile harness's slowish classmate): alone
it needs about 3 s; beside the busy processes its wall-clock time stretches past the 6 s notebook limit, while
its CPU time and its own wall-clock time (less its waits for a CPU, grading/run/monitor.py) do not. Graded with
the notebook's control group (CPU counter) where there is one, and without (the /proc process tree).

On a crowded CPU (the notebook pinned to one core beside six busy processes: a seventh of a core, as at a load of
14 on 2 cores) its 3.5 s of CPU take about 25 s of wall clock, past the old wall-clock cap of 3 x 6 + 1 s that
ended it (``timeout``, 14.14/15, its own time 5.0 s of 6); the cap is now lengthened by its waits for a CPU
during the grader's calls (grading/run/monitor.py ``Watch.credit``).
"""

from __future__ import annotations

import os
import subprocess
import sys

import nbformat
import pytest

from puma_course.grading import EXERCISES, grade
from puma_course.grading.run import limits, monitor
from puma_course.grading.run.limits import open_run
from tests.grading.hostile.harness import SLOWISH, _functions
from tests.support import ROOT

# CI's second pass (another OpenBLAS kernel) leaves this out: marks kept beside busy processes: a test of the limits
# under load, not of numerics.
pytestmark = pytest.mark.no_numerics

EX = "ex01_rotations"


@pytest.mark.parametrize("groups", [True, False], ids=["cgroup", "proc-tree"])
def test_an_honest_slow_notebook_keeps_its_marks_beside_busy_processes(tmp_path, groups):
    subs = tmp_path / "subs"
    (subs / "slowish").mkdir(parents=True)
    nb = nbformat.read(ROOT / "solutions" / f"{EX}.ipynb", as_version=4)
    nb.cells.append(nbformat.v4.new_code_cell(SLOWISH.format(functions=_functions(EX))))
    nbformat.write(nb, subs / "slowish" / f"{EX}.ipynb")
    run = open_run(memory=1 << 30) if groups else open_run(enabled=False)
    if groups and not run.enforced:
        pytest.skip(f"no control groups here: {run.reason}")
    busy = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(4)]
    try:
        results = grade(
            subs, tmp_path / "g.csv", exercises=[EX], sandbox="none", cgroups=run, jobs=1, seed=5,
            timeout_cell=1.0, timeout_total=6.0, timeout_student=12.0,
        )  # fmt: skip
    finally:
        for p in busy:
            p.kill()
            p.wait()
        run.close()
    r = results[0]
    print(f"\nslowish beside 4 busy processes ({'cgroup' if groups else '/proc tree'}): {r.seconds:.1f} s wall")
    full = sum(q.points for q in EXERCISES[EX].questions)
    assert (r.status, r.score) == ("ok", full), (r.status, r.notes, r.question_notes)


def _slowish(tmp_path):
    subs = tmp_path / "subs"
    (subs / "slowish").mkdir(parents=True)
    nb = nbformat.read(ROOT / "solutions" / f"{EX}.ipynb", as_version=4)
    nb.cells.append(nbformat.v4.new_code_cell(SLOWISH.format(functions=_functions(EX))))
    nbformat.write(nb, subs / "slowish" / f"{EX}.ipynb")
    return subs


@pytest.mark.skipif(not hasattr(os, "sched_setaffinity"), reason="no CPU affinity here")
@pytest.mark.parametrize("groups", [True, False], ids=["cgroup", "proc-tree"])
def test_an_honest_slow_notebook_keeps_its_marks_on_a_crowded_cpu(tmp_path, groups, monkeypatch):
    subs = _slowish(tmp_path)
    run = open_run(memory=1 << 30) if groups else open_run(enabled=False)
    if groups and not run.enforced:
        pytest.skip(f"no control groups here: {run.reason}")
    core = min(os.sched_getaffinity(0))
    pinned = f"import os\nos.sched_setaffinity(0, {{{core}}})\nwhile True: pass"
    begin, close, seen, busy = monitor.Watch.begin, monitor.Watch.close, [], []

    def crowded(self, now, pid):
        # the worker, and whatever it starts, on one core beside six busy processes, each in a session of its own
        # (one scheduler autogroup each: each weighs as one process); the grader is not pinned
        busy.extend(subprocess.Popen([sys.executable, "-c", pinned], start_new_session=True) for _ in range(6))
        os.sched_setaffinity(pid, {core})
        begin(self, now, pid)
        seen.append(self)

    def calm(self):
        close(self)
        for p in busy:
            p.kill()
            p.wait()

    monkeypatch.setattr(monitor.Watch, "begin", crowded)
    monkeypatch.setattr(monitor.Watch, "close", calm)
    try:
        results = grade(
            subs, tmp_path / "g.csv", exercises=[EX], sandbox="none", cgroups=run, jobs=1, seed=5,
            timeout_cell=1.0, timeout_total=6.0, timeout_student=12.0,
        )  # fmt: skip
    finally:
        for p in busy:
            p.kill()
            p.wait()
        run.close()
    r, w = results[0], seen[-1]
    print(
        f"\nslowish on a core beside 6 busy processes ({'cgroup' if groups else '/proc tree'}): {w.elapsed:.1f} s wall,"
        f" {w.used:.2f} s CPU, {w.own:.2f} s its own, waits {w.waits.last:.1f} s ({w.credit:.1f} s during calls)"
    )
    full = sum(q.points for q in EXERCISES[EX].questions)
    assert (r.status, r.score) == ("ok", full), (r.status, r.notes, r.question_notes)
    # the crowding was real: past the wall-clock cap the notebook had before (3 x 6 + 1 s)
    assert w.elapsed > limits.WALL_FACTOR * 6.0 + 1.0, w.elapsed
