"""The child side of grading: parse one notebook, run its code cells, call the student's functions, report plain data.

The grader (:mod:`puma_course.grading.run.runner`) copies this folder out of the package and runs it
in a fresh ``python -I -S -B`` process (under the OS sandbox when there is one), so it needs the
standard library only (numpy once student code runs) and imports nothing from the course package:
the ``puma_course`` a student's cell imports is the student-side copy named in the job
(:mod:`puma_course.grading.run.student`). Its standard input holds one JSON line, the job::

    {"notebook_bytes": n, "timeout_cell": s, "wall": s, "max_size": n,
     "forbidden": {qid: ["module:attr", ...]}, "path": [folder, ...], "limits": {...}, "filename": name,
     "cpu_clock": {"fd": n, "format": "ns" | "stat", "wall": s}}   (cpu_clock: with a control group only)

followed by the submitted notebook's ``notebook_bytes`` bytes, which it parses here (never in the grader's
process): its code cells, with hidden-test blocks removed as the release removes them (they check a
solution against the package, which the student side does not have). It executes the cells in
order in one namespace (a cell that raises or runs past ``timeout_cell`` is recorded and the next
cell still runs; the limit is CPU time, with a backstop of ``wall`` s of its own wall-clock time (less its
waits for a CPU others held): with ``cpu_clock``,
the descriptor of the notebook's control-group counter, the whole notebook's, else this process's and its
waited-for children's), then reads the calls from its stdin, one JSON line ``{"qid", "case", "function",
"args"}`` at a time (the grader sends the next once this one is answered, and ends its stdin after the last;
a job with a ``"calls"`` list holds them all instead), calls each requested function on the grader's inputs
and streams JSON lines back on the original stdout, one event per line::

    {"kind": "ready"}   (first, once the job is read: the worker started)
    {"kind": "malformed", "code": "json" | "encoding" | "nesting" | "no-cells" | "cell" | "too-much-code", ...}
    {"kind": "cell", "index": i, "first": "its 1st line", "status": "error" | "timeout", "detail": "...", "line": n}
    {"kind": "cells"}   (the cells ran: the grader sends the first call; not with a "calls" list)
    {"kind": "call", "qid": "q1", "case": 0, "value": [...]}  or  "error": CODE, "detail": "..."
    (a cell or call that ran out of time also says on which "clock": "cpu", "backstop" or "wall")
    {"kind": "done"}

This timer is the polite stop (the notebook goes on with its next question); the limits hold in the
grader's process (:mod:`puma_course.grading.run.monitor`), which ends a worker whose timer was switched off.

Only numbers travel back (at most ``max_size`` of them), and errors travel as a code plus the
student's own text (``detail``); the grader words them, quotes the student's text and compares
the numbers with the package's reference in its own process, so nothing the student's code does
here can change how values are judged. The student's prints go to a small capped buffer, and the
OS-level stdout/stderr are pointed at /dev/null so that a flood of output costs nothing.

"Forbidden" package functions (a question's answer key, e.g. ``puma_course.transforms:rodrigues``
for "write Rodrigues' formula") are absent from the student side unless the exercise allows them;
an allowed class holds only its allowed members (no ``Puma560.ik`` where ``ik`` is the answer).
What is left of the key within reach (an answer that must be allowed, say) is wrapped before any
student code runs and watched by code object while each question is graded; a call to it, or
switching the watch off (``sys.setprofile(None)``, a thread), fails the case: a second line of
defence, not the first.
"""

from __future__ import annotations

import json
import os
import signal
import sys
import time
from typing import Any

from .guard import (
    CappedWriter,
    describe,
    forbidden_codes,
    guarded_call,
    install_tripwires,
    limit_resources,
    resolve,
    type_name,
)
from .notebook import NotebookError, notebook_cells, strip_hidden, strip_magics

__all__ = [
    "main",
    "strip_magics",
    "strip_hidden",
    "notebook_cells",
    "NotebookError",
    "resolve",
    "forbidden_codes",
    "guarded_call",
    "limit_resources",
    "received",
    "MAX_SIZE",
    "as_numbers",
    "describe",
    "type_name",
    "NOT_ATTEMPTED",
]

#: The most numbers one answer may hold (the job's ``max_size``; the grader and the self-check set it).
MAX_SIZE = 10_000

#: The reason given for a case whose function still raises NotImplementedError (the released stub).
NOT_ATTEMPTED = "not attempted yet"


class CellTimeout(BaseException):
    """Raised by the alarm when a cell or a call runs past its time limit (``args``: ("cpu",) for its CPU time,
    ("backstop",) for the wall-clock backstop of a CPU-timed call, () for the wall clock alone)."""


