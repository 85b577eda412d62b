"""Exercise 9 (``solutions/ex09_puma_ik.ipynb``): inverse kinematics of the PUMA-560, and its singular poses.

Every question counts the joints as the controller does (ex03 q2: θ2 and θ3 from the arm straight up), so
the lecture's printed formulas, which give the lecture's joint values, put the arm elsewhere (issue 22: no
question is answered by transcribing a lecture cell). All solutions as a set (any order), graded on hidden
poses and lengths, three of them near a singularity (wrist 1e-5, stretched elbow 1e-4, shoulder cylinder
1e-5), where a formula without care loses a branch or returns NaN; det J and the direction the wrist centre
cannot move at a singular pose (lecture 09 §9); the modelling question puts the robot on a base somewhere in
a cell, with a tool: every configuration for a world pose.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from puma_course.grading.judge.diagnose import SIGN_FLIP, matches, negated, unit_axis_out
from puma_course.grading.judge.judges import solution_set_judge
from puma_course.grading.spec import Exercise, Question

from . import _keys as keys
from ._reference import chains
from ._reference import motion as ref

LECTURE = (0.4318, 0.0203, 0.15005, 0.4318)
Q_LECTURE = np.radians([30.0, -50.0, 20.0, 40.0, 60.0, -30.0])  # lecture 09's example (the lecture's zero)
Q_PUBLIC = ref.to_upright(Q_LECTURE[None])[0]  # the same arm in the controller's joint values
T_PUBLIC = ref.puma_fk(Q_LECTURE, *LECTURE)
#: The public bases: near the cell's origin, so that each usual mistake (the base forgotten or on the wrong side,
#: the tool left out or added) asks for a pose the arm reaches, and is named.
B_PUBLIC = chains.pose(chains.elementary_rotation("z", np.pi / 2), [0.3, 0.0, 0.2])
#: A second public pose and base (the robot hung upside down from a gantry).
T_PUBLIC2 = ref.puma_fk(np.array([-1.2, -0.6, 0.4, -0.9, 1.1, 2.0]), *LECTURE)
B_PUBLIC2 = chains.pose(chains.elementary_rotation("x", np.pi), [0.2, 0.1, 0.3])
#: Two singular arms of lecture 09 §8 in the controller's joint values: the stretched elbow and the shoulder.
Q_ELBOW = ref.to_upright(np.array([[0.5, -0.3, np.arctan2(-0.4318, 0.0203), 0.2, 1.0, 0.1]]))[0]
Q_SHOULDER = ref.to_upright(np.array([[0.2, np.arctan2(0.4318 + 0.0203 * np.cos(0.4) - 0.4318 * np.sin(0.4),
                                                       0.0203 * np.sin(0.4) + 0.4318 * np.cos(0.4)),
                                       0.4, 0.5, 0.7, -0.3]]))[0]  # fmt: skip

ZERO = (
    "your answer is right for the lecture's joint values: this exercise counts θ2 and θ3 from the arm straight up "
    "(the controller's zero of ex03 q2), so θ_lecture = θ - π/2 for joints 2 and 3"
)


def _arm_cases(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    return [(T[:3, 3], *L) for T, *L in ref.puma_cases(rng, n)]


def _solutions(expected: dict[str, Any]) -> np.ndarray:
    return np.asarray(expected["solutions"])


def _lecture_det(q: Any, a2: float, a3: float, d3: float, d4: float) -> float:
    """The mistake: det J with the controller's q used as the lecture's."""
    return ref.puma_det_j(np.asarray(q, dtype=float) - chains.PUMA_ZERO, a2, a3, d3, d4)


def _lecture_direction(q: Any, a2: float, a3: float, d3: float, d4: float) -> np.ndarray:
    """The mistake: the lost direction with the controller's q used as the lecture's."""
    return ref.puma_lost_direction(np.asarray(q, dtype=float) - chains.PUMA_ZERO, a2, a3, d3, d4)


def _lecture_radial(horizontal: bool) -> Any:
    """The mistake: the direction of the wrist centre (from the base origin, or from the base axis if
    ``horizontal``) with the controller's q used as the lecture's, the arm then not singular at all."""

    def wrong(q: Any, a2: float, a3: float, d3: float, d4: float) -> np.ndarray:
        p = ref.puma_fk(np.asarray(q, dtype=float), a2, a3, d3, d4)[:3, 3]
        u = np.array([p[0], p[1], 0.0]) if horizontal else p
        return u / np.linalg.norm(u)

    return wrong


EXERCISE = Exercise(
    "ex09_puma_ik",
    "Inverse kinematics of the PUMA-560",
    (
        Question(
            "q1",
            "puma_arm_angles",
            3,
            "the four (θ1, θ2, θ3), the controller's, putting the wrist centre at p",
            public=((T_PUBLIC[:3, 3], *LECTURE), (T_PUBLIC2[:3, 3], *LECTURE)),
            hidden=lambda rng: _arm_cases(rng, 4),
            reference=ref.puma_arm_upright_expected,
            judge_with=solution_set_judge(),
            answer=lambda p, *L: _solutions(ref.puma_arm_upright_expected(p, *L)),
            forbidden=keys.KEY_PUMA_IK,
            hint="Two shoulders times two elbows (lecture 09 §2-4) give the lecture's joint values; then count θ2 "
            "and θ3 from the arm straight up. Check each row with Puma560(...).fk(q + (0, -π/2, -π/2, 0, 0, 0)).",
        ),
        Question(
            "q2",
            "puma_ik",
            4,
            "every configuration (the controller's joint values) reaching a pose",
            public=((T_PUBLIC, *LECTURE), (T_PUBLIC2, *LECTURE)),
            hidden=lambda rng: ref.puma_cases(rng, 5),
            reference=ref.puma_ik_upright_expected,
            judge_with=solution_set_judge(),
            answer=lambda T, *L: _solutions(ref.puma_ik_upright_expected(T, *L)),
            forbidden=keys.KEY_PUMA_IK,
            hint="Near a singularity a square root of a tiny negative number gives NaN and sin θ5 is tiny: check "
            "your function on poses 1e-5 away from each singularity of lecture 09 §8; the arm straight up is q = 0.",
        ),
        Question(
            "q3",
            "puma_det_j",
            2,
            "det J at a configuration (the controller's joint values)",
            public=((Q_PUBLIC, *LECTURE), (np.array([0.3, 0.2, -0.4, 0.1, 0.9, 0.5]), *LECTURE), (Q_ELBOW, *LECTURE)),
            hidden=lambda rng: ref.puma_det_cases(rng, 5),
            reference=ref.puma_det_j,
            forbidden=keys.KEY_JACOBIAN,
            mistakes=(
                matches("joint_zero", ZERO, _lecture_det),
                matches(
                    "missing_factor",
                    "this is det J_w, the arm's 3×3 block, alone: det J is det J_w times the wrist's factor "
                    "sin θ5 (det [z4 z5 z6], lecture 09 §9), zero at the wrist singularity",
                    lambda q, *L: ref.puma_det_j(q, *L) / np.sin(float(np.asarray(q, dtype=float)[4])),
                ),
                negated(
                    "sign_flip",
                    "your det J has the wrong sign (the rest is right). If you stacked J's rows as (ω, v), the "
                    "angular rows first: the course's J has the linear velocity v on top, J = (J_v; J_ω), and "
                    "swapping the two blocks of three rows flips the determinant's sign. Otherwise check the sign "
                    "of each factor",
                ),
            ),  # fmt: skip
            hint="det J is a product of factors, each zero at one singularity (lecture 09 §9); check yours is 0 with "
            "the wrist straight (θ5 = 0) and at the stretched elbow, and that it changes sign across them.",
        ),
        Question(
            "q4",
            "puma_lost_direction",
            2,
            "the direction the wrist centre cannot move at a singular arm",
            public=((Q_ELBOW, *LECTURE), (Q_SHOULDER, *LECTURE)),
            hidden=lambda rng: ref.puma_singular_cases(rng, 4),
            reference=ref.puma_lost_direction,
            forbidden=keys.KEY_JACOBIAN,
            mistakes=(
                matches("joint_zero", ZERO, _lecture_direction),
                matches("joint_zero", ZERO, _lecture_radial(False)),
                matches("joint_zero", ZERO, _lecture_radial(True)),
                unit_axis_out(3, "direction"),
                negated(
                    "sign_flip",
                    "your direction points the wrong way: the question asks for the unit vector u "
                    "with u · p > 0 (p the wrist centre)",
                ),
                SIGN_FLIP,
            ),  # fmt: skip
            hint="At each singular arm ask which motion of the wrist centre the three arm joints cannot make to first "
            "order (lecture 09 §9): stretched, it cannot move away from the base origin; on the shoulder cylinder, "
            "not away from the base axis. A unit vector, pointing away from the base.",
        ),
        Question(
            "q5",
            "puma_ik_world",
            4,
            "every configuration putting the tool at a pose of the cell",
            public=(
                (B_PUBLIC @ T_PUBLIC @ chains.tz(0.1), B_PUBLIC, 0.1),
                (B_PUBLIC2 @ T_PUBLIC2 @ chains.tz(0.15), B_PUBLIC2, 0.15),
            ),
            hidden=lambda rng: ref.puma_world_cases(rng, 4),
            reference=ref.puma_world_expected,
            judge_with=solution_set_judge(),
            answer=lambda T, B, d6: _solutions(ref.puma_world_expected(T, B, d6)),
            forbidden=keys.KEY_PUMA_IK,
            hint="Write the tool's pose in the cell as a product of B, ⁰T₆ and the tool's offset (lecture 01 §5), "
            "solve it for ⁰T₆, then use your q2 with the lecture's lengths.",
        ),
    ),
    allowed=("puma_course.kinematics.puma560:Puma560", "puma_course.transforms:inverse_transform"),
)
