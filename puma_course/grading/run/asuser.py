"""Running each worker as an unprivileged user of its own, for a grader that is root without bubblewrap (Gradescope).

Gradescope runs its autograder as root in a container where bubblewrap cannot start. Without this module the
student's code would then run as root too: it could outlive its notebook, rewrite ``results.json``, signal the
grader or read the grader's memory. Here (:mod:`puma_course.grading.publish.gradescope` uses it):

* :class:`AsUser` is a :class:`~.sandbox.Sandbox` (kind "user") whose worker command starts with
  :data:`LAUNCHER`: run as root, it gives the worker's fresh folder to the user, tries to enter new PID and
  mount namespaces (``unshare``: where the container allows it, the worker is process 1 of a namespace of its
  own, with a ``/proc`` showing only its processes, and every process in it dies with it), caps the user's
  processes (``RLIMIT_NPROC``), drops every group and sets all its user and group ids to the user's, sets
  ``no_new_privs`` (no set-user-id program can give root back) and only then executes the worker;
* :func:`probe` runs the launcher once and reports what really holds (the ids, the namespaces, which of the
  grader's files the user can open);
* :func:`end_processes` ends every process of the user (root scans ``/proc`` by uid and sends SIGKILL until none
  is left; ``kill(-1)`` sent once as the user, with a short timeout, is only a fast first pass).

The user cannot read another user's ``/proc/<pid>/mem`` or ``environ`` (ptrace rules), cannot signal root's
processes, and cannot open what only root may read: the grader's package, the bank, the results folder.
"""

from __future__ import annotations

import json
import os
import pwd
import shutil
import signal
import subprocess
import sys
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from .sandbox import Sandbox

__all__ = ["AsUser", "User", "LAUNCHER", "STUDENT_USER", "find_user", "make_user", "probe", "end_processes", "uids"]

#: The user ``setup.sh`` makes, that every graded notebook runs as.
STUDENT_USER = "puma-student"
#: The most processes (and threads) the user may have at once.
NPROC = 64

#: Run as root by ``python -I -S -c LAUNCHER UID GID NPROC NAMESPACES -- WORKER...`` (standard library only).
LAUNCHER = r"""
import ctypes, os, resource, signal, sys
uid, gid, nproc, want = (int(a) for a in sys.argv[1:5])
cmd = sys.argv[6:]
libc = ctypes.CDLL(None, use_errno=True)
work = os.environ.get("HOME", "")
if work and os.path.basename(work).startswith("puma-grade-") and os.path.samefile(work, "."):
    os.chown(work, uid, gid)
if want and libc.unshare(0x20000000 | 0x00020000) == 0:
    pid = os.fork()
    if pid:
        while True:
            try:
                status = os.waitpid(pid, 0)[1]
                break
            except InterruptedError:
                continue
        code = os.waitstatus_to_exitcode(status)
        os._exit(code if code >= 0 else 128 - code)
    libc.mount(b"none", b"/", None, 0x4000 | 0x40000, None)
    libc.mount(b"proc", b"/proc", b"proc", 2 | 4 | 8, None)
resource.setrlimit(resource.RLIMIT_NPROC, (nproc, nproc))
os.setgroups([])
os.setresgid(gid, gid, gid)
os.setresuid(uid, uid, uid)
if libc.prctl(38, 1, 0, 0, 0) != 0 or os.getresuid() != (uid,) * 3 or os.getresgid() != (gid,) * 3 or os.getgroups():
    os._exit(125)
try:
    os.setuid(0)
    os._exit(125)
except OSError:
    pass
libc.prctl(1, int(signal.SIGKILL), 0, 0, 0)
os.execv(cmd[0], cmd)
"""


@dataclass(frozen=True)
class User:
    """An unprivileged user: its name and ids."""

    name: str
    uid: int
    gid: int


def find_user(name: str = STUDENT_USER) -> User | None:
    """The user called ``name``, if it exists and is unprivileged (not uid or gid 0); else None."""
    try:
        entry = pwd.getpwnam(name)
    except KeyError:
        return None
    if entry.pw_uid == 0 or entry.pw_gid == 0:
        return None
    return User(name, entry.pw_uid, entry.pw_gid)


def make_user(name: str = STUDENT_USER) -> User | None:
    """Make the system user ``name`` (no home, no login shell) when it does not exist; None if that fails."""
    found = find_user(name)
    if found is not None or shutil.which("useradd") is None:
        return found
    subprocess.run(
        ["useradd", "--system", "--user-group", "--no-create-home", "--shell", "/usr/sbin/nologin", name],
        capture_output=True,
        timeout=60,
    )
    return find_user(name)


def _prefix(user: User, namespaces: bool) -> list[str]:
    return [sys.executable, "-I", "-S", "-c", LAUNCHER, str(user.uid), str(user.gid), str(NPROC), str(int(namespaces))]


