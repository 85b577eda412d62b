"""The question spec: a graded :class:`Question`, an :class:`Exercise` of questions.

An exercise's questions are declared in the course's question bank (``COURSE/bank/``, one file per exercise,
registered in :data:`~puma_course.grading.bank_loader.EXERCISES`). :attr:`Question.points` is the only place a
question's points are written down: the release generator copies them into the exercise notebooks, the grader and
the self-check score with them. :meth:`Question.judge` is the one place a returned value is judged
(:class:`~puma_course.grading.judge.verdict.Verdict`); a question's ``forbidden`` names are its answer key
(:func:`of_course`, :func:`key_words`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from .judge.compare import Comparison, compare_close
from .judge.diagnose import Mistake, base_key, diagnose_all
from .judge.verdict import Judge, Verdict

__all__ = ["Question", "Exercise", "key_words", "of_course"]


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

    >>> from puma_course.grading import EXERCISES
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
