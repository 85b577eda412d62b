"""What grading produces: a :class:`NotebookResult` per (student, exercise), and :func:`score_question`, the one
scoring rule (points × cases passed / cases).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

from .spec import Exercise

__all__ = ["NotebookResult", "score_question", "MAX_NOTES"]

#: At most this many distinct failure reasons are kept per question (after the "k/n cases pass" line).
MAX_NOTES = 3


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
