"""The worker's guards: resource limits, the answer-key tripwire, safe descriptions of the student's errors.

Everything here runs in the student's process, before or around the student's code, and needs
the standard library only.
"""

from __future__ import annotations

import sys
import traceback
from typing import Any

# Private references taken when the worker starts, before any student code runs: a cell that
# replaces ``sys.setprofile`` does not change what the guard calls.
_setprofile, _getprofile, _getframe = sys.setprofile, sys.getprofile, sys._getframe

#: Prefix of a guard hit that is not an answer-key call but the student switching the guard off.
TAMPER = "tamper:"


def _watch_breakers() -> tuple[dict[Any, str], dict[Any, str]]:
    """(builtins, Python code objects) whose call during a guarded question switches the profile off or escapes it.

    ``sys.setprofile`` / ``sys.settrace`` (and their all-threads forms), ``threading.setprofile`` /
    ``settrace`` and starting a thread (a new thread runs without the profile).
    """
    import _thread
    import threading

    builtins: dict[Any, str] = {}
    for owner, names in (
        (sys, ("setprofile", "settrace", "_setprofileallthreads", "_settraceallthreads")),
        (_thread, ("start_new_thread", "start_new", "start_joinable_thread")),
    ):
        for name in names:
            fn = getattr(owner, name, None)
            if fn is not None:
                builtins[fn] = f"{getattr(owner, '__name__', '')}.{name}"
    codes: dict[Any, str] = {}
    for name in ("setprofile", "settrace", "setprofile_all_threads", "settrace_all_threads"):
        code = getattr(getattr(threading, name, None), "__code__", None)
        if code is not None:
            codes[code] = f"threading.{name}"
    start = getattr(getattr(threading.Thread, "start", None), "__code__", None)
    if start is not None:
        codes[start] = "threading.Thread.start"
    return builtins, codes


_BREAKERS, _BREAKER_CODES = _watch_breakers()

__all__ = [
    "CappedWriter",
    "type_name",
    "describe",
    "resolve",
    "forbidden_codes",
    "guarded_call",
    "TAMPER",
    "install_tripwires",
    "limit_resources",
]


class CappedWriter:
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


def type_name(obj: Any) -> str:
    """The name of ``obj``'s type, read past any metaclass property (no student code runs).

    >>> type_name(1.5)
    'float'
    """
    return str(type.__dict__["__name__"].__get__(type(obj), type))


def describe(exc: BaseException) -> tuple[str, int]:
    """The exception's type and first line of message (the student's text, quoted by the grader) and its cell line."""
    line = 0
    try:
        for frame in reversed(traceback.extract_tb(exc.__traceback__)):
            if frame.filename.startswith("<cell"):
                line = int(frame.lineno or 0)
                break
        text = str(exc).strip()
    except BaseException:  # noqa: BLE001 - a hostile __str__ or traceback must not stop the worker
        text = "(the error message could not be read)"
    first = text.splitlines()[0].strip() if text else ""
    return (f"{type_name(exc)}: {first}" if first else type_name(exc))[:2000], line


