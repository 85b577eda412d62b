"""grading.run.runner and .child: the plan stays here, the worker runs the stage's copy, nothing waits or crashes."""

from __future__ import annotations

import json
import os
import sys
import time
from pathlib import Path

import nbformat
import numpy as np
import pytest

from puma_course.grading import EXERCISES, Exercise, Question, grade, grade_notebook
from puma_course.grading.run import child as child_mod
from puma_course.grading.run import runner
from puma_course.grading.run.runner import make_plan
from puma_course.grading.run.sandbox import Sandbox, child_env, choose
from puma_course.grading.run.stage import Stage
from tests.support import ROOT

# CI's second pass (another OpenBLAS kernel) leaves this out: the grading plan, the worker's pipes and time limits:
# no numerics.
pytestmark = pytest.mark.no_numerics

EX = EXERCISES["ex01_rotations"]


def test_hidden_inputs_depend_on_the_seed_and_are_reproducible():
    a, b, c = make_plan(EX, 1), make_plan(EX, 1), make_plan(EX, 2)
    assert [x.args for x in a] == [x.args for x in b]
    assert [x.args for x in a] != [x.args for x in c]


def test_the_worker_never_receives_expected_values(monkeypatch, tmp_path):
    seen = {}

    def fake_run(cmd, payload, *, cwd, env, timeout, calls=(), watch=None, **kw):
        seen["payload"], seen["env"], seen["calls"] = payload, env, calls
        return child_mod.ChildResult()

    monkeypatch.setattr(child_mod, "run", fake_run)
    sub = tmp_path / "ex01_rotations.ipynb"
    nbformat.write(nbformat.v4.new_notebook(), sub)
    result = grade_notebook(sub, EX, "s", seed=1)
    assert result.status == "grader-error" and result.score == 0  # no worker answered at all: not the student's doing
    header, _, notebook = seen["payload"].partition(b"\n")
    job = json.loads(header)
    # the calls travel one at a time, after the notebook (child.run hands each over once the one before is answered)
    calls = [json.loads(line) for line in seen["calls"]]
    assert "calls" not in job and job["notebook_bytes"] == len(notebook)
    assert calls and all(set(c) == {"qid", "case", "function", "args"} for c in calls)
    assert b"expected" not in header + b"".join(seen["calls"]) and notebook == sub.read_bytes()
    # the grader's environment does not travel either
    assert "PATH" in seen["env"] and not set(seen["env"]) - {
        "PATH",
        "HOME",
        "TMPDIR",
        "MPLBACKEND",
        "MPLCONFIGDIR",
        "PYTHONHASHSEED",
        "OMP_NUM_THREADS",
        "OPENBLAS_NUM_THREADS",
        "MKL_NUM_THREADS",
        "PYTHONDONTWRITEBYTECODE",
        "LANG",
        "LC_ALL",
        "OPENBLAS_CORETYPE",
    }


def _worker(cells, calls, exercise=EX, sandbox: Sandbox | None = None, timeout=30.0):
    """Run the stage's worker on a notebook of ``cells``; return its events."""
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(c) for c in cells])
    box = sandbox or choose("none")
    with Stage([exercise]) as stage:
        lib, _, _ = box.paths(stage.libs[exercise.name], stage.bin, Path("."))
        job = {"calls": calls, "timeout_cell": 10, "path": [lib, *box.seen_sites], "filename": "nb.ipynb"}
        payload = json.dumps(job).encode() + b"\n" + nbformat.writes(nb).encode()
        cwd = None if box.kind == "bwrap" else str(stage.root)
        env = child_env("/puma/work" if box.kind == "bwrap" else str(stage.root))
        return child_mod.run(
            box.command(stage.libs[exercise.name], stage.bin), payload, cwd=cwd, env=env, timeout=timeout
        )


def test_a_worker_that_cannot_start_is_the_graders_error_not_the_students(tmp_path, monkeypatch):
    sub = tmp_path / "ex01_rotations.ipynb"
    nbformat.write(nbformat.v4.new_notebook(), sub)
    broken = Sandbox("bwrap", "/bin/sh", sites=choose("none").sites)
    monkeypatch.setattr(
        Sandbox,
        "launch",
        lambda self, *a, **k: (["/bin/sh", "-c", "echo 'bwrap: no user namespaces' >&2; exit 1"], -1),
    )
    r = grade_notebook(sub, EX, "s", sandbox=broken)
    assert r.status == "grader-error" and "could not start (exit code 1): `bwrap: no user namespaces`" in r.notes[0]


def test_the_worker_runs_the_stage_copy_not_the_package():
    cells = [
        "import puma_course, sys",
        "def where(x):\n    import puma_course.grading as g\n"
        "    return [float('/lib/ex01_rotations/' in puma_course.__file__), float('grading/__init__' in g.__file__),"
        " float(any('puma_course' in str(p) and 'site-packages' not in str(p) for p in sys.path[1:]))]",
    ]
    out = _worker(cells, [{"qid": "q1", "case": 0, "function": "where", "args": [0]}])
    assert out.done and out.events[1]["value"] == [1.0, 1.0, 0.0], out.events


