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

Skipped, saying why, where it cannot run: not root, no useradd/runuser, no bubblewrap, no venv for
/usr/bin/python3. Mark: ``unprivileged``.
"""

from __future__ import annotations

import csv
import glob
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
from tests.grading.hostile import Listener, _notebook, fixtures
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
            [str(g.venv / "bin" / "pip"), "install", "-q", "nbformat", "numpy"],  # what grading needs
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
    # said loudly: no control group for this user, the calls on the wall clock; the worker reads a copy in /dev/shm
    assert "WARNING: notebook limits are PER PROCESS ONLY" in done.stderr, done.stderr
    assert "WALL CLOCK" in done.stderr and "a per-run copy in /dev/shm" in done.stderr, done.stderr
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
