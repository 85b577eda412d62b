"""Running one worker process: feed it, read its events, and stop it on time, whatever it does.

:func:`run` starts the command in its own session, writes the payload to its standard input and
reads JSON lines from its standard output in one loop (non-blocking pipes and a selector; on
Linux a pidfd wakes the loop the moment the process exits), so there is no fixed wait anywhere:

* it stops reading as soon as the worker's last event (``{"kind": "done"}``) arrives, or when the
  process has exited and the pipe holds nothing more, even if a grandchild still holds the pipe
  open; whatever runs at the process's exit (``atexit``, threads, ``__del__``) costs nothing;
* at the deadline, or when the output passes its cap, it stops the process;
* it hands the worker its calls one at a time (``calls``: one JSON line each), the first once the worker
  says its cells ran (``{"kind": "cells"}``), each next one once the answer to the one before has come
  (a ``call`` event of that question and case), and closes the worker's stdin after the last;
* with a :class:`~.monitor.Watch`, it reads the notebook's CPU time every :data:`~.monitor.TICK` s and
  stops the process when a cell, a call or the notebook passes its limit (:attr:`ChildResult.stopped`);
* at the end it kills the whole session (``killpg``), so children the student's code started in
  that session end with it (under bubblewrap the whole PID namespace ends with the worker).

Lines that are not JSON objects of a kind the worker sends are skipped and counted
(:attr:`ChildResult.foreign`): the worker writes only whole event lines, so any other line is the
student's code writing to this pipe (which it can find among its descriptors); what the events
mean is for the caller to decide.
"""

from __future__ import annotations

import json
import os
import selectors
import signal
import subprocess
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from .monitor import TICK, Stop, Watch

__all__ = ["ChildResult", "run", "MAX_OUTPUT_BYTES", "MAX_LINE_BYTES"]

#: The most a worker may send back in all, and in one line (10,000 numbers are about 250 kB).
MAX_OUTPUT_BYTES = 16_000_000
MAX_LINE_BYTES = 2_000_000


@dataclass
class ChildResult:
    """What came back from one worker."""

    events: list[dict[str, Any]] = field(default_factory=list)
    timed_out: bool = False
    returncode: int | None = None
    overflow: bool = False
    done: bool = False
    seconds: float = 0.0
    #: the first bytes the process wrote to its stderr (the worker silences it before any student
    #: code runs, so this is bubblewrap's or Python's own complaint when the worker could not start)
    stderr: bytes = b""
    #: lines the worker never writes (not a JSON object of an event kind it sends): the student's code
    #: wrote to the result pipe, so the events cannot be trusted (:func:`.events.apply` fails the notebook)
    foreign: int = 0
    #: the limit the grader's monitor ended the worker on (:mod:`.monitor`), None if it did not
    stopped: Stop | None = None
    #: the notebook's CPU seconds as the monitor last read them (0.0 without a meter)
    cpu: float = 0.0
    #: the notebook's own wall-clock seconds (less its waits for a CPU others held; 0.0 without a watch)
    own: float = 0.0
    #: how many of ``calls`` were sent to the worker
    sent: int = 0
    #: what the grader says about this run beyond the events (a call it had to end, :mod:`.notebook_run`)
    notes: list[str] = field(default_factory=list)


#: The kinds of event the worker sends (:mod:`.worker`).
KINDS = frozenset({"ready", "malformed", "cell", "cells", "call", "done"})


class _Lines:
    """Splits the worker's output into JSON events, within the caps."""

    def __init__(self, result: ChildResult) -> None:
        self.result, self.buffer, self.total = result, bytearray(), 0

    def feed(self, chunk: bytes) -> None:
        self.total += len(chunk)
        if self.total > MAX_OUTPUT_BYTES:
            self.result.overflow = True
            return
        self.buffer += chunk
        while True:
            end = self.buffer.find(b"\n")
            if end < 0:
                if len(self.buffer) > MAX_LINE_BYTES:
                    self.result.overflow = True
                return
            line = bytes(self.buffer[:end])
            del self.buffer[: end + 1]
            try:
                event = json.loads(line)
            except (ValueError, RecursionError):
                event = None
            if not isinstance(event, dict) or event.get("kind") not in KINDS:
                self.result.foreign += 1
            else:
                self.result.events.append(event)
                if event.get("kind") == "done":
                    self.result.done = True
                    return


