"""Limits per notebook, enforced by the system: one control group per graded notebook.

The worker's own ``setrlimit`` caps are per *process*: 4 GiB of address space each, times every process
the notebook forks. A control group holds the notebook's whole process tree, whatever it forks or however
it detaches (``setsid``, double forks), so the limits below hold for the notebook as a whole:

* memory (with swap, where the kernel accounts it) :data:`MEMORY` bytes: past it the kernel's OOM killer
  ends a process of that notebook, never a classmate's or the grader;
* at most :data:`PROCESSES` processes and threads;
* CPU: at most :data:`CPUS` cores (a CFS quota), and an equal share against every other notebook graded
  at the same time (the groups have equal weights, and the kernel's per-session autogroups, which gave a
  notebook's sixty ``setsid`` children sixty shares, apply only outside control groups); the run's folder
  weighs as many ordinary processes as notebooks are graded at once (:meth:`Run.share`);
* each call (and each code cell) is timed on the CPU time of the notebook's group (:meth:`Group.cpu_clock`),
  so a classmate who takes the CPU cannot make a right but slowish call fail, with a wall-clock backstop of
  :data:`WALL_FACTOR` times the limit (a call that sleeps or waits); without a group, on the CPU time of its
  process tree read from /proc (:mod:`.monitor`; :func:`call_limit` says which). The grader's process keeps
  these limits (:mod:`.monitor`); the worker's own timer only stops a call politely.

:func:`open_run` makes a folder for the grading run in each controller's hierarchy, under the grader's own
group (so limits set on the grader, by systemd or a container, still hold above), in the first layout
that works here: the unified hierarchy (cgroup v2: ``memory.max``, ``memory.swap.max``, ``pids.max``,
``cpu.weight``, ``cpu.max``) where it has the controllers, else the v1 controllers of a hybrid hierarchy
(``memory.limit_in_bytes`` and ``memory.memsw.limit_in_bytes``, ``pids.max``, ``cpu.shares``,
``cpu.cfs_quota_us``). It needs root, or a subtree delegated to the grading user (``puma-course limits delegate
--user NAME``, :mod:`.delegation`; or systemd's ``Delegate=yes``). Where it cannot, it says why, and the grader
says so loudly (terminal, CSV ``limits`` column) and falls back to the per-process limits.

:meth:`Run.notebook` makes the group of one notebook; :meth:`Group.wrap` prefixes the worker's command
with a tiny ``/bin/sh`` launcher that writes its own process id into the group's ``cgroup.procs`` and
then ``exec``'s the worker, so the notebook's first instruction already runs inside its group; at the end
every process still in the group is killed and the group removed (:meth:`Group.close`, which also reads
the group's peak memory and CPU time).
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

from .cgroupfs import _int, _key, _own_groups, _rmdir, _v2_mount, _write

__all__ = [
    "MEMORY",
    "PROCESSES",
    "CPUS",
    "ROOT",
    "Run",
    "Group",
    "Usage",
    "open_run",
    "describe",
    "call_limit",
    "WALL_FACTOR",
]

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
            u.peak_memory = _int(f["memory"] / "memory.max_usage_in_bytes")
            u.peak_memory = max(u.peak_memory, _int(f["memory"] / "memory.memsw.max_usage_in_bytes"))
            u.cpu_seconds = _int(f["cpuacct"] / "cpuacct.usage") / 1e9 if "cpuacct" in f else 0.0
            u.oom_kills = _key(f["memory"] / "memory.oom_control", "oom_kill")
            u.pids_refused = _key(f["pids"] / "pids.events", "max")
        else:
            folder = f["memory"]
            u.peak_memory = _int(folder / "memory.peak")
            u.cpu_seconds = _key(folder / "cpu.stat", "usage_usec") / 1e6
            u.oom_kills = _key(folder / "memory.events", "oom_kill")
            u.pids_refused = _key(folder / "pids.events", "max")
        return u

    def close(self) -> Usage:
        """Kill what is left, read the usage, remove the group's folders."""
        self.kill_all()
        self.usage = self.read_usage()
        for folder in dict.fromkeys(reversed(list(self.folders.values()))):
            _rmdir(folder)
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
                _rmdir(folder)
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
                _write(self.folders["cpu"] / "cpu.shares", str(min(262144, 1024 * n)))
            else:
                _write(self.folders["cpu"] / "cpu.weight", str(min(10000, 100 * n)))

    def close(self) -> None:
        for folder in dict.fromkeys(self.folders.values()):
            _rmdir(folder)


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


#: The wall-clock backstop of a call timed on its CPU time: this many times the per-call limit.
WALL_FACTOR = 3.0


def call_limit(run: Run, seconds: float, proc: bool | None = None) -> str:
    """The per-call time limit as it holds, in a few words (the CSV's ``limits`` column, the terminal).

    Without a control group, the grader reads the CPU time of the worker's process tree from /proc
    (``proc``: whether there is one; None: look), and only where there is none either, the wall clock.

    >>> call_limit(Run(1), 10)
    'each call 10 s of CPU time (its whole process tree; wall-clock backstop 30 s)'
    >>> call_limit(Run(0, reason="not root"), 10, proc=True)
    'each call 10 s of CPU time (its process tree, from /proc; wall-clock backstop 30 s)'
    >>> call_limit(Run(0, reason="not root"), 10, proc=False)
    'each call 10 s WALL CLOCK (no CPU time counter)'
    """
    backstop = WALL_FACTOR * seconds
    if run.enforced:
        return f"each call {seconds:g} s of CPU time (its whole process tree; wall-clock backstop {backstop:g} s)"
    if proc if proc is not None else os.path.isfile("/proc/self/stat"):
        return f"each call {seconds:g} s of CPU time (its process tree, from /proc; wall-clock backstop {backstop:g} s)"
    return f"each call {seconds:g} s WALL CLOCK (no CPU time counter)"