@dataclass(frozen=True)
class AsUser(Sandbox):
    """A worker without bubblewrap, run as ``user`` by :data:`LAUNCHER` (in new namespaces where ``namespaces``)."""

    user: User = User("", -1, -1)
    namespaces: bool = False

    @classmethod
    def of(cls, user: User, namespaces: bool, reason: str, sites: Sequence[str]) -> AsUser:
        """The sandbox for ``user``: ``reason`` says why there is no bubblewrap, ``sites`` the import path."""
        return cls("user", reason=reason, sites=tuple(sites), user=user, namespaces=namespaces)

    def command(self, lib: Path, bin_dir: Path, private: Sequence[Path] = ()) -> list[str]:
        """The launcher, then the worker."""
        return [*_prefix(self.user, self.namespaces), "--", *super().command(lib, bin_dir, private)]


_PROBE = """
import json, os, sys
out = {"pid": os.getpid(), "ids": [os.getresuid(), os.getresgid(), os.getgroups()], "readable": []}
out["procs"] = sum(p.isdigit() for p in os.listdir("/proc"))
for p in sys.argv[1:]:
    try:
        (os.listdir if os.path.isdir(p) else lambda q: open(q, "rb").close())(p)
        out["readable"].append(p)
    except OSError:
        pass
parent = os.environ.get("PUMA_PROBE_PARENT", "")
try:
    os.kill(int(parent), 0)
    out["signals_root"] = True
except (OSError, ValueError):
    out["signals_root"] = False
for what in ("environ", "mem"):
    try:
        open(f"/proc/{parent}/{what}", "rb").close()  # opening is what the kernel checks (ptrace rules)
        out["signals_root"] = True
    except OSError:
        pass
sys.stdout.write(json.dumps(out))
"""


@dataclass(frozen=True)
class Probe:
    """What holds for a worker run as the user (:func:`probe`)."""

    ok: bool
    namespaces: bool
    readable: tuple[str, ...]
    said: str


def probe(user: User, private: Sequence[str], namespaces: bool = True, python: str = sys.executable) -> Probe:
    """Run ``python`` through the launcher as ``user``; ``private``: paths it must not be able to open."""
    cmd = [*_prefix(user, namespaces), "--", python, "-I", "-S", "-c", _PROBE, *private]
    env = {"PATH": "/usr/bin:/bin", "PUMA_PROBE_PARENT": str(os.getpid())}
    try:
        done = subprocess.run(cmd, capture_output=True, timeout=60, env=env, cwd="/")
        out = json.loads(done.stdout)
    except (OSError, subprocess.TimeoutExpired, ValueError) as exc:
        return Probe(False, False, (), f"the launcher failed: {type(exc).__name__}: {exc}")
    ids = [[user.uid] * 3, [user.gid] * 3, []]
    if out.get("ids") != ids or out.get("signals_root"):  # signalled, or opened the grader's environ or memory
        return Probe(False, False, (), f"the launcher did not drop to {user.name}: {out}")
    return Probe(True, out.get("pid") == 1 and out.get("procs") == 1, tuple(out.get("readable", ())), "")


def uids(pid: int) -> set[int]:
    """The real, effective, saved and file-system uids of a live (not zombie) process; empty if it is gone."""
    try:
        status = Path(f"/proc/{pid}/status").read_text(encoding="ascii", errors="replace")
    except OSError:
        return set()
    found: set[int] = set()
    for line in status.splitlines():
        if line.startswith("State:") and line.split()[1:2] in (["Z"], ["X"]):
            return set()
        if line.startswith("Uid:"):
            found = {int(x) for x in line.split()[1:]}
    return found


def _of(uid: int) -> list[int]:
    return [int(p) for p in os.listdir("/proc") if p.isdigit() and uid in uids(int(p))]


def _kill_as(user: User, python: str, timeout: float) -> None:
    """``kill(-1)`` sent as ``user``: one pass of the kernel's process list reaches all of them (a fork under way
    then fails). Only a fast first pass: the user may stop this helper too, so its timeout is not an error."""
    try:
        subprocess.run(
            [python, "-I", "-S", "-c", "import os; os.kill(-1, 9)"],
            user=user.uid,
            group=user.gid,
            extra_groups=[],
            env={},
            cwd="/",
            capture_output=True,
            timeout=timeout,
        )
    except (OSError, subprocess.TimeoutExpired):
        pass  # run() has killed it; the scan below ends what is left


def end_processes(user: User, rounds: int = 100, python: str = sys.executable, first: float = 2.0) -> int:
    """End every process of ``user`` (zombies aside); return how many were found. RuntimeError if some survive.

    Root scans ``/proc`` by uid and sends SIGKILL, which a stopped process receives too, until none is left;
    the user's own ``kill(-1)`` (``first`` seconds at most) is only tried once, after the first scan."""
    found: set[int] = set()
    for i in range(rounds):
        left = _of(user.uid)
        if not left:
            return len(found)
        found.update(left)
        for pid in left:
            try:
                os.kill(pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass
        if i == 0:
            _kill_as(user, python, first)
        time.sleep(0.01)
    raise RuntimeError(f"processes of {user.name} survived {rounds} rounds of SIGKILL: {_of(user.uid)}")
