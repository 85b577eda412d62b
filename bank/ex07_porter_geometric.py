"""Exercise 7 (``solutions/ex07_porter_geometric.ipynb``): Porter's chain, the inverse problem by Ver.2.

The construction step by step (the plane's normal, the two elbow points, the signed angle), then
the modelling question: the parallel-planes pose, where the construction breaks down and Porter's
rule (the smallest stroke) picks one configuration from a circle of them.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from puma_course.grading.judge.compare import compare_solution_set
from puma_course.grading.judge.diagnose import DUPLICATES, angle_2pi, degrees_out, matches, matches_set, unit_axis_out
from puma_course.grading.judge.judges import stroke_judge
from puma_course.grading.spec import Exercise, Question

from . import _keys as keys
from ._formulas import porter_elbows, porter_normal
from ._inputs import unit_vectors
from ._reference import porter_chain as ref
from .ex05_porter_fk import PUBLIC_L, PUBLIC_L2, PUBLIC_Q, PUBLIC_Q2

PUBLIC_T = ref.porter_fk(PUBLIC_Q, *PUBLIC_L)
PUBLIC_T2 = ref.porter_fk(PUBLIC_Q2, *PUBLIC_L2)
PARALLEL_Q = np.array([0.7, 0.3, 1.2, 0.4, np.pi / 2, 0.5])
#: A second parallel-planes pose, where Porter's configuration has negative angles (α5 < 0).
PARALLEL_Q_BACK = np.array([-2.0, 0.3, 0.8, -2.2, np.pi / 2, -1.0])


def _angle_cases(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    """Cases (v, w, axis): the first with a positive angle, the others negative (where an unsigned angle
    is wrong), so the unsigned reading passes at most 2 of the 7 cases with the public ones."""
    out = []
    for k, axis in enumerate(unit_vectors(rng, n)):
        u = np.cross(axis, rng.normal(size=3))
        u /= np.linalg.norm(u)
        t = float(rng.uniform(-np.pi, np.pi))
        beta = float(rng.uniform(0.2, 3.0)) * (1.0 if k == 0 else -1.0)
        v, w = (
            float(s) * (np.cos(a) * u + np.sin(a) * np.cross(axis, u))
            for s, a in zip(rng.uniform(0.3, 2.0, 2), (t, t + beta), strict=True)
        )
        out.append((v, w, axis))
    return out


def normal_in_hand(T: Any, l1: float, l4: float) -> np.ndarray:
    """The arm plane's unit normal (along y1) written in the hand frame F5: ⁵n = R05ᵀ n."""
    return np.asarray(T, dtype=float)[:3, :3].T @ porter_normal(T, l1, l4)


def elbows_in_hand(T: Any, l1: float, l3: float, l4: float, rod: float | None = None) -> np.ndarray:
    """The two elbow candidates written in the hand frame F5: ⁵p3 = R05ᵀ (p3 - p5) (``rod``: the printed l4)."""
    T = np.asarray(T, dtype=float)
    return (porter_elbows(T, l1, l3, l4, rod) - T[:3, 3]) @ T[:3, :3]


IN_BASE = (
    "these are the base frame's coordinates; the question asks for them in the hand frame F5 (its origin p5, "
    "its axes the columns of R05): ⁵v = R05ᵀ v for a direction, R05ᵀ (p - p5) for a point (lecture 01 §5)"
)


def _unsigned(v: Any, w: Any, axis: Any) -> float:
    v, w = np.asarray(v, dtype=float), np.asarray(w, dtype=float)
    return float(np.arctan2(np.linalg.norm(np.cross(v, w)), v @ w))


