"""The per-call and per-notebook time limits, kept by the grader's process, out of the notebook's reach.

The worker's own timer (a ``SIGALRM`` tick, :mod:`.worker`) stops a slow cell or call politely, so the
notebook goes on with its next question; but it runs inside the student's process, where
``signal.setitimer(signal.ITIMER_REAL, 0)`` switches it off. What holds is the :class:`Watch` the grader's
loop (:func:`.child.run`) consults every :data:`TICK` s: it reads the notebook's CPU time (a :class:`Meter`)
and ends the worker, with its whole process tree, once a limit is passed by more than :func:`grace`:

* **each call**: its clock starts when the grader *sends* the call (the worker receives one call at a time,
  its arguments included, and only once it has answered the one before: :func:`.child.run`) and stops when
  the answer to *that* call arrives. Writing lines to the result pipe cannot buy time: a line that answers the
  outstanding call is its answer (the first one counts, a second fails the notebook as forged), any other line
  leaves the clock running; a call that never answers is charged until the grader ends it;
* **the code cells** are held by the notebook's limit only (a cell's end is known from the worker's own
  report, which the notebook could write itself as often as it likes; a cell computes no answer);
* **the notebook**: its CPU time since it started, and a wall-clock backstop for one that sleeps or waits;
  and a cap on the wall clock, :data:`.limits.WALL_FACTOR` times its own-time limit, lengthened by the time it
  waited for a CPU while the grader's calls ran (at most :data:`.limits.WAIT_CREDIT` times the CPU seconds they
  used: :attr:`Watch.credit`), so that a busy machine cannot end an honest notebook on it either.

Every clock counts the notebook's own CPU time, never the machine's, so an honest notebook beside a CPU-hungry
classmate or on a busy server keeps its marks; a call that sleeps or waits is ended by the wall-clock backstop
of :data:`.limits.WALL_FACTOR` times its limit, and the notebook by its own wall-clock time: the wall clock
less the time the worker's main thread waited for a CPU that others held (``/proc/<pid>/schedstat``'s run
delay; :class:`Waits`), so that sleeping costs what it costs alone and a busy machine costs nothing. The meters:

* :class:`GroupMeter`: the notebook's control group's counter (v1 ``cpuacct.usage``, v2 ``cpu.stat``): every
  process of the notebook, however it forks or detaches;
* :class:`TreeMeter`, where there is no group: ``/proc``'s per-process CPU times of the worker's process tree
  (every process once seen stays counted, with its last figure after it ends, and waited-for children count
  through their parent), or of every process of a user id (a grading user of its own, as on Gradescope).
  A process that detaches (double fork) within one tick, outside a PID namespace and without a user id of its
  own, can escape it: the control group, the sandbox's PID namespace or the user id close that gap.
"""

from __future__ import annotations

import contextlib
import os
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import cast

from . import limits
from .limits import Group

__all__ = ["TICK", "grace", "Meter", "GroupMeter", "TreeMeter", "meter_for", "Stop", "Watch"]

#: How often (s) the grader's loop reads the notebook's CPU time.
TICK = 0.05


def grace(limit: float) -> float:
    """How far past a limit the grader waits for the worker's own timer before it ends the worker.

    >>> grace(1.0), grace(10.0)
    (0.5, 2.5)
    """
    return max(0.5, 0.25 * limit)


class Meter:
    """The notebook's CPU seconds so far (None: cannot be read now)."""

    kind = "none"

    def __call__(self) -> float | None:  # pragma: no cover - overridden
        return None

    def close(self) -> None:
        pass


class GroupMeter(Meter):
    """The control group's CPU time counter, read with ``pread`` from a descriptor opened once."""

    kind = "group"

    def __init__(self, path: Path, fmt: str) -> None:
        self.fd, self.fmt = os.open(path, os.O_RDONLY | os.O_CLOEXEC), fmt

    def __call__(self) -> float | None:
        try:
            data = os.pread(self.fd, 4096, 0)
            if self.fmt == "ns":
                return int(data.split()[0]) / 1e9
            for line in data.split(b"\n"):
                if line.startswith(b"usage_usec "):
                    return int(line.split()[1]) / 1e6
        except (OSError, ValueError, IndexError):
            pass
        return None

    def close(self) -> None:
        with contextlib.suppress(OSError):
            os.close(self.fd)


