"""The child side of grading: run one student's code cells, call their functions, report plain data.

This module runs in a fresh ``python -I`` process started by
:func:`puma_course.grading.grade`, with a temporary working directory. It reads one
JSON job from stdin::

    {"cells": [source, ...], "calls": [{"qid", "case", "function", "args"}, ...],
     "timeout_cell": seconds, "max_size": n}

executes the cells in order in one namespace (a cell that raises or runs past
``timeout_cell`` is recorded and the next cell still runs), then calls each
requested function on the grader's inputs and streams JSON lines back on the
original stdout, one event per line::

    {"kind": "cell", "index": i, "status": "ok" | "error" | "timeout", "error": "..."}
    {"kind": "call", "qid": "q1", "case": 0, "value": [...]}   or  "error": "..."
    {"kind": "done", "printed": n_chars}

Only numbers travel back (``np.asarray(value, float).tolist()``, at most
``max_size`` of them); the grader compares them with the package's reference in
its own process, so nothing the student's code does here can change how values
are judged. The student's prints go to a small capped buffer, and the OS-level
stdout/stderr are pointed at /dev/null so that a flood of output costs nothing.

Nothing runs at import time; the grader starts :func:`main`.
"""

from __future__ import annotations

import json
import os
import signal
import sys
import traceback
from typing import Any

__all__ = ["main", "strip_magics"]


class CellTimeout(BaseException):
    """Raised by the alarm when a cell or a call runs past its time limit."""


def strip_magics(source: str) -> str:
    """Comment out IPython-only lines (``%magic``, ``!shell``) so plain Python can run a cell.

    >>> strip_magics("%matplotlib inline\\nx = 1")
    '# %matplotlib inline\\nx = 1'
    """
    out = []
    for line in source.splitlines():
        stripped = line.lstrip()
        if stripped.startswith(("%", "!")):
            indent = line[: len(line) - len(stripped)]
            out.append(f"{indent}# {stripped}")
        else:
            out.append(line)
    return "\n".join(out)


class _CappedWriter:
    """A text sink that keeps the first ``cap`` characters and counts the rest."""

    def __init__(self, cap: int = 4000) -> None:
        self.cap = cap
        self.kept: list[str] = []
        self.size = 0

    def write(self, text: Any) -> int:
        text = str(text)
        if self.size < self.cap:
            self.kept.append(text[: self.cap - self.size])
        self.size += len(text)
        return len(text)

    def flush(self) -> None:
        pass

    def isatty(self) -> bool:
        return False


def _short_error(exc: BaseException, filename_prefix: str = "<cell") -> str:
    """One line naming the exception and, if possible, the student's cell and line."""
    where = ""
    for frame in reversed(traceback.extract_tb(exc.__traceback__)):
        if frame.filename.startswith(filename_prefix):
            where = f" ({frame.filename.strip('<>')}, line {frame.lineno})"
            break
    msg = str(exc).strip().splitlines()[0] if str(exc).strip() else ""
    return f"{type(exc).__name__}: {msg}"[:300] + where


def main() -> None:
    """Run one job read from stdin (see the module docstring)."""
    # Keep private references before any student code can monkeypatch them.
    dumps = json.dumps
    write = os.write
    job = json.loads(sys.stdin.read())
    out_fd = os.dup(1)
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)
    os.dup2(devnull, 2)
    sink = _CappedWriter()
    sys.stdout = sys.stderr = sink  # type: ignore[assignment]

    import numpy as np

    asarray, isfinite_dtype = np.asarray, float
    setitimer, ITIMER_REAL = signal.setitimer, signal.ITIMER_REAL

    def emit(event: dict[str, Any]) -> None:
        data = (dumps(event) + "\n").encode()
        view = memoryview(data)
        while view:
            n = write(out_fd, view)
            view = view[n:]

    def on_alarm(signum: int, frame: Any) -> None:
        raise CellTimeout()

    timeout = float(job.get("timeout_cell", 10.0))
    max_size = int(job.get("max_size", 10_000))

    def run_timed(fn: Any, *args: Any) -> Any:
        signal.signal(signal.SIGALRM, on_alarm)
        setitimer(ITIMER_REAL, timeout)
        try:
            return fn(*args)
        finally:
            setitimer(ITIMER_REAL, 0)

    def display(*objs: Any, **kwargs: Any) -> None:  # IPython's display() for plain Python
        for obj in objs:
            print(repr(obj))

    ns: dict[str, Any] = {"__name__": "__main__", "display": display}
    for index, source in enumerate(job["cells"]):
        try:
            code = compile(strip_magics(source), f"<cell {index + 1}>", "exec")
            run_timed(exec, code, ns)
            event = {"kind": "cell", "index": index, "status": "ok"}
        except CellTimeout:
            event = {"kind": "cell", "index": index, "status": "timeout", "error": f"ran longer than {timeout:g} s"}
        except BaseException as exc:  # noqa: BLE001 - SystemExit, KeyboardInterrupt: all are the student's
            event = {"kind": "cell", "index": index, "status": "error", "error": _short_error(exc)}
        emit(event)

    for call in job["calls"]:
        event = {"kind": "call", "qid": call["qid"], "case": call["case"]}
        fn = ns.get(call["function"])
        if fn is None:
            event["error"] = f"no function named {call['function']}() was defined"
        elif not callable(fn):
            event["error"] = f"{call['function']} is a {type(fn).__name__}, not a function"
        else:
            args = [asarray(a, dtype=isfinite_dtype) if isinstance(a, list) else a for a in call["args"]]
            try:
                value = run_timed(fn, *args)
            except CellTimeout:
                event["error"] = f"the call ran longer than {timeout:g} s"
            except NotImplementedError:
                event["error"] = "not attempted yet (NotImplementedError)"
            except BaseException as exc:  # noqa: BLE001
                event["error"] = _short_error(exc)
            else:
                try:
                    arr = asarray(value, dtype=isfinite_dtype)
                except BaseException as exc:  # noqa: BLE001
                    kind = type(value).__name__
                    event["error"] = f"returned a {kind}, which is not an array of numbers ({str(exc)[:120]})"
                else:
                    if arr.size > max_size:
                        event["error"] = f"returned {arr.size} numbers, more than the {max_size} allowed"
                    else:
                        event["value"] = arr.tolist()
        emit(event)
    emit({"kind": "done", "printed": sink.size})


if __name__ == "__main__":  # pragma: no cover - started by the grader
    main()
