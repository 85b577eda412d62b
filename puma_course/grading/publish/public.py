"""The student edition's self-check: every exercise's public cases as data, without the question bank.

The instructor's course checks a student's answer against its question bank (``COURSE/bank/``),
which holds the reference answers and the hidden-case generators. A student edition
(``puma-course edition DIR``) carries none of that: :func:`public_exercise` turns each exercise into
one whose questions hold their public cases and nothing else of the key. Every function of the bank
a question needs (its reference, the mistaken formulas it recognises, the poses a modelling judge
compares with) is replaced by a :class:`Replay`: the values it gave on the public cases, recorded
when the edition was written, and nothing else. The engine's comparisons, judges and mistakes come
with the package (they pickle as their recipe, :mod:`puma_course.grading.remake`), so the edition's
``check("qN", fn)`` and ``puma-course check`` judge, diagnose and hint exactly as the instructor's do
on those cases, and ``hidden`` draws no case at all.

The data lives in the package (``grading/publish/public_data/exercises.pickle``), written only into an
edition: in the instructor's course it does not exist and :func:`exercises` raises.
"""

from __future__ import annotations

import copy
import dataclasses
import io
import pickle
import types
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import numpy as np

from ..bank_loader import BANK_MODULE
from ..judge.diagnose import Mistake
from ..judge.judges.tables import record_diagnosis, table_judge
from ..remake import Made, remake
from ..spec import Exercise, Question

__all__ = [
    "DATA_FILE",
    "Replay",
    "public_exercise",
    "public_cases_only",
    "dumps",
    "exercises",
    "available",
    "no_hidden",
]

#: The edition's self-check data (absent from the instructor's course).
DATA_FILE = Path(__file__).resolve().parent / "public_data" / "exercises.pickle"


def no_hidden(rng: np.random.Generator) -> list[tuple[Any, ...]]:
    """The hidden cases of a public question: none (the self-check runs the public cases only)."""
    return []


def public_cases_only(ex: Exercise) -> Exercise:
    """``ex`` as ``puma-course check`` grades a student's own notebook: on its public cases only.

    Only the hidden cases go (:func:`no_hidden`); every other field (the reference, the answer-key tripwires,
    the bonus flags) stays as graded, so a check passes and fails exactly as grading does on those cases.
    Unlike :func:`public_exercise`, nothing else is replaced: ``ex`` comes from a course's bank or an edition's data.
    """
    return dataclasses.replace(ex, questions=tuple(dataclasses.replace(q, hidden=no_hidden) for q in ex.questions))


def _key(value: Any) -> Any:
    """A hashable, exact key for an argument (arrays by shape and bytes).

    >>> _key((0.5, "x")) == _key((np.float64(0.5), "x")), _key(([1, 2],)) == _key((np.array([1.0, 2.0]),))
    (True, True)
    """
    if isinstance(value, str) or value is None or isinstance(value, bool):
        return ("s", repr(value))
    if isinstance(value, tuple) and not value:
        return ("t",)
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        arr = None
    if arr is not None and arr.dtype != object:
        return ("a", arr.shape, np.ascontiguousarray(arr).tobytes())
    if isinstance(value, (tuple, list)):
        return ("t", tuple(_key(v) for v in value))
    if isinstance(value, dict):
        return ("d", tuple(sorted((k, _key(v)) for k, v in value.items())))
    return ("r", repr(value))


class Replay:
    """A bank function reduced to the values it gave: called with arguments it was recorded on, it gives
    that value again; with others, it raises :class:`LookupError`.

    While recording (``fn`` given), each call computes ``fn(*args)``, keeps ``transform`` of it and
    returns that; :meth:`freeze` drops ``fn``. Only the table is pickled.

    >>> r = Replay(lambda x: 2 * x)
    >>> r(1.5), r.freeze()(1.5)
    (3.0, 3.0)
    >>> r(2.0)
    Traceback (most recent call last):
    ...
    LookupError: the self-check has no recorded value for these arguments (a public case only)
    """

    def __init__(self, fn: Callable[..., Any] | None = None, transform: Callable[[Any], Any] | None = None) -> None:
        self.fn, self.transform = fn, transform
        self.table: dict[Any, Any] = {}

    def __call__(self, *args: Any) -> Any:
        key = _key(args)
        if self.fn is not None and key not in self.table:
            value = self.fn(*copy.deepcopy(args))
            self.table[key] = self.transform(value) if self.transform is not None else value
        if key not in self.table:
            raise LookupError("the self-check has no recorded value for these arguments (a public case only)")
        return copy.deepcopy(self.table[key])

    def freeze(self) -> Replay:
        """Stop recording: from now on only the recorded values answer."""
        self.fn = self.transform = None
        return self

    def __deepcopy__(self, memo: dict[int, Any]) -> Replay:
        return self  # one table, shared by every copy of an expected value that holds it

    def __getstate__(self) -> dict[str, Any]:
        return {"table": self.table}

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.fn, self.transform, self.table = None, None, state["table"]