def test_the_worker_strips_hidden_tests_and_reports_failing_cells_only():
    cells = [
        "x = 1\n### BEGIN HIDDEN TESTS\nfrom puma_course import rotx\nassert False\n### END HIDDEN TESTS",
        "def f(a):\n    return [a + x]",
        "1 / 0",
    ]
    out = _worker(cells, [{"qid": "q1", "case": 0, "function": "f", "args": [1.0]}])
    assert [e["kind"] for e in out.events] == ["ready", "cell", "call", "done"]
    assert out.events[1]["index"] == 2 and out.events[1]["detail"].startswith("ZeroDivisionError")
    assert out.events[2]["value"] == [2.0]


def test_an_absent_name_says_it_is_not_available_in_this_exercise():
    out = _worker(["from puma_course import rotx"], [])
    assert out.events[1]["status"] == "error"
    assert "puma_course.rotx is not available in this exercise" in out.events[1]["detail"]
    out = _worker(["import puma_course.kinematics.dh"], [])
    assert "puma_course.kinematics is not available in this exercise" in out.events[1]["detail"]


def test_an_allowed_name_works_and_a_forbidden_one_still_trips(tmp_path):
    ex = EXERCISES["ex08_three_step"]
    assert "puma_course.transforms:rodrigues" in ex.allowed
    cells = [
        "from puma_course import rodrigues",
        "def base_angle(w):\n    return float(rodrigues([0, 0, 1], 0.1)[0, 0])",
    ]
    calls = [{"qid": "q1", "case": 0, "function": "base_angle", "args": [[1.0, 2.0, 3.0]]}]
    assert _worker(cells, calls, exercise=ex).events[1]["value"] == pytest.approx(0.995004165)
    # an allowed helper that is also a question's answer key: the tripwire is the second line
    key = ("puma_course.transforms:rodrigues",)
    q = Question(
        "q1",
        "turn",
        1,
        "K(a, t)",
        ((np.array([0.0, 0.0, 1.0]), 0.3),),
        lambda rng: [],
        reference=lambda a, t: np.eye(3),
        forbidden=key,
    )
    small = Exercise("ex98_tripwire", "a helper that is also the answer", (q,), allowed=key)
    nb = tmp_path / "ex98_tripwire.ipynb"
    nbformat.write(
        nbformat.v4.new_notebook(
            cells=[
                nbformat.v4.new_code_cell(
                    "from puma_course import rodrigues\ndef turn(a, t):\n    return rodrigues(a, t)"
                )
            ]
        ),
        nb,
    )
    r = grade_notebook(nb, small)
    assert (
        r.score == 0
        and "used the course package's answer (puma_course.transforms.rodrigues)" in r.question_notes["q1"][1]
    )


def test_child_stops_reading_at_done_even_if_the_process_lingers():
    code = 'import sys, time; sys.stdout.write(\'{"kind": "done"}\\n\'); sys.stdout.flush(); time.sleep(30)'
    start = time.monotonic()
    out = child_mod.run([sys.executable, "-c", code], b"", cwd=None, env=dict(os.environ), timeout=20)
    assert out.done and not out.timed_out and time.monotonic() - start < 10


def test_child_does_not_wait_for_a_grandchild_holding_the_pipe():
    code = (
        "import os, sys, time\n"
        "if os.fork() == 0:\n    os.setsid()\n    time.sleep(30)\n    os._exit(0)\n"
        'sys.stdout.write(\'{"kind": "cell", "index": 0}\\n\'); sys.stdout.flush(); os._exit(3)'
    )
    start = time.monotonic()
    out = child_mod.run([sys.executable, "-c", code], b"", cwd=None, env=dict(os.environ), timeout=20)
    assert not out.done and not out.timed_out and out.returncode == 3 and out.events == [{"kind": "cell", "index": 0}]
    assert time.monotonic() - start < 10


def test_child_times_out_and_caps_what_it_keeps():
    out = child_mod.run([sys.executable, "-c", "while True: pass"], b"x" * 10_000_000, cwd=None, env={}, timeout=1)
    assert out.timed_out and out.seconds < 10
    flood = "import sys\nwhile True: sys.stdout.write('[' * 1000000)"
    out = child_mod.run([sys.executable, "-c", flood], b"", cwd=None, env={}, timeout=30)
    assert out.overflow and not out.timed_out


def test_the_tamper_check_covers_every_module_of_the_package():
    digest = runner.package_digest(runner._PACKAGE_DIR, runner.EXERCISES.course)
    modules = {"__init__.py", "grading/run/runner.py", "grading/run/worker/__init__.py", "bank/_reference/__init__.py"}
    assert modules <= set(digest)
    assert all(not key.startswith("/") for key in digest)


