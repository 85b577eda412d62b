"""Each student's total, worked out once per run and shown the same in every file the run writes.

:func:`student_totals` adds a student's auto-graded scores and, with ``grade --marks``, their marked written
points (:func:`.marks.written_totals`, the numbers the gradebooks count). The feedback's ``Total:`` line, the
class summary's table of students, the grades CSV (``score`` plus ``written`` per row) and each gradebook's
total are all this number (:mod:`.writer`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from ..results import NotebookResult

__all__ = ["StudentTotal", "student_totals"]


@dataclass(frozen=True)
class StudentTotal:
    """A student's points: auto-graded and written (None: no written marks in this run), each with its maximum.

    >>> t = StudentTotal(27, 27, 2.5, 4)
    >>> t.total, t.top
    (29.5, 31)
    """

    auto: float
    auto_max: float
    written: float | None = None
    written_max: float = 0.0

    @property
    def total(self) -> float:
        """Auto-graded plus written points (two decimals)."""
        return round(self.auto + (self.written or 0.0), 2)

    @property
    def top(self) -> float:
        """The points possible: the exercises' and the written questions' (two decimals)."""
        return round(self.auto_max + (self.written_max if self.written is not None else 0.0), 2)


def student_totals(
    results: Sequence[NotebookResult], written: Mapping[str, tuple[float, float]] | None = None
) -> dict[str, StudentTotal]:
    """student -> :class:`StudentTotal`, in the order the results name them.

    ``written`` maps a student to (marked written points, written points possible) (:func:`.marks.written_totals`);
    None when the run has no written marks.

    >>> from puma_course.grading import EXERCISES
    >>> r = NotebookResult.blank("ann", EXERCISES["ex01_rotations"])
    >>> r.scores["q1"] = 2.0
    >>> t = student_totals([r], {"ann": (2.5, 4.0)})["ann"]
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
        w = None if written is None else written.get(student, (0.0, 0.0))
        out[student] = StudentTotal(
            round(score, 2), round(most, 2), None if w is None else w[0], 0.0 if w is None else w[1]
        )
    return out
