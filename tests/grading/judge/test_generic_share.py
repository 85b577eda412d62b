"""How often a typical wrong answer of the corpus gets only generic feedback (issue 31: below 10 %).

Generic feedback says only that the values differ ("values differ from the reference by up to ...", "row 1 does
not reach the pose", "no single mistake explains every case"): it names no mistake and says nothing a student can
act on. Typical wrong answers are the corpus's wrong answers but the systematic perturbations of
:mod:`tests.fixtures.answers.generic` that no student writes on purpose (values 1 % off, zeros, the first public
case memorised, the first row negated). ``python -m tests.grading.judge.test_generic_share`` prints the figures.
"""

from __future__ import annotations

from tests.fixtures.answers import CORPUS
from tests.fixtures.answers.model import Answer, grade

#: What the systematic perturbations are called (:func:`tests.fixtures.answers.generic.generic_answers`).
NOISE = ("values 1 % off", "zeros", "the first public case's answer, memorised", "one entry or row negated")

#: The openings of a reason that only says the values differ.
GENERIC = (
    "values differ from the reference",
    "angles differ from the reference",
    "your value differs from the right answer here",
    "the rotation your angles give differs",
    "your chain reaches other poses",
    "does not reach the pose",
    "of yours is none of the",
)

#: The largest share of typical wrong answers allowed only generic feedback.
LIMIT = 0.10


def typical(answer: Answer) -> bool:
    """A wrong answer a student writes (not one of the systematic perturbations, unless it is tagged)."""
    return not answer.valid and (answer.name not in NOISE or answer.mistake is not None)


def generic_only(answer: Answer, seed: int = 0) -> bool:
    """True when every failing case of ``answer`` is told only that its values differ (no mistake, no cause)."""
    failing = grade(answer, seed).failing()
    return bool(failing) and all(
        v.mistake in (None, "not_a_solution") and any(g in (v.reason or "") for g in GENERIC) for v in failing
    )


def shares(seed: int = 0) -> tuple[list[Answer], list[Answer], list[Answer], list[Answer]]:
    """(wrong answers, those with generic feedback only, typical ones, typical ones with generic feedback only)."""
    wrong = [a for a in CORPUS if not a.valid]
    generic = [a for a in wrong if generic_only(a, seed)]
    return wrong, generic, [a for a in wrong if typical(a)], [a for a in generic if typical(a)]


def test_generic_feedback_below_ten_percent_of_typical_wrong_answers():
    wrong, generic, common, common_generic = shares()
    assert len(common) >= 150, len(common)
    share = len(common_generic) / len(common)
    assert share < LIMIT, f"{len(common_generic)}/{len(common)} = {share:.1%}: {[a.label for a in common_generic]}"


def test_the_measure_can_fail():
    """A perturbation is generic, a named mistake is not: the measure separates the two."""
    off = next(a for a in CORPUS if a.name == "values 1 % off" and a.qid == "q1" and a.exercise == "ex01_rotations")
    named = next(a for a in CORPUS if a.mistake == "degrees" and a.exercise == "ex01_rotations")
    assert generic_only(off) and not generic_only(named)


if __name__ == "__main__":  # pragma: no cover - the figures for a report
    wrong, generic, common, common_generic = shares()
    print(f"all wrong answers: {len(generic)}/{len(wrong)} = {len(generic) / len(wrong):.1%} generic feedback only")
    print(f"typical wrong answers: {len(common_generic)}/{len(common)} = {len(common_generic) / len(common):.1%}")
    for a in common_generic:
        print("  ", a.label)