def _stat(pid: str) -> tuple[int, int, float, float] | None:
    """(ppid, start time in ticks, own CPU ticks, waited-for children's CPU ticks) of ``/proc/<pid>/stat``."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as fh:
            data = fh.read()
        f = data[data.rindex(b")") + 2 :].split()
        return int(f[1]), int(f[19]), float(int(f[11]) + int(f[12])), float(int(f[13]) + int(f[14]))
    except (OSError, ValueError, IndexError):
        return None


class TreeMeter(Meter):
    """The CPU time of the process tree under ``root`` (and of every process of ``uid``, if given), from /proc."""

    kind = "tree"

    def __init__(self, root: int, uid: int | None = None, proc: str = "/proc") -> None:
        self.root, self.uid, self.proc = root, uid, proc
        self.hz = float(os.sysconf("SC_CLK_TCK")) if hasattr(os, "sysconf") else 100.0
        #: pid -> (start time, own CPU ticks at the last scan that saw it)
        self.seen: dict[int, tuple[int, float]] = {}
        self.last = 0.0

    def _pids(self) -> list[str] | None:
        """The processes to look at: every process of ``uid`` (all of /proc), else the tree from the root and
        every process seen before (each process's ``children`` file: no scan of the whole of /proc)."""
        if self.uid is not None:
            try:
                return [n for n in os.listdir(self.proc) if n.isdigit()]
            except OSError:
                return None
        out, todo = set(), [self.root, *(p for p in self.seen if p > 0)]
        while todo:
            pid = todo.pop()
            if pid in out:
                continue
            out.add(pid)
            try:
                for task in os.listdir(f"{self.proc}/{pid}/task"):
                    with open(f"{self.proc}/{pid}/task/{task}/children", "rb") as fh:
                        todo += [int(x) for x in fh.read().split()]
            except (OSError, ValueError):
                continue
        return [str(p) for p in out]

    def __call__(self) -> float | None:
        names = self._pids()
        if names is None:
            return None
        stats = {}
        for name in names:
            st = _stat(name)
            if st is not None:
                stats[int(name)] = st
        if not stats and not self.seen:
            return None
        mine = {self.root} | {p for p, st in stats.items() if p in self.seen and self.seen[p][0] == st[1]}
        if self.uid is not None:
            for pid in stats:
                with contextlib.suppress(OSError):
                    if os.stat(f"{self.proc}/{pid}").st_uid == self.uid:
                        mine.add(pid)
        children: dict[int, list[int]] = {}
        for pid, st in stats.items():
            children.setdefault(st[0], []).append(pid)
        todo = list(mine)
        while todo:
            for child in children.get(todo.pop(), ()):
                if child not in mine:
                    mine.add(child)
                    todo.append(child)
        waited = 0.0
        for pid in mine:
            st = stats.get(pid)
            if st is None:
                continue
            old = self.seen.get(pid)
            if old is not None and old[0] != st[1]:  # the pid was reused: keep the old one's figure apart
                self.seen[-len(self.seen) - 1] = old
            self.seen[pid] = (st[1], st[2])
            waited += st[3]
        self.last = max(self.last, (sum(v[1] for v in self.seen.values()) + waited) / self.hz)
        return self.last


def meter_for(group: Group | None, pid: int, uid: int | None = None) -> Meter | None:
    """The best meter here: the group's counter, else /proc's process tree of ``pid``, else None."""
    if group is not None:
        if group.version == 1 and "cpuacct" in group.folders:
            path, fmt = group.folders["cpuacct"] / "cpuacct.usage", "ns"
        elif group.version == 2:
            path, fmt = group.folders["cpu"] / "cpu.stat", "stat"
        else:
            path, fmt = Path(), ""
        if fmt:
            with contextlib.suppress(OSError):
                meter = GroupMeter(path, fmt)
                if meter() is not None:
                    return meter
                meter.close()
    if os.path.isfile(f"/proc/{pid}/stat"):
        tree = TreeMeter(pid, uid)
        if tree() is not None:
            return tree
    return None


class Waits:
    """The seconds the worker's main thread waited for a CPU (run delay), found under ``root``: the first
    Python process of its tree (bubblewrap and the control group's launcher come before it). 0.0 until found,
    or where the kernel does not say (no schedstat): the notebook's time is then the wall clock."""

    def __init__(self, root: int) -> None:
        self.root, self.pid, self.last = root, 0, 0.0
        self.ran = 0.0  # the seconds it ran on a CPU (the same file's first figure)

    def _find(self) -> int:
        todo = [self.root]
        while todo:
            pid = todo.pop(0)
            try:
                with open(f"/proc/{pid}/comm", "rb") as fh:
                    if fh.read().startswith(b"python"):
                        return pid
                with open(f"/proc/{pid}/task/{pid}/children", "rb") as fh:
                    todo += [int(x) for x in fh.read().split()]
            except (OSError, ValueError):
                continue
        return 0

    def __call__(self) -> float:
        if not self.pid:
            self.pid = self._find()
        if self.pid:
            try:
                with open(f"/proc/{self.pid}/schedstat", "rb") as fh:
                    fields = fh.read().split()
                self.ran = max(self.ran, int(fields[0]) / 1e9)
                self.last = max(self.last, int(fields[1]) / 1e9)
            except (OSError, ValueError, IndexError):
                pass
        return self.last


class ThreadWaits:
    """The calling thread's run delay (s), from ``/proc/thread-self/schedstat`` opened once (``ok``: it could be)."""

    def __init__(self) -> None:
        self.fd = -1
        with contextlib.suppress(OSError):
            self.fd = os.open("/proc/thread-self/schedstat", os.O_RDONLY | os.O_CLOEXEC)

    @property
    def ok(self) -> bool:
        return self.fd >= 0

    def __call__(self) -> float:
        return int(os.pread(self.fd, 256, 0).split()[1]) / 1e9

    def close(self) -> None:
        if self.fd >= 0:
            with contextlib.suppress(OSError):
                os.close(self.fd)
            self.fd = -1


@dataclass
class Stop:
    """Why the grader ended the worker: ``what`` ("call", "notebook") passed its limit on ``clock``
    ("cpu", or "backstop": the wall clock of a limit timed on CPU time; "wall": no CPU time counter, or the
    notebook's wall-clock cap);
    ``index``: the call's place in the plan."""

    what: str
    clock: str
    index: int = -1


class Watch:
    """The limits of one worker, checked by the grader's loop (see the module docstring).

    ``cell``: each call's limit (s of CPU time); ``cpu_total`` and ``wall_total``: the notebook's (s of CPU
    time, s of its own wall-clock time). Without a meter, the call's limit is on its own wall-clock time.
    """

    def __init__(self, meters: Callable[[int], Meter | None], cell: float, cpu_total: float, wall_total: float) -> None:
        self.meters, self.meter, self.cell = meters, cast("Meter | None", None), cell
        self.cpu_total, self.wall_total = cpu_total, wall_total
        self.cpu0 = self.cpu = 0.0
        self.wall0 = self.elapsed = 0.0
        self.waits, self.section_waits = Waits(0), 0.0
        self.phase = "cells"
        self.section: tuple[str, int, float, float] | None = None  # (what, index, wall, cpu) of what runs now
        #: the run delay and CPU seconds while the grader's calls ran (:attr:`credit`), and their last reading
        self.call_waits = self.call_cpu = 0.0
        self.mark = (0.0, 0.0)
        #: the grader's own waits for a CPU before it read an answer (:meth:`answered`), and its counter
        self.grader_waits, self.grader = 0.0, cast("ThreadWaits | None", None)
        self.seen: tuple[float, float, float] | None = None  # (time, worker's run, its run delay) at the last check

    def _read(self) -> float | None:
        got = self.meter() if self.meter is not None else None
        if got is not None:
            self.cpu = got
        return got

    def begin(self, now: float, pid: int) -> None:
        """The worker ``pid`` started: its meter (``meters(pid)``), and every clock, start now."""
        self.meter = self.meters(pid)
        self.grader = ThreadWaits()  # the thread that runs the grader's loop: this one
        self.waits = Waits(pid)
        self.wall0 = now
        self.cpu0 = self.cpu = self._read() or 0.0
        self.mark = (self.waits(), self.cpu)

    @property
    def used(self) -> float:
        """The notebook's CPU seconds so far (as last read)."""
        return max(0.0, self.cpu - self.cpu0)

    def event(self, kind: str, now: float) -> None:
        """A worker event arrived: the first "cells" ends the cells' phase (the first call is sent next)."""
        if kind == "cells" and self.phase == "cells":
            self.phase, self.section = "calls", None

    def sent(self, index: int, now: float) -> None:
        """The grader sent call ``index``: its clock starts."""
        self._read()
        self.section_waits = self.waits()
        self._account()
        self.phase, self.section = "calls", ("call", index, now, self.cpu)

    def grader_delay(self) -> float:
        """The seconds the grader's loop has waited for a CPU so far (0.0 where the kernel does not say)."""
        if self.grader is not None and self.grader.ok:
            try:
                return self.grader()
            except (OSError, ValueError, IndexError):
                self.grader.close()
        return 0.0

    def answered(self, grader_wait: float = 0.0, now: float | None = None) -> None:
        """The answer to the call sent last arrived; ``grader_wait``: how long the grader's loop, woken to read it,
        waited for a CPU first (the notebook had answered and waited for the next call meanwhile)."""
        self._read()
        self.waits()
        if grader_wait > 0 and self.seen is not None:
            # at most the time the worker's main thread slept since the last check (neither ran nor waited for a
            # CPU): the loop may have been woken before the answer came, while the notebook still computed
            then, ran, waited = self.seen
            now = time.monotonic() if now is None else now
            slept = (now - then) - (self.waits.ran - ran) - (self.waits.last - waited)
            self.grader_waits += max(0.0, min(grader_wait, slept))
        self._account()
        self.section = None

    def _account(self) -> None:
        """Add the run delay and CPU time since the last reading to the calls' figures if a call ran meanwhile."""
        waits, cpu = self.waits.last, self.cpu
        if self.section is not None and self.section[0] == "call":
            self.call_waits += max(0.0, waits - self.mark[0])
            self.call_cpu += max(0.0, cpu - self.mark[1])
        self.mark = (waits, cpu)

    @property
    def credit(self) -> float:
        """What the notebook's wall-clock cap is lengthened by: its waits for a CPU others held while the grader's
        calls ran, at most :data:`.limits.WAIT_CREDIT` times the CPU seconds they used (0.0 without a meter).

        A notebook on a busy machine waits about as long per CPU second as the machine is loaded; one that lowers
        its priority or yields the CPU in a loop waits far longer per CPU second it uses, and gains no more than
        the machine's load would give it. Its own code cells (where a notebook may loop on anything) earn
        nothing: the calls are the grader's requests, each held by its own limits, and their number is the plan's.
        """
        return min(self.call_waits, limits.WAIT_CREDIT * self.call_cpu)

    def close(self) -> None:
        if self.meter is not None:
            self._read()  # the last figure (what the notebook used) stays in self.cpu
            self.meter.close()
        if self.grader is not None:
            self.grader.close()

    @property
    def own(self) -> float:
        """The notebook's own wall-clock seconds so far: less the time it waited for a CPU others held, and the
        time its answers waited for the grader's loop to get a CPU (:meth:`answered`)."""
        return self.elapsed - self.waits.last - self.grader_waits

    def check(self, now: float) -> Stop | None:
        """A limit passed (beyond its grace), or None."""
        cpu = self._read()
        self.elapsed = now - self.wall0
        self.waits()
        self._account()
        self.seen = (now, self.waits.ran, self.waits.last)
        if cpu is not None and cpu - self.cpu0 > self.cpu_total:
            return Stop("notebook", "cpu")
        if self.own > self.wall_total:
            return Stop("notebook", "wall" if self.meter is None else "backstop")
        if self.elapsed - self.credit > limits.WALL_FACTOR * self.wall_total + 1.0:
            return Stop("notebook", "wall")  # the wall-clock cap: however the notebook's own clock was held back
        if self.section is None:
            return None
        what, index, wall0, cpu0 = self.section
        wall0 += self.waits.last - self.section_waits  # the call's own wall clock, too
        if self.meter is None:
            if now - wall0 > self.cell + grace(self.cell):
                return Stop(what, "wall", index)
            return None
        if cpu is not None and cpu - cpu0 > self.cell + grace(self.cell):
            return Stop(what, "cpu", index)
        backstop = limits.WALL_FACTOR * self.cell
        if now - wall0 > backstop + grace(backstop):
            return Stop(what, "backstop", index)
        return None