def _from_bank(fn: Any) -> bool:
    """Whether ``fn`` is the bank's own code (a function of the bank's modules, or made inside one)."""
    if isinstance(fn, types.MethodType):
        return _from_bank(fn.__func__) or _from_bank(fn.__self__)
    module = getattr(fn, "__module__", None) or ""
    if module == BANK_MODULE or module.startswith(BANK_MODULE + "."):
        return True
    if isinstance(fn, types.FunctionType):
        return "<locals>" in fn.__qualname__ or fn.__name__ == "<lambda>"
    return False


class _Builder:
    """Replaces every piece of bank code inside a question by a :class:`Replay` (all kept, to freeze)."""

    def __init__(self) -> None:
        self.replays: list[Replay] = []

    def replay(self, fn: Callable[..., Any], transform: Callable[[Any], Any] | None = None) -> Replay:
        r = Replay(fn, transform)
        self.replays.append(r)
        return r

    def sub(self, value: Any) -> Any:
        if isinstance(value, Made):
            return remake(
                value.factory,
                tuple(self.sub(a) for a in value.args),
                {k: self.sub(v) for k, v in value.kwargs.items()},
                value.attr,
            )
        if isinstance(value, Mistake):
            return Mistake(value.key, self.sub(value.check))
        if isinstance(value, dict):
            return {k: self.sub(v) for k, v in value.items()}
        if isinstance(value, (list, tuple)) and not isinstance(value, np.ndarray):
            return type(value)(self.sub(v) for v in value)
        if callable(value) and not isinstance(value, (type, Replay)) and _from_bank(value):
            return self.replay(value)
        return value


def _probes(q: Question, args: tuple[Any, ...]) -> list[Any]:
    """Answers the recording judges on each public case: the right one and every recognised mistake."""
    out: list[Any] = []
    try:
        right = q.right_answer(*copy.deepcopy(args))
    except Exception:  # noqa: BLE001 - a probe that cannot be made is skipped
        right = None
    if right is not None:
        out.append(right)
        try:  # the right answer turned wrong in common ways, so that each judge records what it looks up
            arr = np.asarray(right, dtype=float)
            out += [-arr, np.degrees(arr), np.swapaxes(np.atleast_2d(arr), -1, -2), np.zeros_like(arr)]
        except (TypeError, ValueError):
            pass
    for m in q.mistakes:
        check = m.check
        if isinstance(check, Made):
            for a in check.args:
                if callable(a):
                    try:
                        out.append(a(*copy.deepcopy(args)))
                    except Exception:  # noqa: BLE001
                        pass
    return out


def public_exercise(ex: Exercise) -> Exercise:
    """``ex`` reduced to its public cases, every bank function replaced by the values it gave on them."""
    questions = []
    builder = _Builder()
    for q in ex.questions:
        reference = builder.replay(q.reference, builder.sub)
        public_q = dataclasses.replace(
            q,
            hidden=no_hidden,
            reference=reference,
            compare=builder.sub(q.compare),
            mistakes=tuple(builder.sub(m) for m in q.mistakes),
            judge_with=builder.sub(q.judge_with),
            answer=None,
            forbidden=tuple(f for f in q.forbidden if not f.startswith(BANK_MODULE)),
        )
        for args in q.public:
            expected = public_q.reference(*copy.deepcopy(args))
            if not callable(expected) and not isinstance(expected, dict):
                expected = np.asarray(expected, dtype=float)
            if isinstance(q.judge_with, Made) and q.judge_with.factory is table_judge:
                record_diagnosis(expected)  # the poses its diagnosis asks for (a joint reversed, q = 0, ...)
            for got in _probes(q, args):
                try:
                    public_q.judge(got, expected, tuple(args))
                except Exception:  # noqa: BLE001 - what the probe needed is recorded all the same
                    pass
        questions.append(public_q)
    for r in builder.replays:
        r.freeze()
    return dataclasses.replace(ex, questions=tuple(questions))


class _Guard(pickle.Pickler):
    """A pickler that refuses any function of the question bank (nothing of it may reach an edition)."""

    def reducer_override(self, obj: Any) -> Any:
        if isinstance(obj, (types.FunctionType, types.MethodType)) and _from_bank(obj):
            raise ValueError(f"exercises: expected no code of the question bank in an edition, got {obj!r}")
        return NotImplemented


def dumps(public: Mapping[str, Exercise]) -> bytes:
    """The edition's self-check data for ``public`` (name -> :func:`public_exercise`)."""
    buf = io.BytesIO()
    _Guard(buf, protocol=4).dump(dict(public))
    return buf.getvalue()


_LOADED: dict[str, Exercise] = {}


def available() -> bool:
    """Whether this package carries an edition's self-check data."""
    return DATA_FILE.is_file()


def exercises() -> dict[str, Exercise]:
    """The edition's public exercises by name (ValueError when this is not an edition's package)."""
    if not _LOADED:
        if not DATA_FILE.is_file():
            raise ValueError(
                f"exercises: expected the question bank of a course (bank/ beside solutions/) or a student "
                f"edition's self-check data ({str(DATA_FILE)!r}), got neither"
            )
        _LOADED.update(pickle.loads(DATA_FILE.read_bytes()))  # the package's own file, written by the edition
    return _LOADED
