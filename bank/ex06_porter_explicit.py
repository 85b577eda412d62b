"""Exercise 6 (``solutions/ex06_porter_explicit.ipynb``): Porter's chain, the inverse problem by Ver.1.

All configurations as a set (any order), graded on hidden poses including near-singular ones
(c4 within 1e-4 of 0, c1 = 0 where the printed formulas divide by zero, a stroke of 1e-3); the
modelling question puts a tool on the hand: find every configuration for a tool pose.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from puma_course.grading.judge.diagnose import matches
from puma_course.grading.judge.judges import nearest_judge, solution_set_judge
from puma_course.grading.model import Exercise, Question

from . import _keys as keys
from ._formulas import porter_wrist_point
from ._formulas import wrapped_nearest as nearest_row
from ._reference import chains
from ._reference import porter_chain as ref
from .ex05_porter_fk import PUBLIC_L, PUBLIC_L2, PUBLIC_Q, PUBLIC_Q2

TOOL = chains.pose(chains.elementary_rotation("y", 0.4), [0.1, 0.0, 0.05])


def _point(axis: int, sign: float) -> Any:
    return lambda T, l4: np.asarray(T, dtype=float)[:3, 3] + sign * l4 * np.asarray(T, dtype=float)[:3, axis]


def _tool_cases(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    out = []
    for (T, *L), R in zip(ref.porter_poses(rng, n), chains.random_rotations(rng, n), strict=True):
        E = chains.pose(R, rng.uniform(-0.2, 0.2, 3))
        out.append((T @ E, *L, E))
    return out


EXERCISE = Exercise(
    "ex06_porter_explicit",
    "Porter's chain: the inverse problem, Ver.1 (explicit)",
    (
        Question(
            "q1",
            "porter_wrist_point",
            2,
            "the wrist point p4 from the hand frame",
            public=(
                (ref.porter_fk(PUBLIC_Q, *PUBLIC_L), PUBLIC_L[2]),
                (ref.porter_fk(PUBLIC_Q2, *PUBLIC_L2), PUBLIC_L2[2]),
            ),
            hidden=lambda rng: [(T, l4) for T, _, _, l4 in ref.porter_poses(rng, 4)],
            reference=porter_wrist_point,
            mistakes=(
                matches("wrong_axis", "you moved along y5: the l4 rod lies along the hand's x axis", _point(1, -1.0)),
                matches("wrong_axis", "you moved along z5: the l4 rod lies along the hand's x axis", _point(2, -1.0)),
                matches("offset_sign", "p5 is l4 *beyond* p4 along x5: going back means subtracting", _point(0, 1.0)),
            ),
            hint="Which rod ends at p5, and along which axis of F5 does it lie (lecture 05 §1)?",
        ),
        Question(
            "q2",
            "porter_ik",
            5,
            "every configuration reaching F05 (Ver.1)",
            public=(
                (ref.porter_fk(PUBLIC_Q, *PUBLIC_L), *PUBLIC_L),
                (ref.porter_fk(PUBLIC_Q2, *PUBLIC_L2), *PUBLIC_L2),
            ),
            hidden=lambda rng: ref.porter_poses(rng, 5, near_singular=True),
            reference=ref.porter_ik_expected,
            judge_with=solution_set_judge(),
            answer=lambda T, *L: ref.porter_ik_expected(T, *L)["solutions"],
            forbidden=keys.KEY_PORTER_IK,
            hint="Count the solutions before computing them (lecture 06, 'four, not eight'); where a printed formula "
            "divides, ask whether the pose or only the formula is special, and prefer atan2 of two terms.",
        ),
        Question(
            "q3",
            "porter_ik_tool",
            3,
            "every configuration putting a tool at a pose",
            public=(
                (ref.porter_fk(PUBLIC_Q, *PUBLIC_L) @ TOOL, *PUBLIC_L, TOOL),
                (ref.porter_fk(PUBLIC_Q2, *PUBLIC_L2) @ TOOL, *PUBLIC_L2, TOOL),
            ),
            hidden=lambda rng: _tool_cases(rng, 4),
            reference=ref.porter_tool_ik_expected,
            judge_with=solution_set_judge(),
            answer=lambda T, l1, l3, l4, E: ref.porter_tool_ik_expected(T, l1, l3, l4, E)["solutions"],
            forbidden=keys.KEY_PORTER_IK,
            hint="Write the tool's pose as a product of F05 and E (lecture 01 §5: which frame is described in which) "
            "and solve it for F05 before you call your q2.",
        ),
        Question(
            "q4",
            "porter_ik_nearest",
            3,
            "bonus: the configuration nearest the previous one",
            public=(
                (ref.porter_fk(PUBLIC_Q, *PUBLIC_L), *PUBLIC_L, PUBLIC_Q + 0.05),
                (ref.porter_fk(PUBLIC_Q2, *PUBLIC_L2), *PUBLIC_L2, PUBLIC_Q2 - 0.05),
            ),
            hidden=lambda rng: ref.porter_nearest_cases(rng, 4),
            reference=ref.porter_nearest_expected,
            judge_with=nearest_judge(),
            answer=lambda T, l1, l3, l4, q: nearest_row(ref.porter_nearest_expected(T, l1, l3, l4, q)["solutions"], q),
            forbidden=(*keys.KEY_PORTER_IK, *keys.KEY_NEAREST),
            hint="The distance of lecture 10 §2 wraps angle differences; the stroke q2 is a length, not an angle.",
            bonus=True,
        ),
    ),
    allowed=("puma_course.kinematics.porter:Porter", "puma_course.transforms:inverse_transform"),
)