#: How often (s) a cell or call timed on CPU time checks the counter.
TICK = 0.05


def _cpu_clock(spec: Any) -> Any:
    """A function giving the notebook group's CPU seconds, read from the descriptor the grader passed (None: none).

    ``spec`` is ``{"fd": n, "format": "ns" | "stat"}`` (v1's ``cpuacct.usage``, v2's ``cpu.stat``). The
    counter is read with ``pread`` at offset 0, which leaves the descriptor's offset alone: a tick that comes
    while another read is under way (between its seek and its read, with ``lseek`` then ``read``) cannot leave
    that read at the end of the file, empty.
    """
    if not isinstance(spec, dict) or not isinstance(spec.get("fd"), int) or spec.get("format") not in ("ns", "stat"):
        return None
    fd, fmt, pread = spec["fd"], spec["format"], os.pread

    def now() -> float:
        data = pread(fd, 4096, 0)
        if fmt == "ns":
            return int(data.split()[0]) / 1e9
        for line in data.split(b"\n"):
            if line.startswith(b"usage_usec "):
                return int(line.split()[1]) / 1e6
        raise OSError("no usage_usec in cpu.stat")

    try:
        now()
    except (OSError, ValueError, IndexError):
        return None
    return now


def _run_delay() -> Any:
    """A function giving the seconds this thread (the main one, which runs the alarm's handler) has waited for a
    CPU others held, from ``/proc/thread-self/schedstat`` opened now (None where the kernel does not say)."""
    try:
        fd = os.open("/proc/thread-self/schedstat", os.O_RDONLY | os.O_CLOEXEC)
    except OSError:
        return None
    pread = os.pread

    def now() -> float:
        return int(pread(fd, 256, 0).split()[1]) / 1e9

    try:
        now()
    except (OSError, ValueError, IndexError):
        os.close(fd)
        return None
    return now


def _ticker(
    cpu_now: Any, cpu0: float, limit: float, wall: float, wall0: float, monotonic: Any, waits: Any = None
) -> Any:
    """The SIGALRM handler of a call timed on CPU time: every :data:`TICK` s, is the call past its limit?

    It raises :class:`CellTimeout` ("cpu") once the group has used more than ``limit`` CPU seconds since
    ``cpu0``, or ("backstop") once more than ``wall`` seconds of its own have passed since ``wall0``: the wall
    clock less what ``waits()`` (:func:`_run_delay`) grew by meanwhile, the time this process waited for a CPU
    others held, as the grader's monitor counts it (a busy machine must not end an honest call). A tick that comes
    while another is still running returns at once (the running one decides), and a tick that cannot read
    the counter decides nothing about CPU time (the next tick reads again; the backstop still holds): a late
    tick must never surface as an error inside the student's function. It raises once: code that catches it runs
    on until the grader's limits end it, never out by a later tick that lands outside its ``try`` (luck, not work).
    """
    busy = [False]
    try:
        waits0 = waits() if waits is not None else 0.0
    except (OSError, ValueError, IndexError):
        waits = None

    def on_tick(signum: int, frame: Any) -> None:
        if busy[0]:
            return
        busy[0] = True
        try:
            try:
                used: float | None = cpu_now() - cpu0
            except (OSError, ValueError, IndexError):
                used = None
            elapsed = monotonic() - wall0
            if waits is not None:
                try:
                    elapsed -= max(0.0, waits() - waits0)
                except (OSError, ValueError, IndexError):
                    pass  # the wall clock as it is
        finally:
            busy[0] = False
        if (used is not None and used > limit) or elapsed > wall:
            busy[0] = True  # fired: every later tick returns at once
            raise CellTimeout("cpu" if used is not None and used > limit else "backstop")

    return on_tick


def _own_clock(wall: Any) -> Any:
    """Without a control group's counter: this process's CPU time, its waited-for children's included (None
    where the job gives no wall-clock backstop: the wall clock alone, as a job written by hand asks)."""
    if not wall:
        return None
    times = os.times

    def now() -> float:
        t = times()
        return t[0] + t[1] + t[2] + t[3]

    return now


def _ready(job: dict[str, Any]) -> None:
    """Set the import path to the student side first, then the standard library and site-packages (no .pth files)."""
    stdlib = [p for p in sys.path if p]
    sys.path[:] = [str(p) for p in job.get("path", [])[:1]] + stdlib + [str(p) for p in job.get("path", [])[1:]]
    sys.argv = ["notebook"]
    sys.dont_write_bytecode = True


