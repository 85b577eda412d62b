"""Running one worker process: feed it, read its events, and stop it on time, whatever it does.

:func:`run` starts the command in its own session, writes the payload to its standard input and
reads JSON lines from its standard output in one loop (non-blocking pipes and a selector; on
Linux a pidfd wakes the loop the moment the process exits), so there is no fixed wait anywhere:

* it stops reading as soon as the worker's last event (``{"kind": "done"}``) arrives, or when the
  process has exited and the pipe holds nothing more, even if a grandchild still holds the pipe
  open; whatever runs at the process's exit (``atexit``, threads, ``__del__``) costs nothing;
* at the deadline, or when the output passes its cap, it stops the process;
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


#: The kinds of event the worker sends (:mod:`.worker`).
KINDS = frozenset({"ready", "malformed", "cell", "call", "done"})


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
) -> ChildResult:
    """Run ``cmd`` with ``payload`` on its stdin for at most ``timeout`` seconds; collect its events.

    ``pass_fds`` are descriptors the process inherits (bubblewrap's ``--args`` file).
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
            _loop(proc, payload, result, start + timeout)
        else:  # pragma: no cover - Windows: no selectors on pipes; only `puma-course check` runs here
            _communicate(proc, payload, result, timeout)
    finally:
        _kill(proc)
        for stream in (proc.stdin, proc.stdout, proc.stderr):
            try:
                if stream is not None:
                    stream.close()
            except OSError:
                pass
    result.returncode = proc.returncode
    result.seconds = time.monotonic() - start
    return result


def _loop(proc: subprocess.Popen[bytes], payload: bytes, result: ChildResult, deadline: float) -> None:
    assert proc.stdin is not None and proc.stdout is not None and proc.stderr is not None
    out_fd, in_fd, err_fd = proc.stdout.fileno(), proc.stdin.fileno(), proc.stderr.fileno()
    for fd in (out_fd, in_fd, err_fd):
        os.set_blocking(fd, False)
    lines = _Lines(result)
    sel = selectors.DefaultSelector()
    sel.register(out_fd, selectors.EVENT_READ, "out")
    sel.register(err_fd, selectors.EVENT_READ, "err")
    view = memoryview(payload)
    if view:
        sel.register(in_fd, selectors.EVENT_WRITE, "in")
    else:
        proc.stdin.close()
    pidfd = -1
    try:
        pidfd = os.pidfd_open(proc.pid)  # type: ignore[attr-defined,unused-ignore]
        sel.register(pidfd, selectors.EVENT_READ, "exit")
    except (AttributeError, OSError):
        pass
    exited = eof = False
    try:
        while not (result.done or result.overflow or eof or exited):
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                result.timed_out = True
                return
            ready = sel.select(remaining if pidfd >= 0 else min(remaining, 0.02))
            for key, _ in ready:
                if key.data == "in":
                    try:
                        view = view[os.write(in_fd, view[:65536]) :]
                    except BlockingIOError:
                        continue
                    except OSError:  # the worker closed its stdin or died
                        view = view[:0]
                    if not view:
                        sel.unregister(in_fd)
                        proc.stdin.close()
                elif key.data == "out":
                    eof = _read_some(out_fd, lines) == "eof"
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
        sel.close()
        if pidfd >= 0:
            os.close(pidfd)


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
