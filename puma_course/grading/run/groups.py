"""The control groups of a grading run and of each notebook: their folders, their limits, what they used.

A :class:`Run` is the run's folder in each hierarchy (or ``version`` 0 and why there is none); :meth:`Run.notebook`
makes a :class:`Group` per notebook, with the limits :data:`MEMORY`, :data:`PROCESSES`, :data:`CPUS`;
:meth:`Group.close` reads its :class:`Usage`. :mod:`.limits` opens a run where root may
(:func:`~.limits.open_run`), :mod:`.delegation` in a subtree delegated to the grading user; both make it here.
"""

from __future__ import annotations

import contextlib
import os
import secrets
import signal
import time
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from .cgroupfs import read_int, read_key, remove_group, write_setting

__all__ = ["MEMORY", "PROCESSES", "CPUS", "ROOT", "JOIN", "Run", "Group", "Usage", "describe"]

#: The notebook's memory, all of its processes together (plus the worker's in-memory folder's pages).
MEMORY = 4 << 30
#: The notebook's processes and threads, together.
PROCESSES = 64
#: The notebook's CPU cores, together (a CFS quota: ``CPUS`` x the period, per period).
CPUS = 1.0
#: Where the control-group file systems are mounted.
ROOT = "/sys/fs/cgroup"
_PERIOD_US = 100_000
#: The launcher: joins every ``cgroup.procs`` given before ``--``, then becomes the worker.
JOIN = 'while [ "$1" != -- ]; do echo $$ > "$1" || exit 125; shift; done; shift; exec "$@"'


@dataclass
class Usage:
    """What one notebook's group used: peak memory (bytes, 0 if unknown), CPU seconds, and whether it hit a limit."""

    peak_memory: int = 0
    cpu_seconds: float = 0.0
    oom_kills: int = 0
    pids_refused: int = 0


@dataclass
class Group:
    """The control group(s) of one notebook: one folder per v1 hierarchy, or one v2 folder."""

    version: int
    folders: dict[str, Path]
    usage: Usage = field(default_factory=Usage)

    @property
    def procs(self) -> list[str]:
        """The ``cgroup.procs`` files a process joins (one per distinct folder)."""
        return [str(p / "cgroup.procs") for p in dict.fromkeys(self.folders.values())]

    def wrap(self, cmd: Sequence[str]) -> list[str]:
        """``cmd`` started inside this group (see the module docstring)."""
        return ["/bin/sh", "-c", JOIN, "puma-join", *self.procs, "--", *cmd]

    def members(self) -> list[int]:
        out: set[int] = set()
        for procs in self.procs:
            with contextlib.suppress(OSError, ValueError):
                out |= {int(x) for x in Path(procs).read_text().split()}
        return sorted(out)

    def kill_all(self, wait: float = 5.0) -> None:
        """Kill every process in the group (``cgroup.kill`` where v2 has it), until none is left or ``wait`` passes."""
        folder = self.folders.get("memory") or next(iter(self.folders.values()))
        if self.version == 2 and (folder / "cgroup.kill").exists():
            with contextlib.suppress(OSError):
                (folder / "cgroup.kill").write_text("1")
        end = time.monotonic() + wait
        while True:
            pids = self.members()
            if not pids or time.monotonic() > end:
                return
            for pid in pids:
                with contextlib.suppress(OSError):
                    os.kill(pid, signal.SIGKILL)
            time.sleep(0.01)

    def cpu_clock(self) -> tuple[int, str]:
        """An open, read-only descriptor of the group's CPU time counter and its format ("ns": v1's
        ``cpuacct.usage``; "stat": v2's ``cpu.stat``), or (-1, "") where there is none.

        The worker reads it before and after each call (calls run one at a time, so a call's CPU time is
        the difference: every process of the notebook included, however many it forks). The counter is
        made read-only for everyone first (v1's can be reset by its owner, and inside the sandbox the
        notebook runs as the grader's user id, without capabilities).
        """
        if self.version == 1 and "cpuacct" in self.folders:
            path, fmt = self.folders["cpuacct"] / "cpuacct.usage", "ns"
        elif self.version == 2:
            path, fmt = self.folders["cpu"] / "cpu.stat", "stat"
        else:
            return -1, ""
        try:
            os.chmod(path, 0o444)
            return os.open(path, os.O_RDONLY | os.O_CLOEXEC), fmt
        except OSError:
            return -1, ""

    def read_usage(self) -> Usage:
        u = Usage()
        f = self.folders
        if self.version == 1:
            u.peak_memory = read_int(f["memory"] / "memory.max_usage_in_bytes")
            u.peak_memory = max(u.peak_memory, read_int(f["memory"] / "memory.memsw.max_usage_in_bytes"))
            u.cpu_seconds = read_int(f["cpuacct"] / "cpuacct.usage") / 1e9 if "cpuacct" in f else 0.0
            u.oom_kills = read_key(f["memory"] / "memory.oom_control", "oom_kill")
            u.pids_refused = read_key(f["pids"] / "pids.events", "max")
        else:
            folder = f["memory"]
            u.peak_memory = read_int(folder / "memory.peak")
            u.cpu_seconds = read_key(folder / "cpu.stat", "usage_usec") / 1e6
            u.oom_kills = read_key(folder / "memory.events", "oom_kill")
            u.pids_refused = read_key(folder / "pids.events", "max")
        return u

    def close(self) -> Usage:
        """Kill what is left, read the usage, remove the group's folders."""
        self.kill_all()
        self.usage = self.read_usage()
        for folder in dict.fromkeys(reversed(list(self.folders.values()))):
            remove_group(folder)
        return self.usage


