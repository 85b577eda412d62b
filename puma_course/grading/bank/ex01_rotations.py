"""Exercise 1 (``solutions/ex01_rotations.ipynb``): rotations and Rodrigues' formula."""

from __future__ import annotations

import numpy as np

from ..model import Exercise, Question
from . import _reference as ref

EXERCISE = Exercise(
    "ex01_rotations",
    "Rotations and Rodrigues' formula",
    (
        Question(
            "q1",
            "elementary_rotation",
            2,
            "rotation about a coordinate axis",
            public=(("x", 0.3), ("y", -1.2), ("z", np.pi / 2)),
            hidden=lambda rng: [(ax, float(t)) for ax, t in zip("xyzxyz", rng.uniform(-np.pi, np.pi, 6), strict=True)],
            reference=ref.elementary_rotation,
            forbidden=ref.KEY_ROT,
            hint="Each column of R is where the rotation sends e_x, e_y, e_z; check the sign of the sines.",
        ),
        Question(
            "q2",
            "rodrigues_formula",
            3,
            "Rodrigues' formula K(a, θ)",
            public=(([0.0, 0.0, 1.0], 0.4), ([1.0, 1.0, 0.0], 2.0), ([0.0, 3.0, 0.0], -0.7)),
            hidden=lambda rng: [
                (list(rng.normal(size=3) * rng.uniform(0.5, 3)), float(t)) for t in rng.uniform(-3, 3, 5)
            ],
            reference=ref.rodrigues,
            forbidden=ref.KEY_RODRIGUES,
            hint="Normalise the axis first; K = I + sin θ [k]x + (1 - cos θ) [k]x².",
        ),
        Question(
            "q3",
            "axis_angle_from_matrix",
            3,
            "axis and angle of a rotation matrix",
            public=(
                (np.round(ref.elementary_rotation("x", 0.5), 15),),
                (np.array([[0.0, -1, 0], [1, 0, 0], [0, 0, 1]]),),
            ),
            hidden=lambda rng: [(R,) for R in ref.random_rotations(rng, 5)],
            reference=ref.axis_angle,
            forbidden=ref.KEY_AXIS_ANGLE,
            hint="cos θ = (trace R - 1) / 2 and the axis comes from the antisymmetric part R - R^T; "
            "return [kx, ky, kz, θ] with θ in (0, π).",
        ),
        Question(
            "q4",
            "invert_transform",
            2,
            "inverse of a homogeneous transform",
            public=((np.array([[0.0, -1, 0, 1], [1, 0, 0, 2], [0, 0, 1, 3], [0, 0, 0, 1]]),),),
            hidden=lambda rng: ref.random_transforms(rng, 4),
            reference=ref.inverse_transform,
            forbidden=ref.KEY_INVERSE,
            hint="The inverse rotation is R^T and the inverse translation is -R^T p.",
        ),
    ),
    allowed=(),  # the self-check only: rotx ... rodrigues, axis_angle, inverse_transform are the answers
)
