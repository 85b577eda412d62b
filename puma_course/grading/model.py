"""The question model: a graded :class:`Question`, an :class:`Exercise` of questions, the registry.

The registry :data:`EXERCISES` maps an exercise's name (the file stem of
``solutions/NAME.ipynb``) to its :class:`Exercise`; the course's question bank (``COURSE/bank/``,
beside ``solutions/``, imported from the course folder) fills it, one exercise each.
:attr:`Question.points` is the only place a question's points are written down: the release
generator copies them into the exercise notebooks, the grader and the self-check score with them.
:class:`NotebookResult` is what grading one notebook produces, and
:func:`score_question` the one scoring rule (points × cases passed / cases).
"""

from __future__ import annotations

import importlib.util
import os
import sys
from collections.abc import Callable, Iterator, MutableMapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from .judge.compare import Comparison, compare_close
from .judge.diagnose import Mistake, base_key, diagnose_all

__all__ = [
    "Question",
    "Exercise",
    "EXERCISES",
    "register",
    "Bank",
    "BankNotFoundError",
    "BANK_MODULE",
    "load_bank",
    "NotebookResult",
    "Verdict",
    "score_question",
    "key_words",
    "of_course",
    "MAX_NOTES",
    "reconcile",
]

#: At most this many distinct failure reasons are kept per question (after the "k/n cases pass" line).
MAX_NOTES = 3


@dataclass(frozen=True)
class Verdict:
    """How one returned value was judged: ``reason`` is None when it is right, else why not (for the
    student); ``mistake`` names a recognised common mistake (e.g. ``"transposed"``), when one was
    diagnosed, so the class summary can count them.

    >>> Verdict(None).passed, Verdict("values differ", "transposed").mistake
    (True, 'transposed')
    """

    reason: str | None
    mistake: str | None = None
    #: Set when a returned value was judged: every recognised mistake this value *equals*, as (key,
    #: message), in the question's order (empty: none). :func:`reconcile` names a mistake only when
    #: every failing case of the question equals it. None: not a judged value (an error, no answer).
    candidates: tuple[tuple[str, str], ...] | None = None
    #: What differs, without naming a mistake: said instead when the mistake is not the same on every failing case.
    plain: str | None = None

    @property
    def passed(self) -> bool:
        """True when the value was right."""
        return self.reason is None

    def judged(self) -> Verdict:
        """This verdict with ``candidates`` filled in (its own mistake, if it names one) and ``plain`` defaulted."""
        candidates = self.candidates
        if candidates is None:
            candidates = ((self.mistake, self.reason or ""),) if self.mistake is not None else ()
        plain = self.plain if self.plain is not None else (None if self.mistake is not None else self.reason)
        return replace(self, candidates=candidates, plain=plain)


def reconcile(verdicts: Sequence[Verdict]) -> list[Verdict]:
    """The verdicts on one question's cases, a mistake named only where *every* failing judged case equals it.

    A wrong answer can coincide with a mistaken formula on one case (the angle from w to v equals the
    unsigned angle wherever the right angle is negative): naming it from that case alone would tell
    the student about a mistake they did not make. The mistake named is the first one (in the
    question's order) that every failing judged case equals; when there is none, every failing case
    says what differs instead (its ``plain`` reason). Cases that failed without a value (an error, a
    timeout) do not take part.

    >>> a = Verdict("unsigned", "unsigned_angle", (("unsigned_angle", "unsigned"), ("sign_flip", "flip")), "off 1")
    >>> b = Verdict("flip", "sign_flip", (("sign_flip", "flip"),), "off 2")
    >>> [v.mistake for v in reconcile([a, b])], [v.reason for v in reconcile([a, Verdict(None)])]
    (['sign_flip', 'sign_flip'], ['unsigned', None])
    >>> c = Verdict("values differ", None, (), "values differ")
    >>> [(v.reason, v.mistake) for v in reconcile([a, c])]
    [('off 1', None), ('values differ', None)]
    """
    out = list(verdicts)
    failing = [i for i, v in enumerate(out) if not v.passed and v.candidates is not None]
    if not failing:
        return out
    common: list[str] | None = None
    for i in failing:
        keys = [k for k, _ in out[i].candidates or ()]
        common = keys if common is None else [k for k in common if k in keys]
    for i in failing:
        v = out[i]
        if common:
            message = dict(v.candidates or ())[common[0]]
            out[i] = replace(v, reason=message, mistake=base_key(common[0]))
        elif v.mistake is not None or v.candidates:
            plain = v.plain or "your value differs from the right answer here (no single mistake explains every case)"
            out[i] = replace(v, reason=plain, mistake=None)
    return out


