"""Exercise 6 (``solutions/ex06_porter_explicit.ipynb``): Porter's chain, the inverse problem by Ver.1.

Question 1, the wrist point, is asked for a hand holding a tool (lecture 06 prints p4 = p5 - l4 x5 of the
hand frame itself). All configurations as a set (any order). Question 2 is a variant of lecture 06's chain,
so that copying the lecture's steps does not answer it: a telescopic rod, a fixed part l2 plus the stroke
q2 >= 0, so only the configurations whose rod is at least l2 long remain; graded on hidden poses including
near-singular ones (c4 within 1e-4 of 0, c1 = 0 where the printed formulas divide by zero, a stroke of 1e-3).
The modelling question puts a tool on Porter's hand: find every configuration for a tool pose. The bonus
decides reachability with a stroke limit (lecture 06 §5), where the answer may be no configuration at all.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from puma_course.grading.judge.diagnose import matches
from puma_course.grading.judge.judges import solution_set_judge
from puma_course.grading.spec import Exercise, Question

from . import _keys as keys
from ._formulas import porter_wrist_point
from ._reference import chains
from ._reference import porter_chain as ref
from .ex05_porter_fk import PUBLIC_L, PUBLIC_L2, PUBLIC_Q, PUBLIC_Q2

TOOL = chains.pose(chains.elementary_rotation("y", 0.4), [0.1, 0.0, 0.05])


def _point(axis: int, sign: float) -> Any:
    def wrong(T_tool: Any, l4: float, E: Any) -> np.ndarray:
        F = np.asarray(T_tool, dtype=float) @ np.linalg.inv(np.asarray(E, dtype=float))
        return F[:3, 3] + sign * l4 * F[:3, axis]

    return wrong


def _hand_at(which: str) -> Any:
    """The wrist point of a hand frame put at the wrong place: T_tool itself, T_tool E, or E⁻¹ T_tool."""

    def wrong(T_tool: Any, l4: float, E: Any) -> np.ndarray:
        T, E = np.asarray(T_tool, dtype=float), np.asarray(E, dtype=float)
        F = {"tool": T, "right": T @ E, "left": np.linalg.inv(E) @ T}[which]
        return porter_wrist_point(F, l4)

    return wrong


WRONG_SIDE = "you composed the tool on the wrong side: the tool frame is F05 E, so the hand frame is F05 = T_tool E⁻¹"


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
            "porter_tool_wrist_point",
            2,
            "the wrist point p4 of a hand holding a tool",
            public=(
                (ref.porter_fk(PUBLIC_Q, *PUBLIC_L) @ TOOL, PUBLIC_L[2], TOOL),
                (ref.porter_fk(PUBLIC_Q2, *PUBLIC_L2) @ TOOL, PUBLIC_L2[2], TOOL),
            ),
            hidden=lambda rng: [(T, l4, E) for T, _, _, l4, E in _tool_cases(rng, 4)],
            reference=ref.porter_tool_wrist_point,
            mistakes=(
                matches(
                    "tool_frame",
                    "this is the wrist point of a hand frame at T_tool; the hand holds the tool, whose frame is "
                    "F05 E: the hand frame is F05 = T_tool E⁻¹",
                    _hand_at("tool"),
                ),
                matches("order", WRONG_SIDE, _hand_at("right")),
                matches("order", WRONG_SIDE, _hand_at("left")),
                matches("wrong_axis", "you moved along y5: the l4 rod lies along the hand's x axis", _point(1, -1.0)),
                matches("wrong_axis", "you moved along z5: the l4 rod lies along the hand's x axis", _point(2, -1.0)),
                matches("offset_sign", "p5 is l4 *beyond* p4 along x5: going back means subtracting", _point(0, 1.0)),
            ),
            hint="Find the hand frame F05 first (the tool's frame is F05 E, lecture 01 §5); then: which rod ends at "
            "p5, and along which axis of F5 does it lie (lecture 05 §1)?",
        ),
        Question(
            "q2",
            "porter_rod_ik",
            5,
            "every configuration of the chain with a telescopic rod (Ver.1)",
            public=(
                (ref.porter_fk(PUBLIC_Q, *PUBLIC_L), PUBLIC_L[0], 1.6, *PUBLIC_L[1:]),
                (ref.porter_fk(PUBLIC_Q2, *PUBLIC_L2), PUBLIC_L2[0], 0.2, *PUBLIC_L2[1:]),
            ),
            hidden=lambda rng: ref.porter_rod_poses(rng, 5),
            reference=ref.porter_rod_ik_expected,
            judge_with=solution_set_judge(),
            answer=lambda T, *L: ref.porter_rod_ik_expected(T, *L)["solutions"],
            forbidden=keys.KEY_PORTER_IK,
            hint="Where does l2 enter eqs. (13)-(15) (lecture 06 (d)-(e))? Count the configurations before computing "
            "them (lecture 06, 'four, not eight'): which of them can this rod take? Where a printed formula divides, "
            "ask whether the pose or only the formula is special, and prefer atan2 of two terms.",
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
            "and solve it for F05 before you call your q2 (with l2 = 0 it is Porter's own chain).",
        ),
        Question(
            "q4",
            "porter_ik_limited",
            3,
            "bonus: every configuration within a stroke limit, or none",
            public=(
                (ref.porter_fk(PUBLIC_Q, *PUBLIC_L), *PUBLIC_L, 1.5),
                (ref.porter_fk(PUBLIC_Q, *PUBLIC_L), *PUBLIC_L, 1.0),
            ),
            hidden=lambda rng: ref.porter_limited_poses(rng, 4),
            reference=ref.porter_limited_expected,
            judge_with=solution_set_judge(),
            answer=lambda T, l1, l3, l4, m: ref.porter_limited_expected(T, l1, l3, l4, m)["solutions"],
            forbidden=keys.KEY_PORTER_IK,
            hint="A real slide has a stroke 0 <= q2 <= q2_max (lecture 06 §5): which of the four configurations "
            "does this one allow? An unreachable pose is an answer: no configuration, an array of shape (0, 6).",
            bonus=True,
        ),
    ),
    allowed=("puma_course.kinematics.porter:Porter", "puma_course.transforms:inverse_transform"),
)
