"""Exercise 6 (``solutions/ex06_three_step.ipynb``): the three-step inverse kinematics (wrist frame)."""

from __future__ import annotations

import numpy as np

from ..compare import compare_angles
from ..model import Exercise, Question
from . import _reference as ref
from ._inputs import reachable_wrist_points

W = np.array([0.5, 0.5, 2.0])
W_BEHIND = np.array([-0.5, -0.5, 2.0])  # same ratio w_y / w_x: a self-check that catches arctan(w_y / w_x)
TARGET = np.diag([-1.0, 1.0, -1.0])
LENGTHS = (1.5, 1.0)

EXERCISE = Exercise(
    "ex06_three_step",
    "The three-step inverse kinematics of a PUMA with a spherical wrist",
    (
        Question(
            "q1",
            "base_angle",
            2,
            "(a) the base angle θ0",
            public=((W,), (W_BEHIND,)),
            hidden=lambda rng: [(w,) for w, _, _ in reachable_wrist_points(rng, 5)],
            reference=ref.three_step_solution("theta0"),
            compare=compare_angles,
            forbidden=ref.KEY_THREE_STEP,
            hint="Use np.arctan2(w_y, w_x): the ratio w_y / w_x alone loses the quadrant.",
        ),
        Question(
            "q2",
            "step1_frame",
            2,
            "(a) the wrist frame after step 1",
            public=((W,), (W_BEHIND,)),
            hidden=lambda rng: [(w,) for w, _, _ in reachable_wrist_points(rng, 4)],
            reference=ref.three_step_solution("frame_step1"),
            forbidden=ref.KEY_THREE_STEP,
            hint="Starting from the straight arm the wrist frame is the identity; turn it by K(e_z, δ0).",
        ),
        Question(
            "q3",
            "arm_angles",
            3,
            "(b) θ, θ1 and θ2 (elbow up)",
            public=((W, *LENGTHS),),
            hidden=lambda rng: reachable_wrist_points(rng, 5),
            reference=ref.three_step_solution("theta", "theta1", "theta2"),
            compare=compare_angles,
            forbidden=ref.KEY_THREE_STEP,
            hint="θ1 = φ + θ with φ the elevation of w; the elbow bends back by θ2 = -(π - β), "
            "β the triangle's angle at the elbow.",
        ),
        Question(
            "q4",
            "step2_frame",
            2,
            "(b) the wrist frame after step 2",
            public=((W, *LENGTHS),),
            hidden=lambda rng: reachable_wrist_points(rng, 4),
            reference=ref.three_step_solution("frame_step2"),
            forbidden=ref.KEY_THREE_STEP,
            hint="Turn the step-1 frame by K(a, δ) with a = (sin θ0, -cos θ0, 0) and δ = θ1 + θ2.",
        ),
        Question(
            "q5",
            "wrist_rotation",
            3,
            "(c) the composite wrist rotation",
            public=((W, TARGET, *LENGTHS),),
            hidden=lambda rng: [
                (w, R, l1, l2)
                for (w, l1, l2), R in zip(reachable_wrist_points(rng, 4), ref.random_rotations(rng, 4), strict=True)
            ],
            reference=ref.three_step_solution("K_wrist"),
            forbidden=ref.KEY_THREE_STEP,
            hint="You need the rotation K with K F2 = F (F2 the step-2 frame, F the target); "
            "F2 is orthogonal, so its inverse is its transpose.",
        ),
    ),
    allowed=("puma_course.transforms:rodrigues",),  # the solution builds its frames with K(a, θ)
)
