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

import os
import secrets
from pathlib import Path

from .cgroupfs import own_groups, remove_group, v2_mount, write_setting
from .delegation import find_delegated
from .groups import CPUS, JOIN, MEMORY, PROCESSES, ROOT, Group, Run, Usage, describe

__all__ = [
    "MEMORY",
    "PROCESSES",
    "CPUS",
    "ROOT",
    "JOIN",
    "Run",
    "Group",
    "Usage",
    "open_run",
    "describe",
    "call_limit",
    "WALL_FACTOR",
    "WAIT_CREDIT",
    "hard_deadline",
]

#: The wall-clock backstop of a call timed on its CPU time: this many times the per-call limit.
WALL_FACTOR = 3.0

#: The notebook's wall-clock cap (:data:`WALL_FACTOR` times its own-time limit) is lengthened by the time its
#: process waited for a CPU others held while the grader's calls ran, up to this many times the CPU seconds those
#: calls used (:class:`.monitor.Watch`): a busy machine stretches an honest notebook's wall clock by about its load
#: (measured: 4-6 s of waiting per CPU second at a load of 16 on 2 cores; 29 beside a fork storm), while a notebook
#: that waits on purpose (a low priority, a loop yielding the CPU) waits far more per CPU second it uses and gains
#: no more than this: the cap never passes :func:`hard_deadline`.
WAIT_CREDIT = 50.0


def hard_deadline(wall: float, cpu: float) -> float:
    """The wall-clock seconds after which the grader ends a worker whatever its clocks say: its cap (``wall`` s
    of its own time, :data:`WALL_FACTOR` times over) plus the most the waits for a CPU during calls can add
    (:data:`WAIT_CREDIT` times ``cpu``, its CPU time limit), plus 1 s.

    >>> hard_deadline(6.0, 6.0)
    319.0
    """
    return WALL_FACTOR * wall + WAIT_CREDIT * cpu + 1.0


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


def _try_v2(root: Path, own: dict[str, str], name: str) -> Run | str:
    mount = v2_mount(root)
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
        write_setting(parent / "cgroup.subtree_control", "+memory +pids +cpu")
        run = parent / name
        run.mkdir()
    except OSError as exc:
        return f"cannot make a group under {parent} ({exc.strerror}; not root: see puma-course limits delegate)"
    try:
        write_setting(run / "cgroup.subtree_control", "+memory +pids +cpu")
    except OSError as exc:
        remove_group(run)
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
                remove_group(made)
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
    own = own_groups(proc_cgroup)
    name = f"puma-grading-{os.getpid()}-{secrets.token_hex(4)}"
    why = []
    for attempt in (_try_v2, find_delegated, _try_v1):  # find_delegated: not root, in a subtree delegated to this user
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
