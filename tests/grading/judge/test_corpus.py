"""The answer corpus under a sweep of seeds: no false positive, no false negative, no misleading feedback.

Every valid answer of ``tests/fixtures/answers`` earns full marks under each of the :data:`SEEDS`;
every wrong one fails; a wrong *method* earns at most a third of its question (README: "a wrong
method earns little"); a wrong answer tagged with a mistake has that mistake named on every failing
case, and none names a mistake it was told not to; one that ``says`` something says it on every
failing case. Graded in-process with ``Question.judge`` and the grader's
:func:`~puma_course.grading.judge.verdict.reconcile`, so the whole corpus takes seconds.
"""

from __future__ import annotations

import pytest

from tests.fixtures.answers import CORPUS
from tests.fixtures.answers.model import grade

#: The seeds of the sweep (the grader draws the hidden cases from the seed of a grading run).
SEEDS = tuple(range(10))

VALID = [a for a in CORPUS if a.valid]
WRONG = [a for a in CORPUS if not a.valid]


def test_corpus_size():
    assert len(VALID) >= 100, len(VALID)
    assert len(WRONG) >= 130, len(WRONG)


@pytest.mark.parametrize("answer", VALID, ids=lambda a: a.label)
def test_valid_answers_earn_full_marks_under_every_seed(answer):
    for seed in SEEDS:
        g = grade(answer, seed)
        bad = [v.reason for v in g.failing()]
        assert not bad, f"seed {seed}: {bad[:2]}"


@pytest.mark.parametrize("answer", WRONG, ids=lambda a: a.label)
def test_wrong_answers_fail_under_every_seed_and_are_named_fairly(answer):
    for seed in SEEDS:
        g = grade(answer, seed)
        assert g.earned < g.points - 1e-9, f"seed {seed}: a wrong answer earned full marks"
        if answer.method:
            assert g.earned <= g.points / 3 + 1e-9, f"seed {seed}: a wrong method earned {g.earned:.2f}/{g.points}"
        if answer.mistake is not None:
            named = [v.mistake for v in g.failing()]
            assert named and set(named) == {answer.mistake}, f"seed {seed}: named {named}, expected {answer.mistake}"
        if answer.told is not None:
            told = {v.reason for v in g.failing()}
            assert told == {answer.told}, f"seed {seed}: told {told}, expected {answer.told!r}"
        if answer.says is not None:
            unsaid = [v.reason for v in g.failing() if answer.says not in (v.reason or "")]
            assert not unsaid, f"seed {seed}: expected {answer.says!r} on every failing case, got {unsaid[:2]}"
        wrongly = g.mistakes & set(answer.not_named)
        assert not wrongly, f"seed {seed}: named {wrongly}: {[v.reason for v in g.failing()][:2]}"
