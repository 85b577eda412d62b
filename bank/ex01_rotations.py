"""Exercise 1 (``solutions/ex01_rotations.ipynb``): rotations and Rodrigues' formula.

Its first four questions (names, points, cases) are pinned by the hostile-submission fixtures of the
grader's tests; what changed with the mistake diagnosis is how a wrong answer is worded. Question 5
is the modelling question: the pose of a camera on a pan-tilt head, from a description in words.
Question 6 reads three angles back from a rotation, in a controller's X-Y-Z set that lecture 01 does not
print (it prints ZYZ and roll-pitch-yaw), gimbal lock included.
"""

from __future__ import annotations

import numpy as np

from puma_course.grading.judge.compare import compare_angles
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
from ._formulas import (
    camera_fixed_axes,
    camera_head_frame,
    rodrigues_unnormalised,
    rpy_formula_all,
    xyz_angles_all,
    xyz_no_lock_all,
    xyz_other_branch_all,
)
from ._reference import chains as ref


def _xyz(a: float, b: float, c: float) -> np.ndarray:
    return ref.elementary_rotation("x", a) @ ref.elementary_rotation("y", b) @ ref.elementary_rotation("z", c)


def _lock(a: float, sign: float) -> np.ndarray:
    """Rx(a) Ry(±π/2) with exact zeros (the gimbal lock: only a ± c is defined)."""
    Ry = np.array([[0.0, 0.0, sign], [0.0, 1.0, 0.0], [-sign, 0.0, 0.0]])
    return ref.elementary_rotation("x", a) @ Ry


def _xyz_cases(rng: np.random.Generator) -> list[tuple[np.ndarray]]:
    """Four stacks, each of three general rotations, one exactly at the lock and one 1e-4 from it (not locked:
    c is not 0 there), shuffled: a formula wrong in general or at the lock fails every case."""
    out = []
    for _ in range(4):
        a, c, b = rng.uniform(-np.pi, np.pi, 4), rng.uniform(-np.pi, np.pi, 4), rng.uniform(-1.4, 1.4, 4)
        b[3] = float(rng.choice([-1.0, 1.0])) * (np.pi / 2 - 1e-4)
        lock = _lock(float(rng.uniform(-np.pi, np.pi)), float(rng.choice([-1.0, 1.0])))
        Rs = [_xyz(a[i], b[i], c[i]) for i in range(4)] + [lock]
        out.append((np.stack([Rs[i] for i in rng.permutation(5)]),))
    return out


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
        Question(
            "q6",
            "xyz_angles",
            2,
            "a controller's X-Y-Z angles of rotations, gimbal lock included",
            public=(
                (np.stack([_xyz(0.4, 0.3, -1.2), _lock(0.7, 1.0), _xyz(-2.5, -1.2, 3.0)]),),
                (np.stack([_lock(-2.0, -1.0), _xyz(3.0, 1.5, 0.1), _xyz(1.0, 0.2, 0.5)]),),
            ),
            hidden=_xyz_cases,
            reference=xyz_angles_all,
            compare=compare_angles,
            forbidden=(*keys.KEY_ROT, *keys.KEY_EULER),
            mistakes=(
                matches(
                    "order",
                    "these are lecture 01 §7's roll, pitch, yaw, the angles of Rz(c) Ry(b) Rx(a) (fixed axes): the "
                    "controller's set is Rx(a) Ry(b) Rz(c), turns about the moving axes x, new y, newest z",
                    rpy_formula_all,
                ),
                matches(
                    "gimbal_lock",
                    "at b = ±π/2 (the gimbal lock) your a and c come from atan2(0, 0): only a + c or a - c is "
                    "defined there, and the question fixes c = 0 (lecture 01 §6, the lock)",
                    xyz_no_lock_all,
                ),
                matches(
                    "range",
                    "(a + π, π - b, c + π) is the same rotation, but the question asks for b in [-π/2, π/2]",
                    xyz_other_branch_all,
                ),
                degrees_out(),  # every entry is an angle (a (k, 3) array: flat indices would miss rows)
            ),
            hint="Multiply Rx(a) Ry(b) Rz(c) out as lecture 01 §6 does for ZYZ, find the entry that is sin b alone "
            "and the pairs that give a and c; then set b = π/2 and see what is left. Check by multiplying back.",
        ),
    ),
    allowed=(),  # the self-check only: rotx ... rodrigues, axis_angle, inverse_transform are the answers
)
