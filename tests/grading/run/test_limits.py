"""The control group per notebook (puma_course/grading/run/limits.py): the files it writes (cgroup v2 and v1, on a
fake hierarchy), and on this machine, when it allows them, a real group holding a whole process tree."""

from __future__ import annotations

import os
import subprocess
import time
from pathlib import Path

import pytest

from puma_course.grading.run import limits
from puma_course.grading.run.limits import describe, open_run

# CI's second pass (another OpenBLAS kernel) leaves this out: the control-group files a run writes: no numerics.
pytestmark = pytest.mark.no_numerics


def _v2(tmp_path: Path, own: str = "/") -> tuple[Path, Path]:
    root = tmp_path / "cg"
    (root / own.lstrip("/")).mkdir(parents=True)
    (root / "cgroup.controllers").write_text("cpuset cpu io memory pids\n")
    proc = tmp_path / "proc-cgroup"
    proc.write_text(f"0::{own}\n")
    return root, proc


def test_v2_where_the_unified_hierarchy_has_the_controllers(tmp_path):
    root, proc = _v2(tmp_path, "/grader.service")
    run = open_run(memory=1 << 30, processes=32, cpus=0.5, root=root, proc_cgroup=str(proc))
    assert run.version == 2 and run.enforced, run.reason
    parent = root / "grader.service"
    assert (parent / "cgroup.subtree_control").read_text() == "+memory +pids +cpu"
    folder = run.folders["memory"]
    assert folder.parent == parent and folder.name.startswith("puma-grading-")
    assert (folder / "cgroup.subtree_control").read_text() == "+memory +pids +cpu"
    with run.notebook() as group:
        assert group is not None and group.version == 2
        nb = group.folders["memory"]
        assert (nb / "memory.max").read_text() == str(1 << 30)
        assert (nb / "pids.max").read_text() == "32"
        assert (nb / "cpu.max").read_text() == "50000 100000"
        assert (nb / "cpu.weight").read_text() == "100"
        assert group.procs == [str(nb / "cgroup.procs")]
        cmd = group.wrap(["python3", "-c", "pass"])
        assert cmd[:2] == ["/bin/sh", "-c"] and cmd[cmd.index("--") + 1 :] == ["python3", "-c", "pass"]
    run.share(3)
    assert (folder / "cpu.weight").read_text() == "300"
    assert describe(run) == "per notebook (cgroup v2): 1 GiB, 32 processes, 0.5 CPU"


def test_v2_without_controllers_falls_back_to_v1(tmp_path):
    root = tmp_path / "cg"
    (root / "unified").mkdir(parents=True)
    (root / "unified" / "cgroup.controllers").write_text("\n")  # this machine's hybrid layout
    for c in ("memory", "pids", "cpu", "cpuacct"):
        (root / c / "grader").mkdir(parents=True)
        (root / c / "cgroup.procs").write_text("")
    proc = tmp_path / "proc-cgroup"
    proc.write_text("4:memory:/grader\n8:pids:/\n1:cpu:/\n2:cpuacct:/\n0::/\n")
    run = open_run(root=root, proc_cgroup=str(proc))
    assert run.version == 1, run.reason
    assert run.folders["memory"].parent == root / "memory" / "grader"  # under the grader's own memory group
    assert run.folders["pids"].parent == root / "pids"
    with run.notebook() as group:
        assert group is not None
        f = group.folders
        assert (f["memory"] / "memory.limit_in_bytes").read_text() == str(limits.MEMORY)
        assert (f["pids"] / "pids.max").read_text() == str(limits.PROCESSES)
        assert (f["cpu"] / "cpu.cfs_quota_us").read_text() == "100000"
        assert (f["cpu"] / "cpu.shares").read_text() == "1024"
        assert len(group.procs) == 4


def test_no_control_groups_says_why(tmp_path):
    run = open_run(root=tmp_path / "absent")
    assert not run.enforced and "no control-group file system" in run.reason
    assert describe(run).startswith("PER PROCESS ONLY")
    root, proc = tmp_path / "cg", tmp_path / "p"
    root.mkdir()
    proc.write_text("0::/\n")
    run = open_run(root=root, proc_cgroup=str(proc))
    assert not run.enforced and "no cgroup2 mount" in run.reason and "no cgroup v1 memory" in run.reason
    assert "PUMA_GRADING_CGROUPS=0" in open_run(enabled=False).reason
    with run.notebook() as group:
        assert group is None


@pytest.fixture
def real_run():
    run = open_run(memory=256 << 20, processes=16)
    if not run.enforced:
        pytest.skip(f"NO CONTROL GROUPS on this machine (run as root or delegated): {run.reason}")
    yield run
    run.close()


