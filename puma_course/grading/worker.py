"""The child side of grading: run one student's code cells, call their functions, report plain data.

This module runs in a fresh ``python -I`` process started by
:mod:`puma_course.grading.runner` (:func:`~puma_course.grading.grade`), with a temporary
working directory. It needs the standard library only (numpy once student code runs). It reads one
JSON job from stdin::

    {"cells": [source, ...], "calls": [{"qid", "case", "function", "args"}, ...],
     "timeout_cell": seconds, "max_size": n, "forbidden": {qid: ["module:attr", ...]}}

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

"Forbidden" package functions (the answer key of a question, e.g.
``puma_course.transforms:rodrigues`` for "write Rodrigues' formula") are wrapped
before any student code runs; a call to one of them *while that question's
function is being graded* makes the case fail with a clear reason.

Nothing runs at import time; the grader starts :func:`main`.
"""

from __future__ import annotations

import json
import os
import signal
import sys
import traceback
from typing import Any

__all__ = ["main", "strip_magics", "resolve", "forbidden_codes", "guarded_call", "NOT_ATTEMPTED"]

#: The reason given for a case whose function still raises NotImplementedError (the released stub).
NOT_ATTEMPTED = "not attempted yet"


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


def resolve(spec: str) -> Any:
    """The object named by ``"module:attr[.attr]"`` (None if it does not exist).

    >>> resolve("puma_course.transforms:rotx").__name__
    'rotx'
    """
    import importlib

    modname, _, path = spec.partition(":")
    try:
        obj: Any = importlib.import_module(modname)
        for part in path.split("."):
            obj = getattr(obj, part)
    except (ImportError, AttributeError):
        return None
    return obj


def forbidden_codes(specs: Any) -> dict[Any, str]:
    """Map the code objects of the named functions (unwrapped) to their names, for :func:`guarded_call`."""
    codes = {}
    for spec in specs:
        obj = resolve(spec)
        while obj is not None and hasattr(obj, "__wrapped__"):
            obj = obj.__wrapped__
        code = getattr(obj, "__code__", None)
        if code is not None:
            codes[code] = spec
    return codes


def guarded_call(fn: Any, args: Any, codes: dict[Any, str]) -> tuple[Any, str | None]:
    """Call ``fn(*args)``; also return the first forbidden function (by code object) it called, if any.

    Uses ``sys.setprofile``, so it sees calls however the function got hold of them
    (``from puma_course import rodrigues`` included).

    >>> import numpy as np
    >>> from puma_course.transforms import rotx
    >>> guarded_call(lambda t: rotx(t), (0.1,), forbidden_codes(["puma_course.transforms:rotx"]))[1]
    'puma_course.transforms:rotx'
    """
    if not codes:
        return fn(*args), None
    hit: list[str] = []

    def profile(frame: Any, event: str, arg: Any) -> None:
        if event == "call" and not hit and frame.f_code in codes:
            hit.append(codes[frame.f_code])

    old = sys.getprofile()
    sys.setprofile(profile)
    try:
        value = fn(*args)
    finally:
        sys.setprofile(old)
    return value, (hit[0] if hit else None)


def _install_tripwires(specs: set[str], state: dict[str, Any]) -> None:
    """Wrap each ``module:attr[.attr]`` so that calls during a guarded question are recorded in ``state``."""
    import functools
    import importlib

    for spec in sorted(specs):
        modname, _, path = spec.partition(":")
        try:
            owner: Any = importlib.import_module(modname)
            parts = path.split(".")
            for part in parts[:-1]:
                owner = getattr(owner, part)
            original = getattr(owner, parts[-1])
        except (ImportError, AttributeError):
            continue

        def make(original: Any, spec: str) -> Any:
            @functools.wraps(original)
            def wrapper(*args: Any, **kwargs: Any) -> Any:
                if spec in state["guard"] and state["hit"] is None:
                    state["hit"] = spec
                return original(*args, **kwargs)

            return wrapper

        wrapped = make(original, spec)
        setattr(owner, parts[-1], wrapped)
        if len(parts) == 1:  # re-exports such as puma_course.rodrigues
            for mod in list(sys.modules.values()):
                name = getattr(mod, "__name__", "") or ""
                if name.split(".")[0] == "puma_course" and getattr(mod, parts[-1], None) is original:
                    setattr(mod, parts[-1], wrapped)