def _kill(proc: subprocess.Popen[bytes]) -> None:
    try:
        if os.name == "posix":
            os.killpg(proc.pid, signal.SIGKILL)
        else:  # pragma: no cover - Windows
            proc.kill()
    except (ProcessLookupError, PermissionError, OSError):
        pass
    try:
        proc.wait(timeout=10)
    except subprocess.TimeoutExpired:  # pragma: no cover - a process stuck in the kernel
        pass


def run(
    cmd: Sequence[str],
    payload: bytes,
    *,
    cwd: str | None,
    env: dict[str, str],
    timeout: float,
    pass_fds: Sequence[int] = (),
    calls: Sequence[bytes] = (),
    watch: Watch | None = None,
) -> ChildResult:
    """Run ``cmd`` with ``payload`` on its stdin for at most ``timeout`` seconds; collect its events.

    ``pass_fds`` are descriptors the process inherits (bubblewrap's ``--args`` file); ``calls`` the worker's
    calls, each a JSON object ``{"qid", "case", ...}`` on one line, handed over one at a time; ``watch`` the
    limits the grader keeps (:mod:`.monitor`).
    """
    start = time.monotonic()
    result = ChildResult()
    proc = subprocess.Popen(
        list(cmd),
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE if os.name == "posix" else subprocess.DEVNULL,
        cwd=cwd,
        env=env,
        start_new_session=os.name == "posix",
        close_fds=True,
        pass_fds=tuple(pass_fds),
    )
    try:
        if os.name == "posix":
            _loop(proc, payload, result, start + timeout, list(calls), watch)
        else:  # pragma: no cover - Windows: no selectors on pipes; only `puma-course check` runs here
            _communicate(proc, payload + b"".join(calls), result, timeout)  # the calls at once: no monitor
    finally:
        _kill(proc)
        for stream in (proc.stdin, proc.stdout, proc.stderr):
            try:
                if stream is not None:
                    stream.close()
            except OSError:
                pass
    result.returncode = proc.returncode
    if watch is not None:
        result.cpu, result.own = watch.used, watch.own
    result.seconds = time.monotonic() - start
    return result


def _loop(
    proc: subprocess.Popen[bytes],
    payload: bytes,
    result: ChildResult,
    deadline: float,
    calls: list[bytes],
    watch: Watch | None,
) -> None:
    assert proc.stdin is not None and proc.stdout is not None and proc.stderr is not None
    out_fd, in_fd, err_fd = proc.stdout.fileno(), proc.stdin.fileno(), proc.stderr.fileno()
    for fd in (out_fd, in_fd, err_fd):
        os.set_blocking(fd, False)
    lines = _Lines(result)
    sel = selectors.DefaultSelector()
    sel.register(out_fd, selectors.EVENT_READ, "out")
    sel.register(err_fd, selectors.EVENT_READ, "err")
    feed = _Feed(proc, sel, payload, calls, watch)
    pidfd = -1
    try:
        pidfd = os.pidfd_open(proc.pid)  # type: ignore[attr-defined,unused-ignore]
        sel.register(pidfd, selectors.EVENT_READ, "exit")
    except (AttributeError, OSError):
        pass
    if watch is not None:
        watch.begin(time.monotonic(), proc.pid)
    exited = eof = False
    try:
        while not (result.done or result.overflow or eof or exited):
            now = time.monotonic()
            remaining = deadline - now
            if remaining <= 0:
                result.timed_out = True
                return
            if watch is not None:
                result.stopped = watch.check(now)
                if result.stopped is not None:
                    result.timed_out = result.stopped.what == "notebook"
                    return
            wait = remaining if pidfd >= 0 else min(remaining, 0.02)
            before = watch.grader_delay() if watch is not None else 0.0
            ready = sel.select(min(wait, TICK) if watch is not None else wait)
            feed.woke = watch.grader_delay() - before if watch is not None else 0.0  # waited for a CPU to read
            for key, _ in ready:
                if key.data == "in":
                    feed.write()
                elif key.data == "out":
                    seen = len(result.events)
                    eof = _read_some(out_fd, lines) == "eof"
                    for event in result.events[seen:]:
                        feed.event(event)
                elif key.data == "err":
                    try:
                        chunk = os.read(err_fd, 4096)
                    except OSError:
                        chunk = b""
                    if chunk:
                        result.stderr = (result.stderr + chunk)[:4096]
                    else:
                        sel.unregister(err_fd)
                else:
                    exited = True
            if pidfd < 0 and proc.poll() is not None:
                exited = True
        if exited and not (result.done or result.overflow):
            while _read_some(out_fd, lines) == "data" and not (result.done or result.overflow):
                pass  # what the worker wrote before it exited is in the pipe already
    finally:
        result.sent = feed.index
        if watch is not None:
            watch.close()
        sel.close()
        if pidfd >= 0:
            os.close(pidfd)