def of_course(spec: str) -> bool:
    """Whether a ``forbidden`` ``"module:attr"`` is the course's code (package or bank), not another library's."""
    return spec.startswith("puma_course")


def key_words(spec: str) -> str:
    """What a case that called one of its question's ``forbidden`` names is told (``spec`` "" if unknown).

    >>> key_words("puma_course.transforms:rotx")
    "used the course package's answer (puma_course.transforms.rotx) instead of your own code"
    >>> key_words("numpy.linalg:inv")
    'called numpy.linalg.inv, which this question asks you to do without'
    """
    name = spec.replace(":", ".")
    if spec and not of_course(spec):
        return f"called {name}, which this question asks you to do without"
    return f"used the course package's answer ({name or 'a function of the course package'}) instead of your own code"


#: ``judge_with(got, expected, args)``: how a modelling question judges a value (see :attr:`Question.judge_with`).
Judge = Callable[[Any, Any, tuple[Any, ...]], Verdict]


@dataclass(frozen=True)
class Question:
    """One graded question: the student writes ``function``; cases are argument tuples.

    ``public`` cases are shown to the student (self-check); ``hidden(rng)`` draws
    more at grading time. ``reference(*args)`` gives the expected value in the
    grader's process, ``compare(got, expected)`` returns None or a reason.
    A ``bonus`` question's points count in the score but not in the maximum.
    ``forbidden`` names package functions (``"module:attr"``) that are this
    question's answer key; calling them while being graded fails the case.

    ``mistakes`` are the common wrong answers (:mod:`puma_course.grading.judge.diagnose`) recognised
    before the generic reason of ``compare``. A modelling question, graded for what is right rather
    than against one answer, sets ``judge_with`` instead (:mod:`puma_course.grading.judge.judges`); its
    ``reference`` may then return whatever that judge needs (a dict, with callables), and ``answer``
    gives one right answer (the tests use it; default: ``reference`` itself).

    >>> q = Question("q1", "double", 2, "twice x", public=((1.0,),), hidden=lambda rng: [(2.0,)],
    ...              reference=lambda x: 2 * x)
    >>> q.cases(np.random.default_rng(0))
    [(1.0,), (2.0,)]
    """

    qid: str
    function: str
    points: float
    title: str
    public: tuple[tuple[Any, ...], ...]
    hidden: Callable[[np.random.Generator], list[tuple[Any, ...]]]
    reference: Callable[..., Any]
    compare: Comparison = compare_close
    hint: str = ""
    bonus: bool = False
    forbidden: tuple[str, ...] = ()
    mistakes: tuple[Mistake, ...] = ()
    judge_with: Judge | None = None
    answer: Callable[..., Any] | None = None

    def __post_init__(self) -> None:
        if not (isinstance(self.points, (int, float)) and self.points > 0 and np.isfinite(self.points)):
            raise ValueError(f"points: expected a positive number of points for {self.qid}, got {self.points!r}")

    def cases(self, rng: np.random.Generator) -> list[tuple[Any, ...]]:
        """Public cases followed by hidden ones drawn from ``rng``."""
        return list(self.public) + list(self.hidden(rng))

    def judge(self, got: Any, expected: Any, args: tuple[Any, ...]) -> Verdict:
        """Judge the value ``got`` that the student's function returned for ``args``.

        ``expected`` is ``reference(*args)``, computed in the grader's process. The one place where
        a returned value is judged: the grader, the self-check and ``puma-course check`` all call it.
        A modelling question asks its ``judge_with``; otherwise ``compare`` decides, and a failing
        value that matches one of the question's ``mistakes`` is named as that mistake.

        >>> from puma_course.grading.judge.diagnose import DEGREES_OUT
        >>> q = Question("q1", "double", 2, "twice x", public=((1.0,),), hidden=lambda rng: [],
        ...              reference=lambda x: 2 * x, mistakes=(DEGREES_OUT,))
        >>> q.judge(2.0, 2.0, (1.0,)).passed, q.judge(3.0, 2.0, (1.0,)).reason[:25]
        (True, 'values differ from the re')
        >>> q.judge(np.degrees(2.0), 2.0, (1.0,)).mistake
        'degrees'
        """
        if self.judge_with is not None:
            verdict = self.judge_with(got, expected, tuple(args))
            return verdict if verdict.passed else verdict.judged()
        reason = self.compare(got, expected)
        if reason is None:
            return Verdict(None)
        found = diagnose_all(self.mistakes, got, expected, tuple(args), self.reference)
        if not found:
            return Verdict(reason, None, (), reason)
        return Verdict(found[0][1], base_key(found[0][0]), tuple(found), reason)

    def right_answer(self, *args: Any) -> Any:
        """One right answer for ``args`` (``answer``, else ``reference``): what the tests feed the judge."""
        return (self.answer or self.reference)(*args)


