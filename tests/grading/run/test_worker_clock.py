"""The worker's CPU-time clock (puma_course/grading/run/worker): a late tick never fails a right answer.

A call timed on CPU time is watched by a SIGALRM handler every 0.05 s that reads the control group's CPU
counter. Signal handlers run between any two bytecodes of the main thread, the handler's own included, so a
tick can come while the previous tick is reading the counter. With ``lseek`` then ``read`` on the shared
descriptor, the inner tick's read moved the offset to the end of the file, the outer read came back empty
and an ``IndexError`` surfaced inside the student's function (the slowish classmate of the hostile fixture
``setsid_busy_children`` lost a case in CI). Checked here:

* the counter reads right however a nested read interleaves with it (``pread`` at offset 0; this fails on
  the old seek-then-read, which returns nothing to the outer read);
* a tick that comes during another returns at once, without reading;
* a tick that cannot read the counter decides nothing (no error, no timeout), while the wall-clock
  backstop and the CPU limit still hold;
* with real signals firing every 0.1 ms, thousands of reads in a row all give the counter.
"""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from puma_course.grading.run import worker
from puma_course.grading.run.worker import CellTimeout

# CI's second pass (another OpenBLAS kernel) leaves this out: the worker's CPU-time clock and its ticks: no
# numerics.
pytestmark = pytest.mark.no_numerics

ROOT = Path(__file__).resolve().parents[3]
COUNTERS = {"ns": b"123456789000\n", "stat": b"usage_usec 123456789\nuser_usec 100000000\nsystem_usec 23456789\n"}


def _counter(tmp_path: Path, fmt: str) -> int:
    path = tmp_path / ("cpuacct.usage" if fmt == "ns" else "cpu.stat")
    path.write_bytes(COUNTERS[fmt])
    return os.open(path, os.O_RDONLY)


@pytest.mark.parametrize("fmt", ["ns", "stat"])
def test_a_read_interrupted_by_another_read_still_gives_the_counter(tmp_path, monkeypatch, fmt):
    """A tick that comes in the middle of a read (after its seek, before its read) reads the counter itself.

    Both ``os.read`` and ``os.pread`` are wrapped so that the first call, once armed, reads the counter
    again before doing its own read: exactly what a nested tick does. The outer read must still see the
    whole counter.
    """
    fd = _counter(tmp_path, fmt)
    state = {"armed": False, "nested": 0}
    real_read, real_pread = os.read, os.pread

    def interrupted(real):
        def call(*args):
            if state["armed"]:
                state["armed"] = False
                state["nested"] += 1
                assert now() == pytest.approx(123.456789)  # the inner tick reads the counter whole
            return real(*args)

        return call

    monkeypatch.setattr(os, "read", interrupted(real_read))
    monkeypatch.setattr(os, "pread", interrupted(real_pread))
    try:
        now = worker._cpu_clock({"fd": fd, "format": fmt})
        assert now is not None and now() == pytest.approx(123.456789)
        state["armed"] = True
        assert now() == pytest.approx(123.456789)  # the outer read, interrupted: was IndexError / OSError
        assert state["nested"] == 1
        assert now() == pytest.approx(123.456789)  # and the next read too
    finally:
        os.close(fd)


def test_a_clock_that_cannot_be_read_at_the_start_is_no_clock(tmp_path):
    empty = tmp_path / "cpu.stat"
    empty.write_bytes(b"")
    fd = os.open(empty, os.O_RDONLY)
    try:
        assert worker._cpu_clock({"fd": fd, "format": "stat"}) is None
        assert worker._cpu_clock({"fd": fd, "format": "ns"}) is None
        assert worker._cpu_clock({"fd": "3", "format": "ns"}) is None
        assert worker._cpu_clock(None) is None
    finally:
        os.close(fd)


class _Clock:
    """A fake monotonic clock and CPU counter the test sets by hand."""

    def __init__(self) -> None:
        self.cpu, self.wall, self.reads = 0.0, 0.0, 0
        self.fail: BaseException | None = None
        self.during_read = None  # called inside a read: a tick arriving then

    def cpu_now(self) -> float:
        self.reads += 1
        if self.during_read is not None:
            inner, self.during_read = self.during_read, None
            inner()
        if self.fail is not None:
            raise self.fail
        return self.cpu

    def monotonic(self) -> float:
        return self.wall


def _tick(clock: _Clock, limit: float = 1.0, wall: float = 3.0):
    return worker._ticker(clock.cpu_now, 0.0, limit, wall, 0.0, clock.monotonic)


def test_a_tick_decides_on_the_cpu_time_then_on_the_backstop():
    clock = _Clock()
    tick = _tick(clock)
    clock.cpu, clock.wall = 0.9, 2.0
    assert tick(14, None) is None
    clock.cpu = 1.1
    with pytest.raises(CellTimeout) as cpu:
        tick(14, None)
    assert cpu.value.args == ("cpu",)
    clock = _Clock()
    tick = _tick(clock)
    clock.cpu, clock.wall = 0.2, 3.5  # waiting on something: little CPU, the wall clock ran out
    with pytest.raises(CellTimeout) as backstop:
        tick(14, None)
    assert backstop.value.args == ("backstop",)