def main() -> None:
    """Run one job read from stdin (see the module docstring)."""
    # Keep private references before any student code can monkeypatch them.
    dumps, write = json.dumps, os.write
    out_fd = os.dup(1)

    def emit(event: dict[str, Any]) -> None:
        data = (dumps(event) + "\n").encode()
        view = memoryview(data)
        while view:
            n = write(out_fd, view)
            view = view[n:]

    line, exact = _reader(os.dup(0), os.read)
    header = line() or b""
    emit({"kind": "ready"})  # the worker started: what follows is the notebook's doing
    job = json.loads(header)
    size = job.get("notebook_bytes")
    notebook = exact(size) if isinstance(size, int) and size >= 0 else exact(-1)
    limit_resources(job.get("limits"))
    _ready(job)
    try:
        sources = notebook_cells(notebook)
    except NotebookError as exc:
        emit({"kind": "malformed", "code": exc.code, "line": exc.line, "column": exc.column})
        return
    name = str(job.get("filename", ""))
    if name and "/" not in name and "\\" not in name and not name.startswith("."):
        try:
            with open(name, "wb") as fh:  # a copy, for a student whose code opens its own notebook
                fh.write(notebook)
        except OSError:
            pass
    del notebook
    devnull = os.open(os.devnull, os.O_RDWR)
    for fd in (0, 1, 2):
        os.dup2(devnull, fd)
    sink = CappedWriter()
    sys.stdout = sys.stderr = sink
    if isinstance(job.get("calls"), list):  # every call in the job line (a test's job, or a run by hand)
        listed = iter(job["calls"])
        _run(job, sources, emit, lambda: next(listed, None), False)
    else:  # one at a time, each once the one before is answered (the grader's runs: grading/run/child.py)
        _run(job, sources, emit, lambda: _next_call(line), True)


def _reader(fd: int, read: Any) -> tuple[Any, Any]:
    """A private reader of the job's pipe: ``line()`` (None at its end) and ``exact(n)`` (-1: to the end)."""
    buf = bytearray()

    def fill() -> bool:
        chunk = read(fd, 1 << 20)
        buf.extend(chunk)
        return bool(chunk)

    def line() -> bytes | None:
        while True:
            end = buf.find(b"\n")
            if end >= 0:
                out = bytes(buf[:end])
                del buf[: end + 1]
                return out
            if not fill():
                out = bytes(buf)
                buf.clear()
                return out or None

    def exact(n: int) -> bytes:
        while (n < 0 or len(buf) < n) and fill():
            pass
        out = bytes(buf if n < 0 else buf[:n])
        del buf[: len(out)]
        return out

    return line, exact


def _next_call(line: Any) -> dict[str, Any] | None:
    """The next call the grader sends (None once it has sent them all)."""
    data = line()
    if not data:
        return None
    try:
        call = json.loads(data)
    except ValueError:
        return None
    return call if isinstance(call, dict) else None


def first_line(source: str, limit: int = 80) -> str:
    """A code cell's first line that is not blank, at most ``limit`` characters: how the feedback names the cell
    (JupyterLab shows no cell numbers, so "code cell 4" would leave the student counting).

    >>> first_line("\\n  \\ndef f(x):\\n    return x"), first_line("")
    ('def f(x):', '')
    """
    for line in source.splitlines():
        if line.strip():
            line = line.strip()
            return line if len(line) <= limit else line[: limit - 1] + "…"
    return ""


def received(args: list[Any], asarray: Any, to_float: Any) -> list[Any]:
    """A call's arguments (JSON values) as the student's function receives them: each list an array of floats.

    The grader sends every array, list or tuple argument as a JSON list, so the student's function is
    always handed a numpy array there, never a list; the self-check (:mod:`puma_course.grading.selfcheck`)
    hands over the same. ``asarray`` and ``to_float`` are numpy's, taken before the notebook ran.
    """
    return [asarray(a, dtype=to_float) if isinstance(a, list) else a for a in args]


def as_numbers(value: Any, asarray: Any, to_float: Any) -> Any:
    """A returned value as the array of floats the grader judges (complex numbers refused).

    Raises whatever numpy raises for a value that is not an array of numbers (a tuple of an array
    and a number, say): the grader then reports it as ``not-numbers``.
    """
    raw = asarray(value)
    if raw.dtype.kind == "c":
        raise TypeError("complex numbers are not accepted")
    return asarray(raw, dtype=to_float)


