"""The grader's monitor (grading/run/monitor.py, issue 30): limits a notebook cannot switch off or talk its way past.

* the clocks: a call passes its CPU limit (beyond the grace) or its wall-clock backstop; the notebook its CPU
  time or its own wall-clock time, which does not count the time it waited for a CPU others held;
* the channel: a worker receives a call only once it has answered the one before (checked by the worker
  itself), a line that answers another case does not stop the outstanding call's clock, and a call that never
  answers is ended at its limit plus the grace, by CPU time (a fake worker, :func:`.child.run`);
* the /proc meter: a process tree's CPU time, a forked child's included (by hand: the CPU a child burns).
"""

from __future__ import annotations

import os
import sys
import textwrap
import time

import pytest

from puma_course.grading.run import child, limits, monitor

# CI's second pass (another OpenBLAS kernel) leaves this out: the grader's monitor of time and processes: no
# numerics.
pytestmark = pytest.mark.no_numerics


class _Meter(monitor.Meter):
    def __init__(self) -> None:
        self.cpu = 0.0

    def __call__(self) -> float | None:
        return self.cpu


def _watch(meter, cell=1.0, cpu_total=10.0, wall_total=10.0):
    w = monitor.Watch(lambda pid: meter, cell, cpu_total, wall_total)
    w.begin(100.0, 0)
    return w


def test_a_call_ends_on_its_cpu_time_past_the_grace_not_before():
    m = _Meter()
    w = _watch(m)
    w.event("cells", 100.0)
    w.sent(0, 100.0)
    m.cpu = 1.0 + monitor.grace(1.0) - 0.01  # past the limit, within the grace: the worker's own timer acts
    assert w.check(101.0) is None
    m.cpu = 1.0 + monitor.grace(1.0) + 0.01
    assert w.check(101.0) == monitor.Stop("call", "cpu", 0)
    w.answered()
    assert w.check(101.0) is None  # between calls: only the notebook's limits


def test_a_call_that_waits_ends_on_the_backstop_and_the_notebook_on_its_totals():
    m = _Meter()
    w = _watch(m)
    w.sent(3, 100.0)
    backstop = limits.WALL_FACTOR * 1.0
    assert w.check(100.0 + backstop + monitor.grace(backstop) - 0.01) is None
    assert w.check(100.0 + backstop + monitor.grace(backstop) + 0.01) == monitor.Stop("call", "backstop", 3)
    w.answered()
    m.cpu = 10.5
    assert w.check(101.0) == monitor.Stop("notebook", "cpu")
    m.cpu = 0.0
    assert w.check(110.5) == monitor.Stop("notebook", "backstop")


def test_waiting_for_a_cpu_others_hold_is_not_the_notebooks_time():
    m = _Meter()
    w = _watch(m)
    w.waits.pid, w.waits.last = -1, 0.0  # a worker found; its run delay set by hand below
    w.waits.__class__ = type("FixedWaits", (monitor.Waits,), {"__call__": lambda self: self.last})
    w.waits.last = 8.0  # 8 s of the 12 s it ran, it waited for a CPU
    assert w.check(112.0) is None and w.own == pytest.approx(4.0)
    assert w.check(118.5) == monitor.Stop("notebook", "backstop")  # 10.5 s of its own


def _fixed_waits(w):
    w.waits.pid, w.waits.last = -1, 0.0  # a worker found; its run delay set by hand
    w.waits.__class__ = type("FixedWaits", (monitor.Waits,), {"__call__": lambda self: self.last})


def test_the_wall_clock_cap_grows_by_the_waits_during_calls_only_and_at_most_so_much():
    cap = limits.WALL_FACTOR * 10.0 + 1.0  # 31 s of wall clock for a notebook of 10 s
    # in its own cells, waits earn nothing: 25 s of waiting and 6.5 s of its own end it on the wall clock
    m = _Meter()
    w = _watch(m, cell=10.0)
    _fixed_waits(w)
    w.waits.last, m.cpu = 25.0, 1.0
    assert w.check(100.0 + cap - 0.01) is None
    assert w.check(100.0 + cap + 0.01) == monitor.Stop("notebook", "wall")
    assert w.credit == 0.0
    # in the grader's calls, on a busy machine (a few seconds of waiting per CPU second): all of it counts, and
    # only from the call's start (the 5 s it waited in its cells do not)
    m = _Meter()
    w = _watch(m, cell=10.0)
    _fixed_waits(w)
    w.waits.last, m.cpu = 5.0, 0.2
    assert w.check(106.0) is None
    w.event("cells", 106.0)
    w.sent(0, 106.0)
    w.waits.last, m.cpu = 40.0, 2.2  # 35 s of waiting in the call, 2 s of CPU: at most 20 x 2 s
    assert w.check(146.0) is None and w.credit == pytest.approx(35.0)  # 46 s of wall clock, 6 s its own
    w.answered()
    w.waits.last, m.cpu = 58.0, 2.3  # between calls (18 s more waiting): nothing more
    assert w.check(100.0 + cap + 35.0 - 0.01) is None and w.credit == pytest.approx(35.0)
    assert w.check(100.0 + cap + 35.0 + 0.01) == monitor.Stop("notebook", "wall")
    # a call that waits far longer per CPU second (a low priority, a loop yielding the CPU) gains at most
    # WAIT_CREDIT times its CPU time
    m = _Meter()
    w = _watch(m, cell=10.0)
    _fixed_waits(w)
    w.event("cells", 100.0)
    w.sent(0, 100.0)
    most = limits.WAIT_CREDIT * 0.1
    w.waits.last, m.cpu = cap + most - 3.0, 0.1  # it waited all but 3 s, for 0.1 s of CPU
    assert w.check(100.0 + cap + most - 0.01) is None
    assert w.credit == pytest.approx(most)
    assert w.check(100.0 + cap + most + 0.01) == monitor.Stop("notebook", "wall")