@dataclass
class Run:
    """The grading run's folder in each hierarchy (``version`` 1 or 2), or ``version`` 0 and the ``reason``."""

    version: int
    folders: dict[str, Path] = field(default_factory=dict)
    reason: str = ""
    memory: int = MEMORY
    processes: int = PROCESSES
    cpus: float = CPUS
    #: what each notebook's group used, in the order they ended
    usages: list[Usage] = field(default_factory=list)
    _count: int = 0
    #: made in a subtree root delegated to the grading user (:mod:`.delegation`)
    delegated: bool = False

    @property
    def enforced(self) -> bool:
        return self.version > 0

    @property
    def label(self) -> str:
        """What the CSV's ``limits`` column says."""
        return describe(self)

    @contextlib.contextmanager
    def notebook(self) -> Iterator[Group | None]:
        """A fresh group for one notebook with the run's limits (None when limits are not enforced here)."""
        if not self.enforced:
            yield None
            return
        self._count += 1
        name = f"nb-{self._count}-{secrets.token_hex(3)}"
        group = Group(self.version, {c: p / name for c, p in self.folders.items()})
        try:
            for folder in dict.fromkeys(group.folders.values()):
                folder.mkdir()
            _set_limits(group, self.memory, self.processes, self.cpus)
        except OSError:
            for folder in dict.fromkeys(group.folders.values()):
                remove_group(folder)
            raise
        try:
            yield group
        finally:
            self.usages.append(group.close())

    def share(self, notebooks: int) -> None:
        """Weigh the run's folder as ``notebooks`` ordinary processes against the rest of the machine (each of
        the notebooks graded at once then competes as one process would, however many it forks)."""
        if not self.enforced:
            return
        n = max(1, int(notebooks))
        with contextlib.suppress(OSError):
            if self.version == 1:
                write_setting(self.folders["cpu"] / "cpu.shares", str(min(262144, 1024 * n)))
            else:
                write_setting(self.folders["cpu"] / "cpu.weight", str(min(10000, 100 * n)))

    def close(self) -> None:
        for folder in dict.fromkeys(self.folders.values()):
            remove_group(folder)


def describe(run: Run) -> str:
    """The limits as they hold, in a few words (the CSV's ``limits`` column, the terminal).

    >>> describe(Run(1, memory=4 << 30, processes=64, cpus=1.0))
    'per notebook (cgroup v1): 4 GiB, 64 processes, 1 CPU'
    >>> describe(Run(0, reason="not root"))
    'PER PROCESS ONLY (no control group: not root)'
    >>> describe(Run(1, delegated=True))
    'per notebook (cgroup v1, delegated): 4 GiB, 64 processes, 1 CPU'
    """
    if run.enforced:
        how = f"cgroup v{run.version}, delegated" if run.delegated else f"cgroup v{run.version}"
        return f"per notebook ({how}): {_gib(run.memory)}, {run.processes} processes, {run.cpus:g} CPU"
    return f"PER PROCESS ONLY (no control group: {run.reason})"


def _gib(n: int) -> str:
    return f"{n / (1 << 30):g} GiB" if n >= 1 << 30 else f"{n / (1 << 20):g} MiB"


def _set_limits(group: Group, memory: int, processes: int, cpus: float) -> None:
    f = group.folders
    quota = max(1000, int(cpus * _PERIOD_US))
    if group.version == 1:
        write_setting(f["memory"] / "memory.limit_in_bytes", str(memory))
        if (f["memory"] / "memory.memsw.limit_in_bytes").exists():
            write_setting(f["memory"] / "memory.memsw.limit_in_bytes", str(memory))  # no swapping past the limit
        write_setting(f["pids"] / "pids.max", str(processes))
        write_setting(f["cpu"] / "cpu.shares", "1024")
        write_setting(f["cpu"] / "cpu.cfs_period_us", str(_PERIOD_US))
        write_setting(f["cpu"] / "cpu.cfs_quota_us", str(quota))
    else:
        folder = f["memory"]
        write_setting(folder / "memory.max", str(memory))
        if (folder / "memory.swap.max").exists():
            write_setting(folder / "memory.swap.max", "0")
        write_setting(folder / "pids.max", str(processes))
        write_setting(folder / "cpu.weight", "100")
        write_setting(folder / "cpu.max", f"{quota} {_PERIOD_US}")
