"""Each student's total, worked out once per run and shown the same in every file the run writes.

:func:`student_totals` adds a student's auto-graded scores and, with ``grade --marks``, their written points
(:class:`WrittenScore`, from :func:`.marks.written_by_student`: the numbers the gradebooks count). The feedback's
``Total:`` line, the class summary's table of students, the grades CSV (``score`` plus ``written`` per row) and
each gradebook's total are all this number (:mod:`.writer`).

A written answer not marked yet counts nothing, and the total that leaves it out is *provisional*: the feedback
and the summary say so (:meth:`WrittenScore.text`), the CSV's and the gradebooks' written cells of an exercise
none of whose answers is marked stay empty (Canvas's and Moodle's imports read an empty cell as no grade, never
as 0), and the wide gradebook counts the answers still to mark. An answer of a notebook that was not handed in
has nothing to mark: it scores 0, as the notebook's auto-graded questions do.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass

from ..results import NotebookResult
from .text import plural

__all__ = ["WrittenScore", "StudentTotal", "student_totals"]


@dataclass(frozen=True)
class WrittenScore:
    """Written points: those of the answers marked (None: none is, and some wait for a mark), the points
    possible, and how many answers wait for a mark.

    >>> WrittenScore(2.5, 4).text(), WrittenScore(None, 4, 1).text(), WrittenScore(1, 8, 1).text()
    ('2.5 / 4', 'not marked yet (4 points)', '1 / 8 so far, 1 answer not marked yet')
    """

    points: float | None
    possible: float
    unmarked: int = 0

    @property
    def provisional(self) -> bool:
        """True when some answer waits for a mark (the points then count only those marked)."""
        return self.unmarked > 0

    def text(self) -> str:
        """The points as the feedback and the summary show them."""
        if self.points is None:
            return f"not marked yet ({plural(self.possible, 'point')})"
        shown = f"{self.points:g} / {self.possible:g}"
        return f"{shown} so far, {plural(self.unmarked, 'answer')} not marked yet" if self.provisional else shown

    @classmethod
    def add(cls, scores: Iterable[WrittenScore]) -> WrittenScore:
        """The scores of several exercises added up (None only when some answer waits and none is marked).

        >>> WrittenScore.add([WrittenScore(None, 4, 1), WrittenScore(2, 4)])
        WrittenScore(points=2.0, possible=8.0, unmarked=1)
        """
        scores = list(scores)
        known = [s.points for s in scores if s.points is not None]
        unmarked = sum(s.unmarked for s in scores)
        points = round(float(sum(known)), 2) if known or not unmarked else None
        return cls(points, round(float(sum(s.possible for s in scores)), 2), unmarked)


@dataclass(frozen=True)
class StudentTotal:
    """A student's points: auto-graded and written (None: no written marks in this run), each with its maximum.

    >>> t = StudentTotal(27, 27, WrittenScore(2.5, 4))
    >>> t.total, t.top, t.provisional
    (29.5, 31, False)
    """

    auto: float
    auto_max: float
    written: WrittenScore | None = None

    @property
    def total(self) -> float:
        """Auto-graded plus written points (those marked; two decimals)."""
        return round(self.auto + ((self.written.points or 0.0) if self.written is not None else 0.0), 2)

    @property
    def top(self) -> float:
        """The points possible: the exercises' and the written questions' (two decimals)."""
        return round(self.auto_max + (self.written.possible if self.written is not None else 0.0), 2)

    @property
    def provisional(self) -> bool:
        """True when a written answer waits for a mark: the total then leaves it out."""
        return self.written is not None and self.written.provisional


def student_totals(
    results: Sequence[NotebookResult], written: Mapping[str, WrittenScore] | None = None
) -> dict[str, StudentTotal]:
    """student -> :class:`StudentTotal`, in the order the results name them.

    ``written`` maps a student to their written points over the exercises graded for them
    (:func:`.marks.written_totals`); None when the run has no written marks.

    >>> from puma_course.grading import EXERCISES
    >>> r = NotebookResult.blank("ann", EXERCISES["ex01_rotations"])
    >>> r.scores["q1"] = 2.0
    >>> t = student_totals([r], {"ann": WrittenScore(2.5, 4.0)})["ann"]
    >>> t.auto, t.total, t.top
    (2.0, 4.5, 19.0)
    """
    auto: dict[str, list[float]] = {}
    for r in results:
        got = auto.setdefault(r.student, [0.0, 0.0])
        got[0] += r.score
        got[1] += r.max_score
    out = {}
    for student, (score, most) in auto.items():
        w = None if written is None else written.get(student, WrittenScore(0.0, 0.0))
        out[student] = StudentTotal(round(score, 2), round(most, 2), w)
    return out