def test_an_answer_that_waited_for_the_graders_loop_is_not_the_notebooks_time():
    """The worker answers, then waits for the next call; on a busy machine the grader's loop, woken by the answer,
    first waits for a CPU (at a load of 16 on 2 cores: 9 s over 51 calls, 1.5 s of the notebook's 5 s own time)."""
    m = _Meter()
    w = _watch(m)
    _fixed_waits(w)
    w.event("cells", 100.0)
    w.sent(0, 100.0)
    assert w.check(103.0) is None and w.own == pytest.approx(3.0)
    # the loop waited 0.8 s for a CPU before it read the answer, but the worker slept only 0.5 s of it (it was
    # still computing when the loop woke): 0.5 s
    w.answered(0.8, 103.5)
    assert w.check(103.5) is None and w.own == pytest.approx(3.0)
    w.sent(1, 103.5)
    assert w.check(104.0) is None
    w.answered(0.3, 104.6)  # slept 0.6 s, of which the loop's 0.3 s
    assert w.check(104.6) is None and w.own == pytest.approx(3.8)
    w.sent(2, 104.6)
    w.answered(-1.0, 105.0)  # a counter read wrong: nothing
    assert w.check(110.79) is None
    assert w.check(110.81) == monitor.Stop("notebook", "backstop")  # 10.01 s of its own
    g = monitor.ThreadWaits()
    try:
        assert not g.ok or g() >= 0.0
    finally:
        g.close()


#: A fake worker: reads the job line, says ready and cells, then checks that each call comes alone.
_WORKER = textwrap.dedent(
    """
    import json, os, select, sys, time
    fd = 0
    def line():
        buf = b""
        while not buf.endswith(b"\\n"):
            c = os.read(fd, 1)
            if not c:
                return None
            buf += c
        return buf
    def out(obj):
        os.write(1, (json.dumps(obj) + "\\n").encode())
    line()
    out({"kind": "ready"})
    out({"kind": "cells"})
    while (got := line()) is not None:
        call = json.loads(got)
        time.sleep(0.2)
        alone = not select.select([fd], [], [], 0)[0]  # nothing more was sent before this answer
        if call["case"] == {burn}:
            out({"kind": "call", "qid": "zz", "case": 9})  # not this call's answer: its clock runs on
            end = time.process_time() + 30
            while time.process_time() < end:
                pass
        out({"kind": "call", "qid": call["qid"], "case": call["case"], "value": [float(alone)]})
    out({"kind": "done"})
    """
)


def _calls(n):
    return [f'{{"qid": "q1", "case": {i}, "function": "f", "args": []}}\n'.encode() for i in range(n)]


def _run(burn, n=3, cell=1.0):
    watch = monitor.Watch(lambda pid: monitor.meter_for(None, pid), cell, 60.0, 60.0)
    code = _WORKER.replace("{burn}", str(burn))
    return child.run([sys.executable, "-c", code], b"{}\n", cwd=None, env=dict(os.environ), timeout=60,
                     calls=_calls(n), watch=watch)  # fmt: skip


@pytest.mark.skipif(not os.path.isdir("/proc/self/task"), reason="no /proc here")
def test_each_call_comes_alone_once_the_one_before_is_answered():
    out = _run(burn=-1)
    answers = [e for e in out.events if e.get("kind") == "call"]
    assert [(e["case"], e["value"]) for e in answers] == [(0, [1.0]), (1, [1.0]), (2, [1.0])]
    assert out.done and out.sent == 3 and out.stopped is None


@pytest.mark.skipif(not os.path.isdir("/proc/self/task"), reason="no /proc here")
def test_a_call_that_never_answers_is_ended_on_its_cpu_time_whatever_it_writes():
    t0 = time.perf_counter()
    out = _run(burn=1, cell=0.5)
    assert out.stopped == monitor.Stop("call", "cpu", 1), out.stopped
    assert out.sent == 2 and not out.done  # the third call was never sent
    assert 0.5 + monitor.grace(0.5) <= out.cpu < 30, out.cpu
    print(f"\na call burning CPU under a 0.5 s limit ended after {time.perf_counter() - t0:.1f} s, {out.cpu:.2f} s CPU")


@pytest.mark.skipif(not os.path.isdir("/proc/self/task"), reason="no /proc here")
def test_the_proc_meter_counts_a_forked_child():
    import subprocess

    code = (
        "import os, time\nif os.fork() == 0:\n    e = time.process_time() + 1.0\n"
        "    while time.process_time() < e: pass\n    time.sleep(30)\n    os._exit(0)\ntime.sleep(30)"
    )
    p = subprocess.Popen([sys.executable, "-c", code], start_new_session=True)
    try:
        meter = monitor.meter_for(None, p.pid)
        assert isinstance(meter, monitor.TreeMeter)
        end = time.monotonic() + 30
        while (meter() or 0.0) < 0.9 and time.monotonic() < end:
            time.sleep(0.05)
        assert (meter() or 0.0) >= 0.9  # the child's second of CPU, not the parent's sleep
    finally:
        os.killpg(p.pid, 9)
        p.wait()