def _run(job: dict[str, Any], sources: list[str], emit: Any, next_call: Any, asks: bool) -> None:
    """Execute the cells, then make the calls (see the module docstring)."""
    import numpy as np

    asarray, to_float = np.asarray, float
    setitimer, ITIMER_REAL = signal.setitimer, signal.ITIMER_REAL

    def on_alarm(signum: int, frame: Any) -> None:
        raise CellTimeout()

    timeout = float(job.get("timeout_cell", 10.0))
    max_size = int(job.get("max_size", MAX_SIZE))
    cpu_now = _cpu_clock(job.get("cpu_clock")) or _own_clock(job.get("wall"))
    wall = float(job.get("wall") or (job.get("cpu_clock") or {}).get("wall", timeout))
    monotonic = time.monotonic
    waits = _run_delay() if cpu_now is not None else None  # opened before any student code runs

    def run_timed(fn: Any, *args: Any) -> Any:
        if cpu_now is None:  # no CPU time counter: the wall clock
            signal.signal(signal.SIGALRM, on_alarm)
            setitimer(ITIMER_REAL, timeout)
        else:  # the notebook's (or this process's) CPU time, checked every TICK s, and the wall-clock backstop
            signal.signal(signal.SIGALRM, _ticker(cpu_now, cpu_now(), timeout, wall, monotonic(), monotonic, waits))
            setitimer(ITIMER_REAL, TICK, TICK)
        try:
            return fn(*args)
        finally:
            setitimer(ITIMER_REAL, 0)

    def clock(exc: CellTimeout) -> str:
        return exc.args[0] if exc.args in (("cpu",), ("backstop",)) else "wall"

    def described(exc: BaseException) -> tuple[str, int]:
        try:
            return run_timed(describe, exc)  # a hostile __str__ must not escape the time limit
        except CellTimeout:
            return f"{type_name(exc)}: (its message took too long to read)", 0

    def display(*objs: Any, **kwargs: Any) -> None:  # IPython's display() for plain Python
        for obj in objs:
            print(repr(obj))

    forbidden = {qid: set(specs) for qid, specs in job.get("forbidden", {}).items()}
    state: dict[str, Any] = {"guard": set(), "hit": None}
    codes = {qid: forbidden_codes(specs) for qid, specs in forbidden.items()}  # the originals' code, before wrapping
    install_tripwires(set().union(*forbidden.values()) if forbidden else set(), state)

    ns: dict[str, Any] = {"__name__": "__main__", "display": display}
    for index, source in enumerate(sources):
        event: dict[str, Any] = {"kind": "cell", "index": index, "first": first_line(source)}
        try:
            code = compile(strip_magics(source), f"<cell {index + 1}>", "exec")
            run_timed(exec, code, ns)
            continue  # a cell that ran says nothing
        except CellTimeout as exc:
            event["status"], event["clock"] = "timeout", clock(exc)
        except BaseException as exc:  # noqa: BLE001 - SystemExit, KeyboardInterrupt: all are the student's
            event["status"] = "error"
            event["detail"], event["line"] = described(exc)
        emit(event)

    slow: set[str] = set()  # questions whose function already ran out of time: skip their other cases
    if asks:
        emit({"kind": "cells"})  # the cells ran: the grader sends the first call
    while (call := next_call()) is not None:
        event = {"kind": "call", "qid": call["qid"], "case": call["case"]}
        fn = ns.get(call["function"])
        if call["qid"] in slow:
            event["error"] = "skipped"
        elif fn is None:
            event["error"] = "no-function"
        elif not callable(fn):
            event["error"], event["detail"] = "not-callable", type_name(fn)
        else:
            args = received(call["args"], asarray, to_float)
            state["guard"], state["hit"] = forbidden.get(call["qid"], set()), None
            try:
                value, hit = run_timed(guarded_call, fn, args, codes.get(call["qid"], {}))
                if hit is not None and state["hit"] is None:
                    state["hit"] = hit
            except CellTimeout as exc:
                event["error"], event["clock"] = "timeout", clock(exc)
                slow.add(call["qid"])
            except NotImplementedError:
                event["error"] = "not-attempted"
            except BaseException as exc:  # noqa: BLE001
                event["error"] = "raised"
                event["detail"], event["line"] = described(exc)
            else:
                try:
                    arr = run_timed(as_numbers, value, asarray, to_float)  # a hostile __array__: within the limit
                except CellTimeout:
                    event["error"] = "convert-timeout"
                    slow.add(call["qid"])
                except BaseException as exc:  # noqa: BLE001
                    event["error"], event["detail"] = "not-numbers", type_name(value)
                    event["why"] = described(exc)[0]
                else:
                    if state["hit"] is not None:
                        event["error"], event["detail"] = "answer-key", state["hit"]
                    elif arr.size > max_size:
                        event["error"], event["size"] = "too-many", int(arr.size)
                    else:
                        event["value"] = arr.tolist()
            state["guard"] = set()
        emit(event)
    emit({"kind": "done"})


if __name__ == "__main__":  # pragma: no cover - started by the grader
    main()