@dataclass(frozen=True)
class Exercise:
    """An exercise notebook: its file stem (``solutions/NAME.ipynb``) and its questions.

    >>> ex = EXERCISES["ex06_porter_explicit"]
    >>> ex.max_score, ex.question("q4").bonus  # 2 + 5 + 3, and a 3-point bonus on top
    (10.0, True)
    """

    name: str
    title: str
    questions: tuple[Question, ...]
    #: What the student's code may import from the package in this exercise ("module" or "module:name",
    #: e.g. "puma_course.transforms:rotx"); everything else is absent from the grading worker.
    allowed: tuple[str, ...] = ()

    @property
    def answer_keys(self) -> tuple[str, ...]:
        """Every question's ``forbidden`` names of the course package, once each, sorted: what the student side leaves
        out unless allowed. A name of another library (``numpy.linalg:inv``) is only a tripwire: numpy stays whole."""
        return tuple(sorted({spec for q in self.questions for spec in q.forbidden if of_course(spec)}))

    @property
    def max_score(self) -> float:
        """The points of the questions that are not a bonus."""
        return float(sum(q.points for q in self.questions if not q.bonus))

    def question(self, qid: str) -> Question:
        """The question called ``qid`` (ValueError naming the exercise's questions if there is none)."""
        for q in self.questions:
            if q.qid == qid:
                return q
        raise ValueError(f"question: expected one of {[q.qid for q in self.questions]} in {self.name}, got {qid!r}")


#: The name the course's bank is imported under (its ``bank/`` folder is a package of this name).
BANK_MODULE = "puma_course_bank"


class BankNotFoundError(ValueError):
    """The course has no question bank (``bank/`` beside ``solutions/``), e.g. a student edition."""


class Bank(MutableMapping[str, Exercise]):
    """The registry of exercises by name, filled from the question bank of a course folder.

    The bank is content, not engine: it lives in the course folder (``COURSE/bank/``, one file per
    exercise, beside ``solutions/``) and is imported from there, so editing a question needs no
    reinstall. The first lookup loads the bank of the course found from the current directory
    (:func:`puma_course.course.find_course`); :meth:`load` loads another course's bank.
    """

    def __init__(self) -> None:
        self._data: dict[str, Exercise] = {}
        self._course: Path | None = None
        self._loading = False

    @property
    def course(self) -> Path | None:
        """The course folder whose bank is loaded (None before the first lookup)."""
        return self._course

    def load(self, course: str | os.PathLike[str] | None = None) -> Bank:
        """Load the question bank of ``course`` (default: the course found from the current directory).

        Raises :class:`BankNotFoundError` naming the folder it looked in when the course has no ``bank/``.
        """
        from ..course import course_root

        given = Path(course).resolve() if course is not None else None
        # a course folder, or any folder holding a bank/ (an autograder's source folder: .gradescope)
        root = given if given is not None and (given / "bank" / "__init__.py").is_file() else course_root(course)
        init = root / "bank" / "__init__.py"
        if not init.is_file():
            raise BankNotFoundError(
                f"course: expected a question bank at {str(init.parent)!r} (the instructor's course folder holds "
                f"bank/ beside solutions/; a student edition has none), got {str(root)!r} without one"
            )
        if root == self._course and self._data:
            return self
        for name in [m for m in sys.modules if m == BANK_MODULE or m.startswith(BANK_MODULE + ".")]:
            del sys.modules[name]
        self._data.clear()
        self._course = root
        spec = importlib.util.spec_from_file_location(BANK_MODULE, init, submodule_search_locations=[str(init.parent)])
        if spec is None or spec.loader is None:  # pragma: no cover - a file that exists always gives a spec
            raise BankNotFoundError(f"course: could not import the question bank at {str(init)!r}")
        module = importlib.util.module_from_spec(spec)
        sys.modules[BANK_MODULE] = module
        self._loading = True
        try:
            spec.loader.exec_module(module)
        except BaseException:
            sys.modules.pop(BANK_MODULE, None)
            self._data.clear()
            self._course = None
            raise
        finally:
            self._loading = False
        return self

    def _loaded(self) -> dict[str, Exercise]:
        if self._course is None and not self._loading:
            self.load()
        return self._data

    def __getitem__(self, name: str) -> Exercise:
        return self._loaded()[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self._loaded())

    def __len__(self) -> int:
        return len(self._loaded())

    def __setitem__(self, name: str, exercise: Exercise) -> None:
        self._loaded()[name] = exercise

    def __delitem__(self, name: str) -> None:
        del self._loaded()[name]

    def register(self, exercise: Exercise) -> Exercise:
        """Add ``exercise`` (ValueError if the name or a question id is taken twice)."""
        if exercise.name in self._data and self._data[exercise.name] is not exercise:
            raise ValueError(f"exercise: expected a new name, got {exercise.name!r}, which is registered already")
        qids = [q.qid for q in exercise.questions]
        if len(set(qids)) != len(qids) or not qids:
            raise ValueError(f"exercise: expected distinct question ids in {exercise.name}, got {qids}")
        self._data[exercise.name] = exercise
        return exercise


