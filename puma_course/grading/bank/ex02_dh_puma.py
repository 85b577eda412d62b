"""Exercise 2 (``solutions/ex02_dh_puma.ipynb``): the DH link matrix and the PUMA-560 forward kinematics."""

from __future__ import annotations

import numpy as np

from ..model import Exercise, Question
from . import _reference as ref
from ._inputs import angles

EXERCISE = Exercise(
    "ex02_dh_puma",
    "The DH link matrix and the PUMA-560 forward kinematics",
    (
        Question(
            "q1",
            "link_matrix",
            3,
            "Craig's modified DH link matrix",
            public=((0.0, 0.0, 0.3, 0.0), (-np.pi / 2, 0.0, 0.5, 0.2), (np.pi / 2, 0.4, -1.0, 0.15)),
            hidden=lambda rng: [
                tuple(float(x) for x in row)
                for row in np.column_stack(
                    [
                        rng.choice([-np.pi / 2, 0.0, np.pi / 2, 0.7], 5),
                        rng.uniform(-1, 1, 5),
                        rng.uniform(-np.pi, np.pi, 5),
                        rng.uniform(-1, 1, 5),
                    ]
                )
            ],
            reference=ref.mdh,
            forbidden=ref.KEY_MDH,
            hint="Multiply Rot(X, α) Trans(X, a) Rot(Z, θ) Trans(Z, d) in that order.",
        ),
        Question(
            "q2",
            "puma_fk",
            4,
            "PUMA-560 forward kinematics ^0T_6",
            public=((np.zeros(6),), (np.array([0.0, -np.pi / 2, -np.pi / 2, 0, 0, 0]),)),
            hidden=lambda rng: angles(rng, 5, 6),
            reference=ref.puma_fk,
            forbidden=ref.KEY_PUMA,
            hint="Use the lecture's table with a2 = 0.4318, a3 = 0.0203, d3 = 0.15005, d4 = 0.4318 (metres).",
        ),
        Question(
            "q3",
            "puma_frames",
            2,
            "all PUMA-560 frames ^0T_i, i = 0..6",
            public=((np.zeros(6),),),
            hidden=lambda rng: angles(rng, 3, 6),
            reference=ref.puma_frames,
            forbidden=ref.KEY_PUMA,
            hint="Return a (7, 4, 4) array starting with the identity (frame {0}) and ending with ^0T_6.",
        ),
    ),
    allowed=(),  # the self-check only: mdh and the PUMA-560 are the answers
)