def resolve(spec: str) -> Any:
    """The object named by ``"module:attr[.attr]"`` (None if it does not exist or cannot be imported).

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


#: Bytecode shorter than this (a line or two) is too common to call a copy of anything.
SHORTEST_COPY = 24


def fingerprint(code: Any) -> tuple[Any, ...] | None:
    """What a copy of a function's compiled code keeps however it was rebuilt: its bytecode and the names it uses.

    Line numbers, file name, function name and text constants (docstring, messages) are left out
    (``code.replace(co_firstlineno=...)``, ``types.FunctionType(code, ...)`` or the source pasted into a cell
    give the same fingerprint); local names and number constants are kept, and code shorter than
    :data:`SHORTEST_COPY` bytes has no fingerprint (None), so that code written independently does not match
    by chance.

    >>> def f(x, y):
    ...     return 2.5 * x + y ** 3 - x * y
    >>> fingerprint(f.__code__) == fingerprint(f.__code__.replace(co_firstlineno=99, co_name="g"))
    True
    >>> fingerprint((lambda x: 2 * x).__code__) is None
    True
    """
    raw = code.co_code
    if len(raw) < SHORTEST_COPY:
        return None
    nested = tuple(fingerprint(c) if type(c) is type(code) else c for c in code.co_consts if type(c) is not str)
    shape = (code.co_argcount, code.co_posonlyargcount, code.co_kwonlyargcount)
    return ("fingerprint", raw, code.co_names, code.co_varnames, shape, nested)


def forbidden_codes(specs: Any) -> dict[Any, str]:
    """Map what :func:`guarded_call` watches for the named functions to their names.

    A Python function (unwrapped) gives its code object and its :func:`fingerprint`; a function written in C
    (``builtin_function_or_method``, e.g. ``numpy.linalg.lapack_lite.dgelsd``) its module and name. Anything else
    (a numpy ufunc such as ``numpy.linalg._umath_linalg.inv``) no profile can see being called:
    :func:`install_tripwires` replaces it where the student can reach it.
    """
    codes: dict[Any, str] = {}
    for spec in specs:
        obj = resolve(spec)
        while obj is not None and hasattr(obj, "__wrapped__"):
            obj = obj.__wrapped__
        code = getattr(obj, "__code__", None)
        if code is not None and type(code) is type(_watch_breakers.__code__):
            codes[code] = spec
            mark = fingerprint(code)
            if mark is not None:
                codes[mark] = spec
        elif type(obj) is type(len):
            codes[_compiled(obj)] = spec  # by name: the function itself is kept out of sight
    return codes


def _compiled(fn: Any) -> tuple[str, Any, Any]:
    """How a function written in C is known to the profile: its module and name (read in C: no student code runs)."""
    return ("compiled", getattr(fn, "__module__", None), getattr(fn, "__name__", None))


def guarded_call(fn: Any, args: Any, codes: dict[Any, str]) -> tuple[Any, str | None]:
    """Call ``fn(*args)``; also return the first forbidden function (by code object) it called, if any.

    Uses ``sys.setprofile``, so it sees calls however the function got hold of them
    (``from puma_course import rodrigues``, a wrapper's ``__wrapped__``, an object found through ``gc``).
    Switching the profile off (``sys.setprofile(None)``, ``sys.settrace``, ``threading.setprofile``),
    starting a thread (which would run without it) or leaving another profile in place counts as a hit
    too, reported as :data:`TAMPER` followed by what was called: the profile sees that call before it runs.

    >>> import numpy as np
    >>> from puma_course.transforms import rotx
    >>> guarded_call(lambda t: rotx(t), (0.1,), forbidden_codes(["puma_course.transforms:rotx"]))[1]
    'puma_course.transforms:rotx'
    """
    if not codes:
        return fn(*args), None
    hit: list[str] = []

    breakers, breaker_codes = _BREAKERS, _BREAKER_CODES
    own = _getframe().f_code  # this function's own calls (putting the old profile back) are not the student's

    builtin = type(len)
    by_name = any(type(key) is tuple and key[0] == "compiled" for key in codes)
    seen: dict[int, tuple[Any, str | None]] = {}  # id(code) -> (code, what it is a copy of): each code read once

    def copied(code: Any) -> str | None:
        known = seen.get(id(code))
        if known is None or known[0] is not code:
            mark = fingerprint(code)
            known = seen[id(code)] = (code, None if mark is None else codes.get(mark))
        return known[1]

    def profile(frame: Any, event: str, arg: Any) -> None:
        if hit:
            return
        if event == "call":
            code = frame.f_code
            if code in codes:
                hit.append(codes[code])
            elif code in breaker_codes:
                hit.append(TAMPER + breaker_codes[code])
            else:
                name = copied(code)
                if name is not None:
                    hit.append(name)
        elif event == "c_call" and frame.f_code is not own:
            try:
                name = breakers.get(arg)
            except TypeError:  # an unhashable callable
                name = None
            key = codes.get(_compiled(arg)) if by_name and type(arg) is builtin else None
            if name is not None:
                hit.append(TAMPER + name)
            elif key is not None:
                hit.append(key)

    old = _getprofile()
    _setprofile(profile)
    try:
        value = fn(*args)
    finally:
        still = _getprofile() is profile
        _setprofile(old)
    if not still and not hit:
        hit.append(TAMPER + "sys.setprofile")
    return value, (hit[0] if hit else None)


def _out_of_sight(original: Any) -> tuple[int, Any, Any]:
    """(address, cast, py_object): enough for a wrapper to call ``original`` while holding no reference to it.

    A numpy ufunc (``numpy.linalg._umath_linalg.inv``), or a C function called from other compiled code
    (``functools.partial``, ``map``), is called without any event a profile could see, so the wrapper that
    replaces it must be the only way to it: one reference is leaked on purpose (the original lives as long as
    the process), the original is taken off ``gc``'s lists, and the wrapper keeps its address, which only
    ``ctypes`` turns back into the object. Neither the wrapper's closure nor ``gc`` leads to the original.
    Without ``ctypes`` the wrapper keeps the object itself.
    """
    try:
        import ctypes
        import gc

        ctypes.pythonapi.Py_IncRef(ctypes.py_object(original))
        if gc.is_tracked(original):  # a function written in C is listed by gc.get_objects(): no longer
            untrack = ctypes.pythonapi.PyObject_GC_UnTrack
            untrack.argtypes, untrack.restype = [ctypes.py_object], None
            untrack(original)
        return id(original), ctypes.cast, ctypes.py_object
    except (ImportError, AttributeError, OSError):  # pragma: no cover - a Python without ctypes
        return 0, original, None


def install_tripwires(specs: set[str], state: dict[str, Any]) -> None:
    """Wrap each ``module:attr[.attr]`` so that calls during a guarded question are recorded in ``state``.

    The wrapper keeps the original's name and docstring but not a ``__wrapped__`` reference to it; the
    profile of :func:`guarded_call` (by code object or copy of it) is what catches a call that reaches a
    Python original anyway. An original no profile sees (a numpy ufunc) is replaced wherever a module of its
    package holds it (``np.linalg._umath_linalg.inv`` is ``sys.modules["numpy.linalg._umath_linalg"].inv``),
    and its wrapper holds it out of sight (:func:`_out_of_sight`).
    """
    import importlib

    function = type(install_tripwires)
    for spec in sorted(specs):
        modname, _, path = spec.partition(":")
        try:
            owner: Any = importlib.import_module(modname)
            parts = path.split(".")
            for part in parts[:-1]:
                owner = getattr(owner, part)
            original = getattr(owner, parts[-1])
        except (ImportError, AttributeError):
            continue  # not in the student side: nothing to guard
        hidden = type(original) is not function and callable(original) and not isinstance(original, type)

        def make(original: Any, spec: str, hidden: bool) -> Any:
            if hidden:
                address, cast, py_object = _out_of_sight(original)
                original = None

                def wrapper(*args: Any, **kwargs: Any) -> Any:
                    if spec in state["guard"] and state["hit"] is None:
                        state["hit"] = spec
                    target = cast(address, py_object).value if py_object is not None else cast
                    return target(*args, **kwargs)

            else:

                def wrapper(*args: Any, **kwargs: Any) -> Any:
                    if spec in state["guard"] and state["hit"] is None:
                        state["hit"] = spec
                    return original(*args, **kwargs)

            return wrapper

        wrapped = make(original, spec, hidden)
        for attr in ("__module__", "__name__", "__qualname__", "__doc__"):
            try:
                setattr(wrapped, attr, getattr(original, attr))
            except (AttributeError, TypeError):
                pass
        setattr(owner, parts[-1], wrapped)
        if len(parts) == 1:  # re-exports (puma_course.rodrigues) and other holders in the package (numpy's modules)
            top = modname.split(".")[0]
            for mod in list(sys.modules.values()):
                name = getattr(mod, "__name__", "") or ""
                if name.split(".")[0] == top:
                    for key, value in list(getattr(mod, "__dict__", {}).items()):
                        if value is original:
                            setattr(mod, key, wrapped)
        del original


def limit_resources(limits: dict[str, Any] | None = None) -> None:
    """Cap this process (POSIX; no-op elsewhere): address space, file size, open files, CPU seconds, processes, no core.

    ``limits`` may give ``memory``, ``file_size``, ``open_files``, ``cpu_seconds`` and ``processes``
    (0 or absent: that limit is left as it is, except memory 4 GiB and file size 200 MiB).
    """
    limits = limits or {}
    try:
        import resource
    except ImportError:  # pragma: no cover - Windows
        return
    wanted = [
        (resource.RLIMIT_AS, int(limits.get("memory", 4 << 30))),
        (resource.RLIMIT_FSIZE, int(limits.get("file_size", 200 << 20))),
        (resource.RLIMIT_CORE, 0),
        (resource.RLIMIT_NOFILE, int(limits.get("open_files", 0))),
        (resource.RLIMIT_CPU, int(limits.get("cpu_seconds", 0))),
        (getattr(resource, "RLIMIT_NPROC", -1), int(limits.get("processes", 0))),
    ]
    for kind, value in wanted:
        if kind < 0 or (value <= 0 and kind != resource.RLIMIT_CORE):
            continue
        try:
            soft, hard = resource.getrlimit(kind)
            unlimited = hard == resource.RLIM_INFINITY
            cap = value if unlimited else min(value, hard)
            # CPU: the soft limit sends SIGXCPU, the hard one SIGKILL a little later
            top = (cap + 5 if unlimited else min(cap + 5, hard)) if kind == resource.RLIMIT_CPU else cap
            resource.setrlimit(kind, (cap, top))
        except (ValueError, OSError):
            pass