EXERCISE = Exercise(
    "ex07_porter_geometric",
    "Porter's chain: the inverse problem, Ver.2 (geometric)",
    (
        Question(
            "q1",
            "arm_plane_normal",
            2,
            "the unit normal of the arm plane, pointing along y1, in the hand frame",
            public=((PUBLIC_T, 1.0, 0.3), (PUBLIC_T2, PUBLIC_L2[0], PUBLIC_L2[2])),
            hidden=lambda rng: [(T, l1, l4) for T, l1, _, l4 in ref.porter_poses(rng, 4)],
            reference=normal_in_hand,
            mistakes=(
                matches("frame_coordinates", IN_BASE, porter_normal),
                matches(
                    "printed_formula",
                    "your normal points along -y1: that is the printed order of the cross "
                    "product (lecture 07 step 2); the angles are measured about +y1",
                    lambda T, l1, l4: -normal_in_hand(T, l1, l4),
                ),
                unit_axis_out(3),
            ),
            hint="Which points span the arm plane, and which order of the cross product gives the joint axis y1 "
            "(lecture 07 step 2)? Compare with y1 of a configuration you know.",
        ),
        Question(
            "q2",
            "elbow_candidates",
            3,
            "the two candidates for the elbow point p3, in the hand frame",
            public=((PUBLIC_T, *PUBLIC_L), (PUBLIC_T2, *PUBLIC_L2)),
            hidden=lambda rng: ref.porter_poses(rng, 4),
            reference=elbows_in_hand,
            compare=compare_solution_set([]),
            mistakes=(
                matches_set("frame_coordinates", IN_BASE, porter_elbows),
                matches_set(
                    "printed_formula",
                    "your points are l4 from p4, as eq. (18) is printed; the rod from p3 to "
                    "p4 is l3 long (lecture 07 step 3)",
                    lambda T, l1, l3, l4: elbows_in_hand(T, l1, l3, l4, l4),
                ),
                DUPLICATES,
            ),
            hint="p3 lies in the arm plane, at the rod's length from p4, on a line perpendicular to x5: two points "
            "(lecture 07 step 3). Return a (2, 3) array, in any order.",
        ),
        Question(
            "q3",
            "signed_angle",
            2,
            "the signed angle from v to w about an axis",
            public=(
                ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
                ([1.0, 0.0, 0.0], [-1.0, -1.0, 0.0], [0.0, 0.0, 1.0]),
            ),
            hidden=lambda rng: _angle_cases(rng, 5),
            reference=ref.signed_angle,
            forbidden=keys.KEY_PORTER_IK,
            mistakes=(
                matches(
                    "unsigned_angle",
                    "your angle is the unsigned one, atan2(|v × w|, v · w), where the angle asked for is "
                    "negative: |v × w| is the unsigned reading of Porter's angle(); the sign comes from the "
                    "component of v × w along the axis (lecture 07 step 4)",
                    _unsigned,
                ),
                matches(
                    "sign_flip",
                    "your angle has the wrong sign: measured about -axis",
                    lambda v, w, axis: -ref.signed_angle(v, w, axis),
                ),
                degrees_out(),
                angle_2pi(where="(-π, π]"),
            ),
            hint="A quarter turn about +z takes e_x to e_y: +π/2; about -z it is -π/2. Return the angle in (-π, π].",
        ),
        Question(
            "q4",
            "porter_parallel_planes",
            4,
            "Porter's configuration when the planes are parallel",
            public=(
                (ref.porter_fk(PARALLEL_Q, *PUBLIC_L), *PUBLIC_L),
                (ref.porter_fk(PARALLEL_Q_BACK, *PUBLIC_L), *PUBLIC_L),
            ),
            hidden=lambda rng: ref.porter_parallel_cases(rng, 4),
            reference=ref.porter_parallel_expected,
            judge_with=stroke_judge(),
            answer=lambda T, *L: ref.porter_geometric(T, *L)[0],
            forbidden=keys.KEY_PORTER_IK,
            hint="Here n × x5 = 0, so step 3 gives no direction (lecture 07 step 6): which p3 on the circle does "
            "Porter's rule take, and what do the angles of step 4 need from it? Check your result with Porter(...).fk.",
        ),
    ),
    allowed=("puma_course.kinematics.porter:Porter",),
)