def _gib(n: int) -> str:
    return f"{n / (1 << 30):g} GiB" if n >= 1 << 30 else f"{n / (1 << 20):g} MiB"


def _set_limits(group: Group, memory: int, processes: int, cpus: float) -> None:
    f = group.folders
    quota = max(1000, int(cpus * _PERIOD_US))
    if group.version == 1:
        _write(f["memory"] / "memory.limit_in_bytes", str(memory))
        if (f["memory"] / "memory.memsw.limit_in_bytes").exists():
            _write(f["memory"] / "memory.memsw.limit_in_bytes", str(memory))  # no swapping past the limit
        _write(f["pids"] / "pids.max", str(processes))
        _write(f["cpu"] / "cpu.shares", "1024")
        _write(f["cpu"] / "cpu.cfs_period_us", str(_PERIOD_US))
        _write(f["cpu"] / "cpu.cfs_quota_us", str(quota))
    else:
        folder = f["memory"]
        _write(folder / "memory.max", str(memory))
        if (folder / "memory.swap.max").exists():
            _write(folder / "memory.swap.max", "0")
        _write(folder / "pids.max", str(processes))
        _write(folder / "cpu.weight", "100")
        _write(folder / "cpu.max", f"{quota} {_PERIOD_US}")


def _try_v2(root: Path, own: dict[str, str], name: str) -> Run | str:
    mount = _v2_mount(root)
    if mount is None:
        return "no cgroup2 mount"
    try:
        available = set((mount / "cgroup.controllers").read_text().split())
    except OSError as exc:
        return f"cannot read {mount}/cgroup.controllers ({exc.strerror})"
    missing = {"memory", "pids", "cpu"} - available
    if missing:
        return f"the unified hierarchy ({mount}) has no {', '.join(sorted(missing))} controller"
    parent = mount / own.get("", "/").lstrip("/")
    try:
        _write(parent / "cgroup.subtree_control", "+memory +pids +cpu")
        run = parent / name
        run.mkdir()
    except OSError as exc:
        return f"cannot make a group under {parent} ({exc.strerror}; not root: see puma-course limits delegate)"
    try:
        _write(run / "cgroup.subtree_control", "+memory +pids +cpu")
    except OSError as exc:
        _rmdir(run)
        return f"cannot enable the controllers in {run} ({exc.strerror})"
    return Run(2, {"memory": run, "pids": run, "cpu": run})


def _try_v1(root: Path, own: dict[str, str], name: str) -> Run | str:
    folders: dict[str, Path] = {}
    for controller in ("memory", "pids", "cpu", "cpuacct"):
        mount = next(
            (
                root / m
                for m in (controller, "cpu,cpuacct", "cpuacct,cpu")
                if controller in m.split(",") and (root / m).is_dir() and (root / m / "cgroup.procs").exists()
            ),
            None,
        )
        if mount is None:
            if controller == "cpuacct":
                continue  # only the CPU time figure is lost
            return f"no cgroup v1 {controller} controller under {root}"
        parent = mount / own.get(controller, "/").lstrip("/")
        run = parent / name
        try:
            if run not in folders.values():
                run.mkdir()
        except OSError as exc:
            for made in dict.fromkeys(folders.values()):
                _rmdir(made)
            return f"cannot make a group under {parent} ({exc.strerror}; not root: see puma-course limits delegate)"
        folders[controller] = run
    return Run(1, folders)


def open_run(
    memory: int = MEMORY,
    processes: int = PROCESSES,
    cpus: float = CPUS,
    *,
    root: str | os.PathLike[str] = ROOT,
    proc_cgroup: str = "/proc/self/cgroup",
    enabled: bool = True,
) -> Run:
    """The grading run's groups (v2, else v1), or a :class:`Run` with ``version`` 0 and the reason why not.

    ``root`` and ``proc_cgroup`` are for tests (a fake hierarchy). ``enabled`` False (or the environment
    variable ``PUMA_GRADING_CGROUPS=0``) turns them off on purpose.
    """
    if not enabled or os.environ.get("PUMA_GRADING_CGROUPS", "1") == "0":
        return Run(0, reason="turned off (PUMA_GRADING_CGROUPS=0)")
    base = Path(root)
    if not base.is_dir():
        return Run(0, reason=f"no control-group file system at {base} (not Linux, or not mounted)")
    own = _own_groups(proc_cgroup)
    name = f"puma-grading-{os.getpid()}-{secrets.token_hex(4)}"
    why = []
    from .delegation import find_delegated  # not root: in a subtree delegated to this user

    for attempt in (_try_v2, find_delegated, _try_v1):
        got = attempt(base, own, name)
        if got is None:
            continue
        if isinstance(got, Run):
            got.memory, got.processes, got.cpus = memory, processes, cpus
            try:  # a group that cannot take the limits is no group
                with got.notebook():
                    pass
            except OSError as exc:
                got.close()
                why.append(f"cgroup v{got.version}: cannot set the limits ({exc.strerror})")
                continue
            return got
        why.append(got)
    return Run(0, reason="; ".join(why))