def test_the_stage_holds_the_worker_and_one_package_per_exercise():
    with Stage([EX, EXERCISES["ex08_three_step"]]) as stage:
        files = {p.relative_to(stage.root).as_posix() for p in stage.root.rglob("*.py")}
        assert "bin/puma_worker/__init__.py" in files and "bin/puma_worker/guard.py" in files
        assert "lib/ex01_rotations/puma_course/grading/__init__.py" in files
        assert "lib/ex01_rotations/puma_course/transforms.py" not in files
        assert "lib/ex08_three_step/puma_course/transforms.py" in files
        assert not any("bank" in f or "runner" in f for f in files)
        assert not os.access(stage.root / "lib", os.W_OK) or os.geteuid() == 0
        assert stage.changed() == []
        root = stage.root
    assert not root.exists()


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"jobs": 0}, "jobs"),
        ({"timeout_cell": -1}, "timeout_cell"),
        ({"timeout_student": float("nan")}, "timeout_student"),
        ({"sandbox": "docker"}, "sandbox"),
        ({"exercises": ["ex99"]}, "exercises"),
    ],
)
def test_grade_refuses_bad_arguments_naming_them(tmp_path, kwargs, name):
    (tmp_path / "subs").mkdir()
    with pytest.raises(ValueError, match=f"^{name}:"):
        grade(tmp_path / "subs", tmp_path / "g.csv", **kwargs)


def test_grade_notebook_refuses_a_link_and_reads_nothing_through_it(tmp_path):
    link = tmp_path / "ex01_rotations.ipynb"
    link.symlink_to(ROOT / "solutions" / "ex01_rotations.ipynb")
    r = grade_notebook(link, EX)
    assert r.status == "refused" and r.score == 0 and "symbolic link" in r.notes[0]
    assert grade_notebook(tmp_path / "none.ipynb", EX).status == "missing"


def test_a_students_total_time_limit_spans_its_notebooks(tmp_path):
    subs = tmp_path / "subs"
    (subs / "slow").mkdir(parents=True)
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell("import time\ntime.sleep(30)")])
    for name in ("ex01_rotations", "ex02_dh_frames", "ex03_puma_fk"):
        nbformat.write(nb, subs / "slow" / f"{name}.ipynb")
    names = ["ex01_rotations", "ex02_dh_frames", "ex03_puma_fk"]
    start = time.monotonic()
    results = grade(
        subs, tmp_path / "g.csv", exercises=names, timeout_cell=60, timeout_total=60, timeout_student=2, sandbox="none"
    )
    assert time.monotonic() - start < 30
    assert [r.status for r in results] == ["timeout"] * 3
    assert "total time for all of this student's notebooks" in results[0].notes[-1]
    assert "not run" in results[1].notes[0] and "not run" in results[2].notes[0]


#: A cell that finds the worker's result pipe and writes to it; ``{line}`` is what it writes.
_WRITE_TO_PIPE = (
    "import os\nfor fd in range(3, 64):\n    try:\n"
    "        if os.readlink(f'/proc/self/fd/{{fd}}').startswith('pipe:'):\n"
    "            os.write(fd, {line!r})\n    except OSError:\n        pass"
)


@pytest.mark.parametrize(
    "line",
    [
        # a forged right answer, before the worker's own event for that case
        b'{"kind": "call", "qid": "q1", "case": 0, "value": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}\n',
        b"[[[[",  # a partial line (what a flood interrupted by the worker's clock leaves): the next event is lost
        b'{"kind": "report", "total": 56}\n',  # a kind the worker never sends
    ],
)
def test_a_notebook_that_writes_to_the_result_pipe_is_crashed_and_not_graded(tmp_path, line):
    nb = nbformat.read(ROOT / "solutions" / "ex01_rotations.ipynb", as_version=4)
    nb.cells.append(nbformat.v4.new_code_cell(_WRITE_TO_PIPE.format(line=line)))
    sub = tmp_path / "ex01_rotations.ipynb"
    nbformat.write(nb, sub)
    r = grade_notebook(sub, EX, "s", seed=1, sandbox="none")
    assert r.status == "crashed" and r.score == 0, (r.status, r.notes)
    assert any("wrote to the grader's results channel" in n for n in r.notes), r.notes


def test_child_counts_the_lines_the_worker_never_sends():
    code = (
        'import sys\nsys.stdout.write(\'{"kind": "ready"}\\nnot json\\n[1]\\n{"kind": "x"}\\n'
        '{"kind": "call", "qid": "q1", "case": 0}\\n{"kind": "done"}\\n\')'
    )
    out = child_mod.run([sys.executable, "-c", code], b"", cwd=None, env=dict(os.environ), timeout=20)
    assert out.done and out.foreign == 3 and [e["kind"] for e in out.events] == ["ready", "call", "done"]
