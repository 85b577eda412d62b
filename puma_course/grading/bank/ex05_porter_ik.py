"""Exercise 5 (``solutions/ex05_porter_ik.ipynb``): Porter's chain, the inverse problem."""

from __future__ import annotations

import numpy as np

from ..compare import compare_solution_set
from ..model import Exercise, Question
from . import _reference as ref
from .ex04_porter_fk import PUBLIC_L, PUBLIC_Q

#: Joint columns that are angles (compared modulo 2π); column 2 is the slide q2.
ANGLE_COLUMNS = [0, 1, 3, 4, 5]

EXERCISE = Exercise(
    "ex05_porter_ik",
    "Porter's chain: the inverse problem",
    (
        Question(
            "q1",
            "porter_p4",
            2,
            "the wrist point p4 from the end-effector pose",
            public=((np.array([[0.0, -1, 0, 1], [1, 0, 0, 2], [0, 0, 1, 3], [0, 0, 0, 1]]), 0.5),),
            hidden=lambda rng: [(T, l4) for T, _, _, l4 in ref.porter_poses(rng, 4)],
            reference=ref.porter_wrist_point,
            hint="The last link runs along x5 with length l4, so p4 = p5 - l4 x5.",
        ),
        Question(
            "q2",
            "porter_ik",
            6,
            "every configuration reaching F05 (Ver.1, explicit)",
            public=(ref.porter_pose(PUBLIC_Q, *PUBLIC_L),),
            hidden=lambda rng: ref.porter_poses(rng, 5),
            reference=ref.porter_ik_explicit,
            compare=compare_solution_set(ANGLE_COLUMNS, tol=1e-6),
            forbidden=ref.KEY_PORTER_IK,
            hint="In general position there are four configurations with q2 >= 0: α1 and α1 + π, times the two "
            "solutions of eq. 10 for α4. Return them as a (4, 6) array, angles in [0, 2π).",
        ),
        Question(
            "q3",
            "porter_ik_geometric",
            3,
            "bonus: Porter's Ver.2 (geometric) pair",
            public=(ref.porter_pose(PUBLIC_Q, *PUBLIC_L),),
            hidden=lambda rng: ref.porter_poses(rng, 4),
            reference=ref.porter_ik_geometric,
            compare=compare_solution_set(ANGLE_COLUMNS, tol=1e-6),
            forbidden=ref.KEY_PORTER_IK,
            hint="Keep the arm plane α1 = atan2(p4_y, p4_x) and the two elbow points p3 = p4 ± l3 z4; "
            "return a (2, 6) array.",
            bonus=True,
        ),
    ),
    allowed=(),  # the self-check only: Porter is the answer
)