class _Feed:
    """The worker's stdin: the payload, then each call once the one before it is answered (module docstring)."""

    def __init__(
        self,
        proc: subprocess.Popen[bytes],
        sel: selectors.BaseSelector,
        payload: bytes,
        calls: list[bytes],
        watch: Watch | None,
    ) -> None:
        self.proc, self.sel, self.calls, self.watch = proc, sel, calls, watch
        assert proc.stdin is not None
        self.fd = proc.stdin.fileno()
        self.view = memoryview(payload)
        self.index = 0  # calls sent so far
        self.waiting: tuple[Any, Any] | None = None  # (qid, case) of the call sent and not yet answered
        self.keys = []
        for line in calls:
            job = json.loads(line)
            self.keys.append((job.get("qid"), job.get("case")))
        self.registered = False
        self.started = False
        self.woke = 0.0  # how long the loop, once woken, waited for a CPU before it read what came (the watch's)
        self._arm()

    def _arm(self) -> None:
        if self.view and not self.registered:
            self.sel.register(self.fd, selectors.EVENT_WRITE, "in")
            self.registered = True
        elif not self.view and self.index >= len(self.calls) and self.waiting is None:
            self.close()

    def close(self) -> None:
        if self.registered:
            self.sel.unregister(self.fd)
            self.registered = False
        assert self.proc.stdin is not None
        if not self.proc.stdin.closed:
            try:
                self.proc.stdin.close()
            except OSError:
                pass

    def write(self) -> None:
        try:
            self.view = self.view[os.write(self.fd, self.view[:65536]) :]
        except BlockingIOError:
            return
        except OSError:  # the worker closed its stdin or died
            self.view = self.view[:0]
            self.calls = self.calls[: self.index]
            self.waiting = None
        if not self.view:
            self.sel.unregister(self.fd)
            self.registered = False
            self._arm()

    def _send_next(self) -> None:
        if self.index < len(self.calls) and self.proc.stdin is not None and not self.proc.stdin.closed:
            self.view = memoryview(bytes(self.view) + self.calls[self.index])
            self.waiting = self.keys[self.index]
            if self.watch is not None:
                self.watch.sent(self.index, time.monotonic())
            self.index += 1
        else:
            self.waiting = None
        self._arm()

    def event(self, event: dict[str, Any]) -> None:
        kind = event.get("kind")
        if self.watch is not None:
            self.watch.event(str(kind), time.monotonic())
        if kind == "cells" and not self.started:
            self.started = True
            self._send_next()
        elif kind == "call" and self.waiting is not None and (event.get("qid"), event.get("case")) == self.waiting:
            if self.watch is not None:
                self.watch.answered(self.woke, time.monotonic())
                self.woke = 0.0  # once per wake: one answer only
            self._send_next()


def _read_some(fd: int, lines: _Lines) -> str:
    """Read what is there (at most 1 MB): "data", "empty" (nothing waiting) or "eof"."""
    try:
        chunk = os.read(fd, 1 << 20)
    except BlockingIOError:
        return "empty"
    except OSError:
        return "eof"
    if not chunk:
        return "eof"
    lines.feed(chunk)
    return "data"


def _communicate(
    proc: subprocess.Popen[bytes], payload: bytes, result: ChildResult, timeout: float
) -> None:  # pragma: no cover - Windows
    try:
        out, _ = proc.communicate(payload, timeout=timeout)
    except subprocess.TimeoutExpired:
        result.timed_out = True
        return
    lines = _Lines(result)
    lines.feed(out[:MAX_OUTPUT_BYTES])