#: Every exercise by name, from the question bank of the course (``COURSE/bank/``, one file per exercise).
EXERCISES: Bank = Bank()


def load_bank(course: str | os.PathLike[str] | None = None) -> Bank:
    """Load the question bank of ``course`` into :data:`EXERCISES` (default: the course found from here)."""
    return EXERCISES.load(course)


def register(exercise: Exercise) -> Exercise:
    """Add ``exercise`` to :data:`EXERCISES` (ValueError if the name or a question id is taken twice)."""
    return EXERCISES.register(exercise)


@dataclass
class NotebookResult:
    """The outcome of grading one (student, exercise) pair."""

    student: str
    exercise: str
    status: str
    max_score: float
    scores: dict[str, float] = field(default_factory=dict)
    question_notes: dict[str, list[str]] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)
    seconds: float = 0.0
    #: qid -> the keys of the common mistakes diagnosed in its failing cases (one per case)
    mistakes: dict[str, list[str]] = field(default_factory=dict)
    #: names this notebook's hidden inputs (:meth:`~puma_course.grading.secret.Secret.run_id`); "" outside a class run
    run_id: str = ""

    @classmethod
    def blank(cls, student: str, exercise: Exercise, status: str = "ok", note: str | None = None) -> NotebookResult:
        """A result with every question of ``exercise`` at 0 points and no notes (but ``note``)."""
        qids = [q.qid for q in exercise.questions]
        result = cls(student, exercise.name, status, exercise.max_score, {q: 0.0 for q in qids}, {q: [] for q in qids})
        if note is not None:
            result.notes.append(note)
        return result

    @property
    def score(self) -> float:
        """The sum of the question scores (bonus included), to 0.01."""
        return round(sum(self.scores.values()), 2)


def score_question(points: float, outcomes: Sequence[tuple[str, str | None]]) -> tuple[float, list[str]]:
    """Points earned and notes for a question's cases, given as (label, reason or None when it passed).

    The notes are "k/n cases pass" followed by up to :data:`MAX_NOTES` distinct failure reasons,
    each after the label of the first case that gave it.

    >>> score_question(3, [("case 1", None), ("case 2", "wrong"), ("case 3", "wrong")])
    (1.0, ['1/3 cases pass', 'case 2: wrong'])
    """
    passed, seen = 0, set()
    notes: list[str] = []
    for label, reason in outcomes:
        if reason is None:
            passed += 1
        elif reason not in seen:
            seen.add(reason)
            if len(notes) < MAX_NOTES:
                notes.append(f"{label}: {reason}")
    total = len(outcomes)
    earned = round(points * passed / total, 2) if total else 0.0
    return earned, [f"{passed}/{total} cases pass", *notes]
