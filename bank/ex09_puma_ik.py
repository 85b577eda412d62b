"""Exercise 9 (``solutions/ex09_puma_ik.ipynb``): inverse kinematics of the PUMA-560.

All solutions as a set (any order) and the one nearest a given configuration, graded on hidden
poses and lengths, three of them near a singularity (wrist 1e-5, stretched elbow 1e-4, shoulder
cylinder 1e-5), where a formula without care loses a branch or returns NaN; the modelling question
puts the robot on a base somewhere in a cell, with a tool: every configuration for a world pose.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from puma_course.grading.judge.judges import nearest_judge, solution_set_judge
from puma_course.grading.model import Exercise, Question

from . import _keys as keys
from ._formulas import nearest_row
from ._reference import chains
from ._reference import motion as ref

LECTURE = (0.4318, 0.0203, 0.15005, 0.4318)
Q_PUBLIC = np.radians([30.0, -50.0, 20.0, 40.0, 60.0, -30.0])  # lecture 09's example
T_PUBLIC = ref.puma_fk(Q_PUBLIC, *LECTURE)
B_PUBLIC = chains.pose(chains.elementary_rotation("z", np.pi / 2), [0.5, 0.0, 0.8])
#: A second public pose and base (the robot hung upside down from a gantry).
T_PUBLIC2 = ref.puma_fk(np.array([-1.2, -0.6, 0.4, -0.9, 1.1, 2.0]), *LECTURE)
B_PUBLIC2 = chains.pose(chains.elementary_rotation("x", np.pi), [1.0, -0.5, 2.2])


def _arm_cases(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    return [(T[:3, 3], *L) for T, *L in ref.puma_cases(rng, n)]


def _solutions(expected: dict[str, Any]) -> np.ndarray:
    return np.asarray(expected["solutions"])


EXERCISE = Exercise(
    "ex09_puma_ik",
    "Inverse kinematics of the PUMA-560",
    (
        Question(
            "q1",
            "puma_arm_angles",
            3,
            "the four (θ1, θ2, θ3) putting the wrist centre at p",
            public=((T_PUBLIC[:3, 3], *LECTURE), (T_PUBLIC2[:3, 3], *LECTURE)),
            hidden=lambda rng: _arm_cases(rng, 4),
            reference=ref.puma_arm_expected,
            judge_with=solution_set_judge(),
            answer=lambda p, *L: _solutions(ref.puma_arm_expected(p, *L)),
            forbidden=keys.KEY_PUMA_IK,
            hint="Two shoulders times two elbows (lecture 09 §2-4); check each row by putting it into the forward "
            "kinematics with θ4 = θ5 = θ6 = 0.",
        ),
        Question(
            "q2",
            "puma_ik",
            5,
            "every configuration reaching a pose",
            public=((T_PUBLIC, *LECTURE), (T_PUBLIC2, *LECTURE)),
            hidden=lambda rng: ref.puma_cases(rng, 5),
            reference=ref.puma_ik_expected,
            judge_with=solution_set_judge(),
            answer=lambda T, *L: _solutions(ref.puma_ik_expected(T, *L)),
            forbidden=keys.KEY_PUMA_IK,
            hint="Near a singularity a square root of a tiny negative number gives NaN and sin θ5 is tiny: check "
            "your function on poses 1e-5 away from each singularity of lecture 09 §8, with Puma560(...).fk.",
        ),
        Question(
            "q3",
            "puma_ik_nearest",
            3,
            "the solution nearest a given configuration",
            public=(
                (T_PUBLIC, Q_PUBLIC + 0.05, *LECTURE),
                (T_PUBLIC, np.array([3.1, 1.0, 2.9, -3.1, 2.4, 0.9]), *LECTURE),
            ),
            hidden=lambda rng: ref.puma_nearest_cases(rng, 4),
            reference=ref.puma_nearest_expected,
            judge_with=nearest_judge(),
            answer=lambda T, q_ref, *L: nearest_row(_solutions(ref.puma_nearest_expected(T, q_ref, *L)), q_ref),
            forbidden=(*keys.KEY_PUMA_IK, *keys.KEY_NEAREST),
            hint="Distance between configurations as lecture 10 §2 defines it: 179° and -179° are 2° apart.",
        ),
        Question(
            "q4",
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