def test_the_backstop_is_the_calls_own_wall_clock_less_its_waits_for_a_cpu():
    """On a busy machine (fork storms beside the grader, load ~19 on 2 cores) an honest call of 0.2 s of CPU
    took over 3 s of wall clock and the worker's own backstop failed it ("ran longer than 3 s on the wall
    clock"): the time the call waited for a CPU others held does not count, as in the grader's monitor."""
    clock = _Clock()
    waited = [0.5]  # before the call: not the call's
    tick = worker._ticker(clock.cpu_now, 0.0, 1.0, 3.0, 0.0, clock.monotonic, lambda: waited[0])
    clock.cpu, clock.wall, waited[0] = 0.2, 3.5, 2.0  # 1.5 s of the 3.5 s waiting for a CPU: 2 s its own
    assert tick(14, None) is None
    clock.wall = 5.01  # 3.01 s its own
    with pytest.raises(CellTimeout) as backstop:
        tick(14, None)
    assert backstop.value.args == ("backstop",)
    clock = _Clock()  # a counter that cannot be read: the wall clock as it is
    tick = worker._ticker(clock.cpu_now, 0.0, 1.0, 3.0, 0.0, clock.monotonic, lambda: int("x"))
    clock.wall = 3.01
    with pytest.raises(CellTimeout):
        tick(14, None)


@pytest.mark.skipif(not hasattr(os, "sched_setaffinity"), reason="no CPU affinity here")
def test_the_run_delay_counter_grows_while_another_process_holds_the_cpu():
    waits = worker._run_delay()
    if waits is None:
        pytest.skip("no /proc/thread-self/schedstat here")
    core = min(os.sched_getaffinity(0))
    before = os.sched_getaffinity(0)
    code = f"import os\nos.sched_setaffinity(0, {{{core}}})\nwhile True: pass"
    busy = subprocess.Popen([sys.executable, "-c", code], start_new_session=True)
    try:
        time.sleep(0.2)
        os.sched_setaffinity(0, {core})
        w0, t0 = waits(), time.process_time()
        while time.process_time() < t0 + 0.3:  # 0.3 s of CPU on a core shared with a busy process
            pass
        waited = waits() - w0
    finally:
        os.sched_setaffinity(0, before)
        busy.kill()
        busy.wait()
    assert waited > 0.1, waited  # about as long as it ran (a fair share of the core): at least a third of it


def test_a_tick_raises_once_and_never_again_in_that_call():
    """Code that catches the timeout runs on until the grader's own limits end it: a second tick that landed
    outside its ``try`` would end the cell by luck (stubborn_loop: 10/15 instead of 0 in one CI run of two)."""
    clock = _Clock()
    tick = _tick(clock)
    clock.cpu = 1.5
    with pytest.raises(CellTimeout):
        tick(14, None)
    clock.cpu, clock.wall = 9.0, 9.0  # far past both limits
    assert [tick(14, None) for _ in range(100)] == [None] * 100
    assert clock.reads == 1  # the later ticks read nothing and decided nothing


def test_a_tick_during_another_returns_at_once():
    clock = _Clock()
    tick = _tick(clock)
    clock.cpu = 5.0  # past the limit: the outer tick raises, the inner one must not
    inner: list[object] = []
    clock.during_read = lambda: inner.append(tick(14, None))
    with pytest.raises(CellTimeout) as exc:
        tick(14, None)
    assert exc.value.args == ("cpu",)
    assert inner == [None] and clock.reads == 1  # the inner tick read nothing and decided nothing
    clock = _Clock()
    tick = _tick(clock)
    clock.cpu = 0.5
    clock.during_read = lambda: inner.append(tick(14, None))
    assert tick(14, None) is None and inner == [None, None] and clock.reads == 1
    assert tick(14, None) is None and clock.reads == 2  # the guard is released after a tick that decided nothing


@pytest.mark.parametrize("error", [IndexError("list index out of range"), OSError(9, "bad descriptor"), ValueError()])
def test_a_tick_that_cannot_read_the_counter_decides_nothing(error):
    clock = _Clock()
    tick = _tick(clock)
    clock.fail = error
    assert tick(14, None) is None  # was: the error, raised inside the student's function
    clock.fail, clock.cpu = None, 2.0
    with pytest.raises(CellTimeout) as exc:  # and the next tick that reads decides again
        tick(14, None)
    assert exc.value.args == ("cpu",)
    clock = _Clock()
    tick = _tick(clock)
    clock.fail, clock.wall = error, 3.5
    with pytest.raises(CellTimeout) as exc:  # the backstop holds while the counter cannot be read
        tick(14, None)
    assert exc.value.args == ("backstop",)


_STORM = """
import os, signal, sys
sys.path.insert(0, {folder!r})
import worker
fd = os.open({path!r}, os.O_RDONLY)
now = worker._cpu_clock({{"fd": fd, "format": "stat"}})
bad = []
def tick(signum, frame):
    try:
        now()
    except Exception as exc:
        bad.append(repr(exc))
signal.signal(signal.SIGALRM, tick)
signal.setitimer(signal.ITIMER_REAL, 0.0001, 0.0001)
for _ in range(20000):
    try:
        assert now() == 123.456789
    except Exception as exc:
        bad.append(repr(exc))
signal.setitimer(signal.ITIMER_REAL, 0)
print(len(bad), bad[:3])
"""


def test_reads_under_a_storm_of_real_ticks_all_give_the_counter(tmp_path):
    """20 000 reads with a SIGALRM handler reading the same descriptor every 0.1 ms: none fails."""
    path = tmp_path / "cpu.stat"
    path.write_bytes(COUNTERS["stat"])
    folder = str(ROOT / "puma_course" / "grading" / "run")  # the worker imports the standard library only
    code = textwrap.dedent(_STORM).format(folder=folder, path=str(path))
    done = subprocess.run([sys.executable, "-I", "-c", code], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split()[0] == "0", done.stdout
