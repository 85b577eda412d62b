"""No question is answered by copying a lecture cell (issue 22, deliverable 1).

Every auto-graded question has a fixture in ``tests/fixtures/answers/transcriptions.py`` (and ``variants.py``):
the answer a student gets by transcribing the nearest lecture cell, adapted only to the question's signature.
Each must earn less than a third of its question under every seed of the sweep, graded in-process as the
grader judges (``tests/fixtures/answers/model.py``). The audit, maximum over seeds 0-9 (†: graded with the
grader's tripwires, the cell's code being a call to a key the question forbids); no question is answered by its
lecture (``ANSWERED_BY_LECTURE`` is empty, and a test keeps it so):

=========  =====================================================  ===========
question   nearest lecture cell transcribed                       max earned
=========  =====================================================  ===========
ex01 q1    L01 §1 cell 4, R_x R_y R_z (by name; sign stripped)    0.60/2
ex01 q2    L01 §2 cell 8, K(u, angle between u and v)             0.55/3
ex01 q3    L01 §3 cell 14, of R_b; of R_aᵀ R_b                    0/3
ex01 q4    L01 §4 cell 16, [[Rᵀ, -Rᵀp], [0, 1]] of ⁰T_A; of ⁰T_B  0/2
ex01 q5    L01 §5 cell 25, Rz Tz(h) Ry                            0/3
ex01 q6    L01 §7, roll-pitch-yaw                                 0/2
ex02 q1    L02 §5 cells 17, 20, entries read off ⁰T_i             0/2
ex02 q2    L02 §5 cell 17, the four motions (not undone)          0/2
ex02 q3    L02 §6 cells 27-29, the worked table                   0/6
ex02 q4    L02 §8 cells 39-40, α and a moved up                   0/2
ex03 q1    L03 §4-5, the product of link matrices from the base   0/3
ex03 q2    L03 cell 17, the table displayed                       0/6
ex04 q1    L04 cell 18, w = p - d5 z5 on the tool's pose          0/2
ex04 q2    L04 cell 2, the table multiplied (no tool)             0/3
ex04 q3    L04 cell 2, the table printed                          0/5
ex04 q4    L04 §8, Craig's nearest pose                           0/3
ex05 q1    L05 cells 7, 9, the nine motions (two fixtures)        0/3
ex05 q2    L05 cell 29, the first 1, 3, 5, 7, 9 factors, a pen     0/2
ex05 q3    none (NO_LECTURE_CELL: Porter has no DH table)         --
ex06 q1    L06 cell 5, p4 = p5 - l4 x5                            0/2
ex06 q2    L06 cells 5-11, Ver.1                                  0/5
ex06 q3    L06 cells 5-11 on the tool's pose                      0/3
ex06 q4    L06 cells 5-11, Ver.1                                  0/3
ex07 q1    L07 cells 3, 5                                         0/2
ex07 q2    L07 cell 7                                             0/3
ex07 q3    L07 cell 9, the unsigned angle                         0.57/2
ex07 q4    L07 cell 17, Ver.2 (†)                                 0/4
ex08 q1-5  L08 §2-§4, the lecture's arm                           0 each
ex09 q1    L09 cells 7, 11, 14                                    0/3
ex09 q2    L09 cells 7-16                                         0/4
ex09 q3    L09 cell 34                                            0/2
ex09 q4    L09 cell 41                                            0/2
ex09 q5    L09 cells 7-16 on the cell's pose                      0/4
ex10 q1    L10 §2 cell 4, D(q, q') (the weights left out)         0/2
ex10 q2    L10 §2 cell 4, sorted by D (unweighted)                0/2
ex10 q3    L10 §2 cells 4-5, nearest at every step                0/6
ex10 q4    L10 §5, the quintic, unwrapped                         0.33/2
=========  =====================================================  ===========

Print the current figures with ``python -m tests.grading.bank.test_transcriptions``.
"""

from __future__ import annotations

import pytest

from puma_course.grading import EXERCISES
from tests.fixtures.answers.model import Answer, grade
from tests.fixtures.answers.transcriptions import ANSWERED_BY_LECTURE, NO_LECTURE_CELL, TRANSCRIPTIONS

#: The seeds of the sweep, as in ``test_corpus.py``.
SEEDS = tuple(range(10))

# ex07 q4's transcription solves singular poses on purpose (the planes parallel): the solver says so
pytestmark = pytest.mark.filterwarnings("ignore::puma_course.kinematics.ik.SingularityWarning")


def _param(answer: Answer) -> object:
    reason = ANSWERED_BY_LECTURE.get((answer.exercise, answer.qid))
    marks = [pytest.mark.xfail(strict=True, reason=f"answered by the lecture: {reason}")] if reason else []
    return pytest.param(answer, id=answer.label, marks=marks)


@pytest.mark.parametrize("answer", [_param(a) for a in TRANSCRIPTIONS])
def test_a_transcribed_lecture_cell_earns_less_than_a_third(answer):
    for seed in SEEDS:
        g = grade(answer, seed)
        assert g.earned < g.points / 3, f"seed {seed}: {g.earned:.2f}/{g.points}"


def test_every_question_has_a_transcription_fixture():
    questions = {(name, q.qid) for name, ex in EXERCISES.items() for q in ex.questions}
    covered = {(a.exercise, a.qid) for a in TRANSCRIPTIONS}
    missing = sorted(questions - covered - set(NO_LECTURE_CELL))
    assert not missing, f"no transcription fixture (tests/fixtures/answers/transcriptions.py) for {missing}"
    assert not set(NO_LECTURE_CELL) & covered, "a question exempted in NO_LECTURE_CELL has a fixture"
    assert set(ANSWERED_BY_LECTURE) <= covered, "ANSWERED_BY_LECTURE names a question without a fixture"
    stale = (set(NO_LECTURE_CELL) | set(ANSWERED_BY_LECTURE)) - questions
    assert not stale, f"listed questions that no longer exist: {sorted(stale)}"


def test_no_question_is_answered_by_its_lecture():
    """Every question asks more than its lecture prints: the drills of ex01 q1-q4 and ex02 q1-q2 were changed."""
    assert ANSWERED_BY_LECTURE == {}, f"questions a copied lecture cell answers: {sorted(ANSWERED_BY_LECTURE)}"


if __name__ == "__main__":  # pragma: no cover - prints the audit's figures
    for a in TRANSCRIPTIONS:
        earned = max(grade(a, s).earned for s in SEEDS)
        print(f"{a.exercise} {a.qid}  {earned:.2f}/{a.question.points}  {a.name}")
