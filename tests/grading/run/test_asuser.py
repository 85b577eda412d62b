"""Running a worker as an unprivileged user (the Gradescope autograder's own sandbox): the launcher, the probe, ending
every process of the user, and results.json written atomically. Root only (the launcher drops from root); a uid
made up for the test (no passwd entry is needed), and /usr/bin/python3, which any user can run."""

from __future__ import annotations

import json
import os
import secrets
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pytest

from puma_course.grading.publish.gradescope_run import write_results
from puma_course.grading.run.asuser import _PROBE, LAUNCHER, NPROC, User, end_processes, probe, uids

# CI's second pass (another OpenBLAS kernel) leaves this out: an unprivileged user's launcher, probe and process
# ending: no numerics.
pytestmark = pytest.mark.no_numerics

PYTHON = "/usr/bin/python3"
needs_root = pytest.mark.skipif(
    os.geteuid() != 0 or not os.access(PYTHON, os.X_OK), reason="needs root and /usr/bin/python3"
)


@pytest.fixture
def user() -> User:
    uid = 64000 + secrets.randbelow(1000)
    return User("test", uid, uid)


def _launch(user: User, code: str, namespaces: bool) -> subprocess.CompletedProcess[str]:
    cmd = [PYTHON, "-I", "-S", "-c", LAUNCHER, str(user.uid), str(user.gid), str(NPROC), str(int(namespaces))]
    return subprocess.run([*cmd, "--", PYTHON, "-I", "-S", "-c", code], capture_output=True, text=True, cwd="/")


@needs_root
@pytest.mark.parametrize("namespaces", [False, True])
def test_the_launcher_drops_every_id_and_privilege(user, namespaces):
    code = (
        "import os, resource\n"
        "status = dict(l.split(':', 1) for l in open('/proc/self/status'))\n"
        "print(os.getresuid(), os.getresgid(), os.getgroups(), status['NoNewPrivs'].strip(), status['CapEff'].strip(),"
        " resource.getrlimit(resource.RLIMIT_NPROC), os.getpid())"
    )
    done = _launch(user, code, namespaces)
    assert done.returncode == 0, done.stderr
    ids, pid = done.stdout.rsplit(" ", 1)
    u, g = user.uid, user.gid
    assert ids == f"({u}, {u}, {u}) ({g}, {g}, {g}) [] 1 0000000000000000 ({NPROC}, {NPROC})"
    assert (int(pid) == 1) == namespaces  # this machine allows root new namespaces


@needs_root
def test_the_probe_says_what_the_user_can_open(user):
    tmp_path = Path(tempfile.mkdtemp(prefix="puma-probe-"))  # /tmp: reachable by every user, unlike pytest's folder
    private = tmp_path / "private"
    private.mkdir(mode=0o700)
    public = tmp_path / "public.txt"
    public.write_text("x")
    tmp_path.chmod(0o755)
    public.chmod(0o644)
    try:
        found = probe(user, [str(private), str(public)], python=PYTHON)
    finally:
        shutil.rmtree(tmp_path)
    assert found.ok and found.readable == (str(public),) and found.namespaces, found


@needs_root
def test_every_process_of_the_user_ends_even_a_double_forked_daemon_and_a_fork_loop(user):
    daemon = (
        "import os, time\n"
        "if os.fork() == 0:\n"
        "    os.setsid()\n"
        "    if os.fork() == 0:\n"
        "        for _ in range(20):\n"
        "            if os.fork() == 0:\n"
        "                time.sleep(30)\n"
        "                os._exit(0)\n"
        "        while True:\n"
        "            time.sleep(0.01)\n"
        "    os._exit(0)\n"
    )
    cmd = [
        PYTHON,
        "-I",
        "-S",
        "-c",
        LAUNCHER,
        str(user.uid),
        str(user.gid),
        str(NPROC),
        "0",
        "--",
        PYTHON,
        "-c",
        daemon,
    ]
    launched = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    assert launched.wait(60) == 0  # no namespace ends what it left: only the uid finds it
    time.sleep(0.5)
    alive = [p for p in os.listdir("/proc") if p.isdigit() and user.uid in uids(int(p))]
    assert len(alive) == 21  # the daemon and its children outlived the launcher
    assert end_processes(user, python=PYTHON) >= len(alive)
    time.sleep(0.2)
    assert [p for p in os.listdir("/proc") if p.isdigit() and user.uid in uids(int(p))] == []


@needs_root
def test_a_daemon_that_stops_every_process_of_the_user_is_ended_quickly(user):
    """A daemon looping ``kill(-1, SIGSTOP)`` stops the user's own kill helper; root's scan ends it anyway, at once."""
    stopper = (
        "import os, signal, time\n"
        "if os.fork() == 0:\n"
        "    os.setsid()\n"
        "    if os.fork() == 0:\n"
        "        for _ in range(5):\n"
        "            if os.fork() == 0:\n"
        "                time.sleep(60)\n"
        "                os._exit(0)\n"
        "        time.sleep(2.0)\n"  # its parents have exited (else it stops them too, and the launch never returns)
        "        end = time.time() + 60\n"
        "        while time.time() < end:\n"
        "            try:\n"
        "                os.kill(-1, signal.SIGSTOP)\n"
        "            except OSError:\n"
        "                pass\n"
        "        os._exit(0)\n"
        "    os._exit(0)\n"
    )
    cmd = [PYTHON, "-I", "-S", "-c", LAUNCHER, str(user.uid), str(user.gid), str(NPROC), "0", "--"]
    cmd += [PYTHON, "-c", stopper]
    launched = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    assert launched.wait(60) == 0
    time.sleep(3.0)  # the daemon is stopping every process of the user by now
    alive = [p for p in os.listdir("/proc") if p.isdigit() and user.uid in uids(int(p))]
    assert len(alive) == 6  # the stopper and its five stopped children
    start = time.monotonic()
    assert end_processes(user, python=PYTHON) >= len(alive)
    assert time.monotonic() - start < 10  # not the helper's old 60 s timeout
    time.sleep(0.2)
    assert [p for p in os.listdir("/proc") if p.isdigit() and user.uid in uids(int(p))] == []


def test_results_are_written_by_rename_never_through_a_link(tmp_path):
    outside = tmp_path / "outside.json"
    outside.write_text("keep")
    (tmp_path / "results").mkdir()
    (tmp_path / "results" / "results.json").symlink_to(outside)
    out = {"score": 1.5, "tests": []}
    write_results(tmp_path, out)
    path = tmp_path / "results" / "results.json"
    assert not path.is_symlink() and json.loads(path.read_text()) == out and outside.read_text() == "keep"
    assert [p.name for p in (tmp_path / "results").iterdir()] == ["results.json"]  # no temporary file left


def test_the_probe_would_see_a_process_that_can_reach_the_grader():
    """Run without the launcher (as the grader's own user), the probe's check of the grader's reach fires."""
    env = {"PUMA_PROBE_PARENT": str(os.getpid())}
    done = subprocess.run([sys.executable, "-I", "-S", "-c", _PROBE], capture_output=True, text=True, env=env)
    assert json.loads(done.stdout)["signals_root"] is True
