"""Exercise 1 (``solutions/ex01_rotations.ipynb``): rotations and Rodrigues' formula.

Its first four questions (names, points, cases) are pinned by the hostile-submission fixtures of the
grader's tests; what changed with the mistake diagnosis is how a wrong answer is worded. Question 5
is the modelling question: the pose of a camera on a pan-tilt head, from a description in words.
"""

from __future__ import annotations

import numpy as np

from puma_course.grading.judge.diagnose import (
    SIGN_FLIP,
    TRANSLATION,
    TRANSPOSED,
    angle_2pi,
    degrees_in,
    degrees_out,
    matches,
    negated,
    unit_axis_out,
)
from puma_course.grading.model import Exercise, Question

from . import _keys as keys
from ._formulas import camera_fixed_axes, camera_head_frame, rodrigues_unnormalised
from ._reference import chains as ref

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
            forbidden=keys.KEY_ROT,
            mistakes=(TRANSPOSED, degrees_in(1), SIGN_FLIP),
            hint="Each column of R is where the rotation sends e_x, e_y, e_z (lecture 01 §1): check your columns "
            "with a quarter turn, whose images you can draw.",
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
            forbidden=keys.KEY_RODRIGUES,
            mistakes=(
                matches(
                    "unnormalised",
                    "the axis was not normalised: K(a, θ) needs the unit vector k = a/|a|",
                    rodrigues_unnormalised,
                ),
                TRANSPOSED,
                degrees_in(1),
                SIGN_FLIP,
            ),
            hint="Two checks by hand (lecture 01 §2): the axis does not move, K k = k, and a turn about e_z must "
            "be your rotation about z of question 1.",
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
            forbidden=keys.KEY_AXIS_ANGLE,
            mistakes=(
                degrees_out([3]),
                angle_2pi([3], "(0, π)"),
                unit_axis_out(3),
                negated(
                    "range",
                    "(-k, -θ) is the same rotation as (k, θ), but the question asks for 0 < θ < π: flip both signs",
                ),
            ),
            hint="The trace gives cos θ and the antisymmetric part R - Rᵀ gives sin θ times the axis (lecture 01 §3); "
            "return a unit axis and 0 < θ < π.",
        ),
        Question(
            "q4",
            "invert_transform",
            2,
            "inverse of a homogeneous transform",
            public=(
                (np.array([[0.0, -1, 0, 1], [1, 0, 0, 2], [0, 0, 1, 3], [0, 0, 0, 1]]),),
                (np.array([[1.0, 0, 0, 0.5], [0, 0, -1, -1], [0, 1, 0, 0.25], [0, 0, 0, 1]]),),
            ),
            hidden=lambda rng: ref.random_transforms(rng, 4),
            reference=ref.inverse_transform,
            forbidden=keys.KEY_INVERSE,
            mistakes=(TRANSLATION, TRANSPOSED),
            hint="Check your answer by multiplying: T⁻¹ T must be the identity (lecture 01 §4).",
        ),
        Question(
            "q5",
            "camera_pose",
            3,
            "modelling: the camera of a pan-tilt head",
            public=((0.0, 0.0), (np.pi / 2, 0.0), (0.0, np.pi / 6), (0.4, -0.3)),
            hidden=lambda rng: [
                (float(a), float(b))
                for a, b in zip(rng.uniform(-np.pi, np.pi, 5), rng.uniform(-1.2, 1.2, 5), strict=True)
            ],
            reference=ref.camera_pose,
            forbidden=keys.KEY_ROT,
            mistakes=(
                matches(
                    "tool_frame",
                    "this is the head's frame (x forward, z up), not the camera's: the camera's "
                    "z looks forward, its x points right and its y down the image",
                    camera_head_frame,
                ),
                matches(
                    "order",
                    "the tilt turned about the base's fixed y0 axis: the tilt axis turns with the "
                    "pan, so the tilt is about the head's own y axis (moving axes multiply on the right)",
                    camera_fixed_axes,
                ),
                TRANSPOSED,
                degrees_in(0, 1),
            ),
            hint="Build it as motions along the chain, each about or along the axes reached so far (lecture 01 §5), "
            "then name the camera's axes in the head's frame; check pan = tilt = 0 by hand.",
        ),
    ),
    allowed=(),  # the self-check only: rotx ... rodrigues, axis_angle, inverse_transform are the answers
)
