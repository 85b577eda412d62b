"""Exercise 2 (``solutions/ex02_dh_frames.ipynb``): attaching frames, Craig's modified DH convention.

From reading the four parameters of a link off the world poses of its two frames, and the inverse link
matrix ⁱT_{i-1} (the one Craig premultiplies by in inverse kinematics), to the modelling question:
the DH table of an arm the lectures did not treat (an RRP arm with a shoulder offset, the first
three joints of the Stanford arm), graded by the poses its chain reaches; then a standard-DH table (a
book's, a library's) rewritten in Craig's convention, the direction lecture 02 §8 does not print.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from puma_course.grading.judge.compare import compare_angles_at
from puma_course.grading.judge.diagnose import (
    SIGN_FLIP,
    degrees_in,
    degrees_out,
    matches,
    matches_entries,
    sign_flip,
)
from puma_course.grading.judge.judges import table_judge
from puma_course.grading.spec import Exercise, Question

from . import _keys as keys
from ._formulas import (
    link_parameters_between,
    modified_from_standard,
    parameters_in_order,
    parameters_of_inverse,
    parameters_of_pose,
    standard_reading_between,
)
from ._reference import chains as ref

#: A valid table of the RRP arm (frame {1} with x1 along x0 at q = 0): rows α_{i-1}, a_{i-1}, θ_i, d_i, σ_i.
H = np.pi / 2

#: ex02 q1's mistaken readings are recognised from α, a and θ (entries 0-2, the angles modulo 2π): d read off a
#: matrix that is not a link matrix depends on which entries it was read from.
ENTRIES = ([0, 1, 2], [0, 2])


def rrp_table(h: float, d2: float) -> np.ndarray:
    """One valid modified-DH table of the RRP arm (the solution's)."""
    return np.array([[0.0, 0.0, 0.0, h, 0], [H, 0.0, H, -d2, 0], [H, 0.0, 0.0, 0.0, 1]])


def _world_pose(rng: np.random.Generator) -> np.ndarray:
    """A pose ⁰T_{i-1} of frame {i-1} in the world: a turn of at least 0.2 rad about a random axis, an offset."""
    (R,) = ref.random_rotations(rng, 1)
    return ref.pose(R, rng.uniform(-1.0, 1.0, 3))


def _poses(T_prev: np.ndarray, alpha: float, a: float, theta: float, d: float) -> tuple[np.ndarray, np.ndarray]:
    """The arguments of q1: ⁰T_{i-1} and ⁰T_i = ⁰T_{i-1} ⁱ⁻¹T_i."""
    return T_prev, T_prev @ ref.mdh(alpha, a, theta, d)


def _away_from_zero(rng: np.random.Generator, lo: float, hi: float) -> float:
    return float(rng.choice([-1.0, 1.0]) * rng.uniform(lo, hi))


def _parameter_cases(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    """``n`` pairs of world poses. Exactly one link has no twist (α = 0, where -α is the same twist, so an α with the
    wrong sign is right there and nowhere else; at α = π the same holds, but rounding decides whether the reference
    reads π or -π, and a sign flip or degrees could no longer be told exactly); the other twists are ±π/2 or random,
    never near 0 or π. Every a is positive, away from 0: Craig's a_{i-1} is the distance between the two z axes
    (lecture 02 §2), so two frames whose link matrix shows a < 0 are no valid pair, and an answer that reads a as
    that distance is right. One d is positive and the others negative, so that |d| is right on one hidden case
    only."""
    twists = [0.0] + [float(rng.choice([H, -H])) if k % 2 else _away_from_zero(rng, 0.3, 2.8) for k in range(1, n)]
    ds = [float(rng.uniform(0.1, 1.0))] + [-float(rng.uniform(0.1, 1.0)) for _ in range(1, n)]
    order = rng.permutation(n)
    return [
        _poses(
            _world_pose(rng),
            twists[k],
            float(rng.uniform(0.1, 1.0)),
            _away_from_zero(rng, 0.2, np.pi - 0.2),
            ds[int(order[k])],
        )
        for k in range(n)
    ]


def _inverse_cases(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    """``n`` links none of whose four numbers is near 0 or π: at α = 0 or θ = 0 the motions negated in their own
    order are the translation -p, and at a zero number several mistakes give the same matrix. a is positive, a
    distance as in q1 (Craig's a_{i-1} >= 0)."""
    return [
        (
            float(rng.choice([H, -H])) if k % 2 else _away_from_zero(rng, 0.3, 2.8),
            float(rng.uniform(0.1, 1.0)),
            _away_from_zero(rng, 0.3, np.pi - 0.3),
            _away_from_zero(rng, 0.1, 1.0),
        )
        for k in range(n)
    ]


INVERSE_Q2 = (
    "this is the link matrix ⁱ⁻¹T_i itself, the four motions as lecture 02 §5 multiplies them: the question asks for "
    "the matrix that takes {i} back to {i-1}"
)
NEGATED_Q2 = (
    "each motion is undone, but in the order the frames moved: undoing a walk of four steps starts with the last "
    "step (this is also the inverse of the standard-DH link matrix)"
)
REVERSED_Q2 = (
    "the motions are in the reverse order, but each still goes forward: undoing a step moves by its negative "
    "(this is also the standard-DH link matrix of the same four numbers)"
)

EXERCISE = Exercise(
    "ex02_dh_frames",
    "Attaching frames: Craig's modified DH convention",
    (
        Question(
            "q1",
            "dh_parameters",
            2,
            "the four parameters of a link, from the world poses of its two frames",
            public=(
                _poses(ref.world_pose([("z", H)], [0.5, 0.0, 0.3]), H, 0.4, -1.0, 0.15),
                _poses(ref.world_pose([("x", 0.6), ("z", -0.4)], [0.2, -0.3, 0.8]), -H, 0.25, 0.5, -0.3),
            ),
            hidden=lambda rng: _parameter_cases(rng, 5),
            reference=link_parameters_between,
            compare=compare_angles_at([0, 2]),
            forbidden=keys.KEY_LINK_PARAMETERS,
            mistakes=(
                matches_entries(
                    "base_frame",
                    "you read the numbers off ⁰T_i, the pose of {i} in the world: the four parameters describe "
                    "{i} as seen from {i-1}, and ⁰T_{i-1} is not the identity",
                    parameters_of_pose,
                    *ENTRIES,
                ),
                matches_entries(
                    "inverse",
                    "these are the numbers of the link matrix the other way round, {i-1} seen from {i}: the "
                    "parameters describe {i} as seen from {i-1}",
                    parameters_of_inverse,
                    *ENTRIES,
                ),
                matches_entries(
                    "order",
                    "these are the numbers of ⁰T_i (⁰T_{i-1})⁻¹: a product of poses is read from the left, "
                    "the frame it starts from first (lecture 01 §5)",
                    parameters_in_order,
                    *ENTRIES,
                ),
                matches_entries(
                    "standard_dh",
                    "these are the numbers a standard-DH link matrix shows in those places "
                    "(θ in its first column, α in its third row); Craig's matrix places them differently "
                    "(lecture 02 §3 and §5)",
                    standard_reading_between,
                    *ENTRIES,
                ),
                degrees_out([0, 2]),
                sign_flip(("α_(i-1)", "a_(i-1)", "θ_i", "d_i")),
            ),
            hint="Lecture 02 §5 reads the four numbers off a matrix you are not given: which matrix describes {i} "
            "as seen from {i-1}? Test on a case you can draw, with ⁰T_(i-1) the identity; then move both frames "
            "together by the same pose: the four numbers must not change.",
        ),
        Question(
            "q2",
            "link_matrix_inverse",
            2,
            "the inverse link matrix ⁱT_(i-1)",
            public=((H, 0.4, -1.0, 0.15), (-H, 0.3, 0.5, -0.2), (0.7, 0.25, 2.0, 0.35)),
            hidden=lambda rng: _inverse_cases(rng, 5),
            reference=ref.mdh_inverse,
            # the four motions undone is the skill: numpy's general inverses and solvers would skip it
            forbidden=(*keys.KEY_MDH_INVERSE, *keys.KEY_GENERAL_INVERSE),
            mistakes=(
                matches("inverse", INVERSE_Q2, ref.mdh),
                matches("order", NEGATED_Q2, ref.mdh_negated),
                matches("standard_dh", REVERSED_Q2, ref.mdh_reversed),
                matches(
                    "transposed",
                    "you returned the inverse transposed as a whole 4×4: only its rotation block is a transpose "
                    "(lecture 01 §4)",
                    ref.mdh_inverse_transposed,
                ),
                matches(
                    "transposed",
                    "you returned the link matrix transposed as a whole 4×4: its rotation block Rᵀ is right, but "
                    "the translation of an inverse does not come from a transpose (lecture 01 §4)",
                    ref.mdh_transposed,
                ),
                matches(
                    "translation",
                    "the rotation part is right, the translation is -p (p the origin of {i} in {i-1}): the origin of "
                    "{i-1} is -p written in {i-1}'s axes, and the answer needs it in {i}'s axes",
                    ref.mdh_inverse_minus_p,
                ),
                matches(
                    "translation",
                    "the rotation part is right, the translation is p, the origin of {i} in {i-1}: the answer needs "
                    "the origin of {i-1}, written in {i}'s axes",
                    ref.mdh_inverse_plus_p,
                ),
                degrees_in(0, 2),
                SIGN_FLIP,
            ),
            hint="Check your matrix: multiplied by Craig's link matrix of lecture 02 §5, on either side, it must "
            "give the identity; try a link with a single non-zero number first.",
        ),
        Question(
            "q3",
            "rrp_table",
            6,
            "the DH table of the RRP arm, from its picture",
            public=((0.8, 0.2), (1.2, 0.35)),
            hidden=lambda rng: [
                (float(h), float(d)) for h, d in zip(rng.uniform(0.3, 1.5, 4), rng.uniform(0.05, 0.5, 4), strict=True)
            ],
            reference=ref.rrp_expected,
            judge_with=table_judge(),
            answer=rrp_table,
            forbidden=keys.KEY_TABLES,
            hint="Draw z_i along each joint axis in its positive sense first, then each x_i along the common normal "
            "(lecture 02 §3, intersecting axes §4); evaluate your table at q = 0 and with one joint moved, and compare "
            "with the picture.",
        ),
        Question(
            "q4",
            "modified_from_standard",
            2,
            "a standard-DH table rewritten as Craig's modified table",
            public=(
                (np.array([[H, 0.0, 0.0, 0.5, 0], [0.0, 0.4, 0.3, 0.0, 0], [0.0, 0.0, 0.0, 0.1, 0]]),),
                (np.array([[-H, 0.2, 0.0, 0.3, 0], [H, 0.0, -0.4, 0.0, 1], [0.0, 0.0, 0.2, 0.0, 0]]),),
            ),
            hidden=lambda rng: ref.standard_tables(rng, 5),
            reference=ref.standard_expected,
            judge_with=table_judge(standard_section="lecture 02 §8"),
            answer=modified_from_standard,
            forbidden=keys.KEY_TABLES,
            hint="Write both products for a two-joint chain and group the factors (lecture 02 §8): which joint's "
            "factors does Rot(X, α_1) Trans(X, a_1) follow in each? Check with the chain cell under question 3: both "
            "tables must give the same ⁰T_n at q = 0 and at one other q.",
        ),
    ),
    allowed=(),
)