def test_a_real_group_holds_the_whole_tree_and_kills_it(real_run):
    """A process joins before it runs anything; its setsid'd grandchild is in the group and dies with it."""
    with real_run.notebook() as group:
        assert group is not None
        script = "setsid sleep 60 >/dev/null 2>&1 & cat /proc/self/cgroup; echo $!"
        out = subprocess.run(group.wrap(["/bin/sh", "-c", script]), capture_output=True, text=True, timeout=30)
        assert out.returncode == 0, out.stderr
        lines = out.stdout.split()
        grandchild = int(lines[-1])
        name = group.folders["pids"].name
        assert any(name in line for line in lines[:-1]), out.stdout
        assert grandchild in group.members()
    time.sleep(0.1)
    assert not os.path.exists(f"/proc/{grandchild}") or "zombie" in Path(f"/proc/{grandchild}/status").read_text()
    assert all(not p.exists() for p in group.folders.values())


def test_a_real_group_limits_memory_and_processes_of_the_tree(real_run):
    """Two processes of 200 MB each under a 256 MiB group: one is ended; 40 forks under 16: most refused."""
    code = "import os, time\npid = os.fork()\nhog = b'x' * (200 << 20)\ntime.sleep(1)\nif pid: os.waitpid(pid, 0)\n"
    forks = (
        "import os\nn = 0\nfor _ in range(40):\n    try:\n        os.fork() or os._exit(0); n += 1\n"
        "    except OSError:\n        pass\nprint(n)\n"
    )
    with real_run.notebook() as group:
        assert group is not None
        subprocess.run(group.wrap(["python3", "-c", code]), capture_output=True, timeout=60)
    assert group.usage.peak_memory <= 256 << 20 and group.usage.oom_kills >= 1, group.usage
    with real_run.notebook() as group:
        assert group is not None
        out = subprocess.run(group.wrap(["python3", "-c", forks]), capture_output=True, text=True, timeout=60)
    assert int(out.stdout) < 40 and group.usage.pids_refused >= 1, (out.stdout, group.usage)


#: Appended to ex01's solution: the first call of q1's function first sleeps (wall clock, no CPU), or forks two
#: children that burn 5 s of CPU each while it waits for them (CPU time of its process tree, little of its own).
_FIRST_CALL = """
import os as _os, time as _time
_first = {{"done": False}}
_real = {function}


def {function}(*args):
    if not _first["done"]:
        _first["done"] = True
        if {kind!r} == "sleeps":
            _time.sleep(1.6)
        else:
            for _ in range(2):
                if _os.fork() == 0:
                    while _time.process_time() < 5:
                        pass
                    _os._exit(0)
            for _ in range(2):
                _os.wait()
    return _real(*args)
"""


def test_a_call_is_timed_on_the_cpu_time_of_its_whole_tree(real_run, tmp_path, monkeypatch):
    """Per call: 1 s of the notebook group's CPU time. A call that sleeps 1.6 s keeps its points (the wall clock
    would have failed it); a call whose two children burn CPU while it waits fails on CPU time (its own process
    used almost none), and the CSV says which clock held. (The wall-clock backstop is raised to 20 s here, so
    that a loaded machine, which gives the children little CPU, cannot end the call on the wall clock first.)"""
    monkeypatch.setattr(limits, "WALL_FACTOR", 20.0)
    import csv

    import nbformat

    from puma_course.grading import EXERCISES, grade
    from tests.support import ROOT

    ex = EXERCISES["ex01_rotations"]
    q1 = ex.questions[0]
    subs = tmp_path / "subs"
    for kind in ("sleeps", "forks"):
        nb = nbformat.read(ROOT / "solutions" / f"{ex.name}.ipynb", as_version=4)
        nb.cells.append(nbformat.v4.new_code_cell(_FIRST_CALL.format(function=q1.function, kind=kind)))
        (subs / kind).mkdir(parents=True)
        nbformat.write(nb, subs / kind / f"{ex.name}.ipynb")
    real_run.memory = 1 << 30
    out = tmp_path / "grades.csv"
    results = grade(
        subs, out, jobs=1, seed=3, exercises=[ex.name], sandbox="none", cgroups=real_run,
        timeout_cell=1.0, timeout_total=40.0, timeout_student=60.0,
    )  # fmt: skip
    got = {r.student: r for r in results}
    full = sum(q.points for q in ex.questions)
    assert got["sleeps"].score == full, got["sleeps"].question_notes
    assert got["forks"].score == full - q1.points, got["forks"].question_notes
    assert any("used more than 1 s of CPU time" in n for n in got["forks"].question_notes[q1.qid])
    with open(out, newline="", encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    assert all("each call 1 s of CPU time" in row["limits"] for row in rows), rows[0]["limits"]
