"""An honest, slowish notebook keeps its marks on a busy machine (issue 30): the limits count its own time.

Four busy processes run beside the grader (started here, ended by their process ids). The notebook is ex01's
solution whose graded functions each burn 0.05 s of CPU first (the hostile harness's slowish classmate): alone
it needs about 3 s; beside the busy processes its wall-clock time stretches past the 6 s notebook limit, while
its CPU time and its own wall-clock time (less its waits for a CPU, grading/run/monitor.py) do not. Graded with
the notebook's control group (CPU counter) where there is one, and without (the /proc process tree).
"""

from __future__ import annotations

import subprocess
import sys

import nbformat
import pytest

from puma_course.grading import EXERCISES, grade
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