def limit_resources(memory_bytes: int = 4 << 30, file_bytes: int = 200 << 20) -> None:
    """Cap this process's address space and file sizes and disable core dumps (POSIX; no-op elsewhere)."""
    try:
        import resource

        resource.setrlimit(resource.RLIMIT_AS, (memory_bytes, memory_bytes))
        resource.setrlimit(resource.RLIMIT_FSIZE, (file_bytes, file_bytes))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    except (ImportError, ValueError, OSError):
        pass


def main() -> None:
    """Run one job read from stdin (see the module docstring)."""
    limit_resources()
    # Keep private references before any student code can monkeypatch them.
    dumps = json.dumps
    write = os.write
    job = json.loads(sys.stdin.read())
    out_fd = os.dup(1)
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)
    os.dup2(devnull, 2)
    sink = _CappedWriter()
    sys.stdout = sys.stderr = sink

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

    forbidden = {qid: set(specs) for qid, specs in job.get("forbidden", {}).items()}
    state: dict[str, Any] = {"guard": set(), "hit": None}
    _install_tripwires(set().union(*forbidden.values()) if forbidden else set(), state)
    codes = {qid: forbidden_codes(specs) for qid, specs in forbidden.items()}

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

    slow: set[str] = set()  # questions whose function already ran out of time: skip their other cases
    for call in job["calls"]:
        event = {"kind": "call", "qid": call["qid"], "case": call["case"]}
        fn = ns.get(call["function"])
        if call["qid"] in slow:
            event["error"] = "skipped: an earlier case of this question ran out of time"
        elif fn is None:
            event["error"] = f"no function named {call['function']}() was defined"
        elif not callable(fn):
            event["error"] = f"{call['function']} is a {type(fn).__name__}, not a function"
        else:
            args = [asarray(a, dtype=isfinite_dtype) if isinstance(a, list) else a for a in call["args"]]
            state["guard"], state["hit"] = forbidden.get(call["qid"], set()), None
            try:
                value, hit = run_timed(guarded_call, fn, args, codes.get(call["qid"], {}))
                if hit is not None and state["hit"] is None:
                    state["hit"] = hit
            except CellTimeout:
                event["error"] = f"the call ran longer than {timeout:g} s"
                slow.add(call["qid"])
            except NotImplementedError:
                event["error"] = f"{NOT_ATTEMPTED} (NotImplementedError)"
            except BaseException as exc:  # noqa: BLE001
                event["error"] = _short_error(exc)
            else:

                def to_floats(value: Any) -> Any:
                    raw = asarray(value)
                    if raw.dtype.kind == "c":
                        raise TypeError("complex numbers are not accepted")
                    return asarray(raw, dtype=isfinite_dtype)

                try:
                    arr = run_timed(to_floats, value)  # a hostile __array__ must not escape the time limit
                except CellTimeout:
                    event["error"] = f"converting the returned value to numbers took longer than {timeout:g} s"
                    slow.add(call["qid"])
                except BaseException as exc:  # noqa: BLE001
                    kind = type(value).__name__
                    event["error"] = f"returned a {kind}, which is not an array of numbers ({str(exc)[:120]})"
                else:
                    if state["hit"] is not None:
                        event["error"] = (
                            f"used the course package's answer ({state['hit'].replace(':', '.')}) "
                            "instead of your own code"
                        )
                    elif arr.size > max_size:
                        event["error"] = f"returned {arr.size} numbers, more than the {max_size} allowed"
                    else:
                        event["value"] = arr.tolist()
            state["guard"] = set()
        emit(event)
    emit({"kind": "done", "printed": sink.size})


if __name__ == "__main__":  # pragma: no cover - started by the grader
    main()
