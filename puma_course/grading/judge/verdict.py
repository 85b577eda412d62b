"""How one returned value was judged: a :class:`Verdict`, and :func:`reconcile`, the rule that names a mistake
only where every failing case of a question equals it.

:meth:`Question.judge <puma_course.grading.spec.Question.judge>` gives a verdict per case; a modelling question's
judge (:mod:`.judges`, typed :data:`Judge`) gives one itself.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import Any

from .mistake import base_key

__all__ = ["Verdict", "Judge", "reconcile"]


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


#: ``judge_with(got, expected, args)``: how a modelling question judges a value (see :attr:`Question.judge_with`).
Judge = Callable[[Any, Any, tuple[Any, ...]], Verdict]
