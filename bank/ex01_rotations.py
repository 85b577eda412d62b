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
    TRANSPOSED,
    Mistake,
    angle_2pi,
    degrees_in,
    degrees_out,
    matches,
    negated,
    unit_axis_out,
)
from puma_course.grading.spec import Exercise, Question

from . import _keys as keys
from ._formulas import (
    camera_fixed_axes,
    camera_head_frame,
    camera_offset_unturned,
    camera_panned_back,
    camera_tilted_back,
    carried_about_u,
    carried_arcsin,
    carried_back,
    carried_in_degrees,
    carried_minus_square,
    carried_unnormalised_angle,
    carried_unnormalised_axis,
    pose_base_difference,
    pose_minus_p,
    pose_of_a_in_b,
    pose_other_order,
    rpy_formula_all,
    turn_b_onto_a,
    turn_b_then_a,
    turn_in_a_frame,
    turn_the_other_way_round,
    turned_about_unsigned_axis,
    turned_other_way,
    turned_other_way_about_minus_y,
    turned_other_way_about_y,
    xyz_angles_all,
    xyz_no_lock_all,
    xyz_other_branch_all,
    xyz_threshold_all,
)
from ._reference import chains as ref


def _xyz(a: float, b: float, c: float) -> np.ndarray:
    return ref.elementary_rotation("x", a) @ ref.elementary_rotation("y", b) @ ref.elementary_rotation("z", c)


def _lock(a: float, sign: float) -> np.ndarray:
    """Rx(a) Ry(±π/2) with exact zeros (the gimbal lock: only a ± c is defined)."""
    Ry = np.array([[0.0, 0.0, sign], [0.0, 1.0, 0.0], [-sign, 0.0, 0.0]])
    return ref.elementary_rotation("x", a) @ Ry


#: cos b of the two rotations beside the question's threshold cos b < 1e-9: 2⁻³³ ≈ 1.2e-10 (inside: the lock, c = 0)
#: and 2⁻²⁶ ≈ 1.5e-8 (outside: the regular formula), each with sin b chosen so that sin²b + cos²b = 1 to 1e-20.
NEAR_LOCK = ((2.0**-33, 1.0), (2.0**-26, 1.0 - 2.0**-53))


def _near_lock(a: float, c: float, sign: float, inside: bool) -> np.ndarray:
    """Rx(a) Ry(b) Rz(c) with cos b exactly :data:`NEAR_LOCK`'s: 1.2e-10 (``inside`` the threshold) or 1.5e-8.

    The first row is (cos b cos c, -cos b sin c, ±sin b): its hypot is cos b to the last bit, and so is
    sqrt(1 - r13²) (r13 = 1 exactly inside, 1 - 2⁻⁵³ outside), so every reading of cos b agrees which side it is.
    """
    cb, sb = NEAR_LOCK[0 if inside else 1]
    Ry = np.array([[cb, 0.0, sign * sb], [0.0, 1.0, 0.0], [-sign * sb, 0.0, cb]])
    return ref.elementary_rotation("x", a) @ Ry @ ref.elementary_rotation("z", c)


def _xyz_cases(rng: np.random.Generator) -> list[tuple[np.ndarray]]:
    """Four stacks, each of three general rotations, one exactly at the lock, one 1e-4 from it (not locked:
    c is not 0 there) and one on each side of the threshold the question states (:data:`NEAR_LOCK`: a threshold
    of 1e-6 or of exactly 0 fails one of them), shuffled: a formula wrong in general or at the lock fails every
    case."""
    out = []
    for _ in range(4):
        a, c, b = rng.uniform(-np.pi, np.pi, 6), rng.uniform(-np.pi, np.pi, 6), rng.uniform(-1.4, 1.4, 4)
        b[3] = float(rng.choice([-1.0, 1.0])) * (np.pi / 2 - 1e-4)
        lock = _lock(float(rng.uniform(-np.pi, np.pi)), float(rng.choice([-1.0, 1.0])))
        sides = [_near_lock(a[4 + k], c[4 + k], float(rng.choice([-1.0, 1.0])), k == 0) for k in range(2)]
        Rs = [_xyz(a[i], b[i], c[i]) for i in range(4)] + [lock, *sides]
        out.append((np.stack([Rs[i] for i in rng.permutation(7)]),))
    return out


def _sign_left_out() -> tuple[Mistake, ...]:
    """The axis's sign left out, one variant per negative axis (its message names that axis): R_e(+θ) for "-e"."""
    return tuple(
        matches(
            "rotation_sense#sign",
            f'this is the turn by +θ about {e}, not about -{e}: a turn about "-e" is a turn about e by -θ, so "-{e}" '
            f"gives R_{e}(-θ). The axis's sign was left out (a positive turn about x carries y towards z; about y, "
            "z towards x; about z, x towards y)",
            lambda axis, angle, e=e: turned_about_unsigned_axis(axis, angle, f"-{e}"),
        )
        for e in "xyz"
    )


def _signed_axis_cases(rng: np.random.Generator) -> list[tuple[str, float]]:
    """Six turns, five about a negative axis (two about -y) and one about a positive one, by 0.3 to 2.9 rad either
    way: the three matrices looked up by name, the axis's sign dropped, are right on three cases of ten."""
    axes = rng.permutation(["-x", "-y", "-z", "-y", "-x", "z"])
    angles = rng.uniform(0.3, 2.9, 6) * rng.choice([-1.0, 1.0], 6)
    return [(str(a), float(t)) for a, t in zip(axes, angles, strict=True)]


def _direction_pairs(rng: np.random.Generator) -> list[tuple[list[float], list[float]]]:
    """Seven pairs (u, v) of any lengths: six between 100° and 165° apart (an angle from arcsin |u × v|, never
    above 90°, is wrong there), one pointing the same way (the identity), in random order."""
    out = []
    for phi in rng.uniform(np.radians(100), np.radians(165), 6):
        u = rng.normal(size=3)
        w = np.cross(u, rng.normal(size=3))
        v = np.cos(phi) * u / np.linalg.norm(u) + np.sin(phi) * w / np.linalg.norm(w)
        out.append((list(u * rng.uniform(0.5, 3)), list(v * rng.uniform(0.5, 3))))
    u = rng.normal(size=3)  # scaled by a power of two: u × v is exactly zero, as it is for the public parallel pair
    out.append((list(u), list(u * float(rng.choice([0.25, 0.5, 2.0, 4.0])))))
    return [out[i] for i in rng.permutation(len(out))]


#: The orientations of q3's second public case: R_a a turn about (1, 1, 0), and q3's first R_b = R_z(π/2) R_x(π/2).
_Q3_A2 = ref.rodrigues([1.0, 1.0, 0.0], 0.7)
_Q3_B1 = np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])


def _orientation_pairs(rng: np.random.Generator) -> list[tuple[np.ndarray, np.ndarray]]:
    """Five pairs (R_a, R_b = K R_a), R_a and K random turns by 0.2 to 3 rad."""
    R_a, K = ref.random_rotations(rng, 5), ref.random_rotations(rng, 5)
    return [(a, k @ a) for a, k in zip(R_a, K, strict=True)]


def _pose_pairs(rng: np.random.Generator) -> list[tuple[np.ndarray, np.ndarray]]:
    """Four pairs (⁰T_A, ⁰T_B) of random rigid transforms."""
    poses = ref.random_transforms(rng, 8)
    return [(poses[2 * i][0], poses[2 * i + 1][0]) for i in range(4)]


EXERCISE = Exercise(
    "ex01_rotations",
    "Rotations and Rodrigues' formula",
    (
        Question(
            "q1",
            "elementary_rotation",
            2,
            "rotation about a signed coordinate axis",
            public=(("-y", 0.4), ("y", -1.2), ("-z", 2.0), ("z", np.pi / 2), ("-x", 1.1)),
            hidden=_signed_axis_cases,
            reference=ref.signed_rotation,
            forbidden=keys.KEY_ROT,
            mistakes=(
                # variants of one mistake (key#variant): named only where every failing case is that variant, so a
                # matrix transposed on every axis is not told that the axis's sign was left out
                *_sign_left_out(),
                matches(
                    "rotation_sense#ry",
                    "R_y's sines are swapped: a positive turn about y carries z towards x, so R_y's top row ends in "
                    "+sin θ and its bottom row starts with -sin θ (about -y, turn about y by -θ)",
                    turned_other_way_about_minus_y,
                ),
                matches(
                    "rotation_sense#ry",
                    "this is R_y(-θ): R_y's sines are swapped (a positive turn about y carries z towards x, so "
                    "R_y's top row ends in +sin θ and its bottom row starts with -sin θ)",
                    turned_other_way_about_y,
                ),
                matches(
                    "rotation_sense",
                    "your matrix turns the wrong way: it is the transpose of the right one, which for a turn about a "
                    'coordinate axis is the turn by -θ (column k must be where e_k goes). A turn about "-e" is a turn '
                    "about e by -θ, and a positive turn about x carries y towards z (about y, z towards x; about z, "
                    "x towards y)",
                    turned_other_way,
                ),
                degrees_in(1),
                SIGN_FLIP,
            ),
            hint='Point your right thumb along the axis given ("-z" points down) and curl your fingers: that is a '
            "positive turn. Check a quarter turn by hand: where must e_x, e_y, e_z go?",
        ),
        Question(
            "q2",
            "rotation_between",
            3,
            "the smallest turn carrying one direction onto another",
            public=(
                ([2.0, 0.0, 0.0], [-1.0, 1.0, 0.0]),
                ([0.0, 0.0, 3.0], [1.0, 0.0, 1.0]),
                ([1.0, 2.0, -1.0], [0.5, 1.0, -0.5]),
                ([0.0, 1.0, 1.0], [0.5, -1.0, -0.2]),
            ),
            hidden=_direction_pairs,
            reference=ref.rotation_between,
            forbidden=keys.KEY_RODRIGUES,
            mistakes=(
                matches(
                    "unnormalised",
                    "the axis u × v was not normalised: its length is |u||v| sin θ, and K(k, θ) needs the unit "
                    "vector k = (u × v) / |u × v|",
                    carried_unnormalised_axis,
                ),
                matches(
                    "unnormalised",
                    "the angle came from arccos(u · v) of the vectors as given: u · v = |u||v| cos θ, so divide by "
                    "both lengths first (or take atan2(|u × v|, u · v), which needs no division)",
                    carried_unnormalised_angle,
                ),
                matches(
                    "transposed",
                    "this turn carries v onto u (its transpose carries u onto v): turn about u × v, not v × u",
                    carried_back,
                ),
                matches(
                    "degrees",
                    "your axis is right but the angle went into the sines and cosines in degrees: np.sin and np.cos "
                    "take radians (leave out np.degrees)",
                    carried_in_degrees,
                ),
                matches(
                    "angle_quadrant",
                    "your angle is arcsin |u × v| / (|u||v|), which never exceeds 90°: these vectors are more than "
                    "a right angle apart, so the turn is 180° minus yours. atan2(|u × v|, u · v) gives every angle",
                    carried_arcsin,
                ),
                matches(
                    "sign_flip",
                    "Rodrigues' last term has the wrong sign: K(k, θ) = I + sin θ [k]x + (1 - cos θ) [k]x² "
                    "(lecture 01 §3), with a plus",
                    carried_minus_square,
                ),
                matches(
                    "wrong_axis",
                    "you turned about u itself, which leaves u where it is: the turn carrying u onto v is about "
                    "u × v, perpendicular to both",
                    carried_about_u,
                ),
                SIGN_FLIP,
            ),
            hint="Check by hand: R u must point along v, and R (u × v) = u × v. Is your angle right when u and v are "
            "more than a right angle apart?",
        ),
        Question(
            "q3",
            "axis_angle_between",
            3,
            "axis and angle of the turn from one orientation to another",
            public=(
                (np.round(ref.elementary_rotation("x", np.pi / 2), 15), _Q3_B1),
                (_Q3_A2, ref.rodrigues([0.0, 1.0, -1.0], 2.5) @ _Q3_A2),
            ),
            hidden=_orientation_pairs,
            reference=ref.axis_angle_between,
            forbidden=keys.KEY_AXIS_ANGLE,
            mistakes=(
                matches(
                    "frame_coordinates",
                    "this is the axis and angle of R_aᵀ R_b, whose axis is written in the tool's own coordinates "
                    "(along the columns of R_a): the question asks for the axis in the base frame, of the turn K "
                    "with R_b = K R_a",
                    turn_in_a_frame,
                ),
                matches(
                    "rotation_sense",
                    "this turn carries R_b back onto R_a (the axis points the other way): K carries R_a onto R_b, "
                    "K = R_b R_aᵀ",
                    turn_b_onto_a,
                ),
                matches(
                    "frame_coordinates",
                    "this is the axis and angle of R_bᵀ R_a, the turn back from {B} to {A} written in {B}'s own "
                    "coordinates: the question asks for K with R_b = K R_a, its axis in the base frame",
                    turn_b_then_a,
                ),
                matches(
                    "rotation_sense",
                    "(k, 2π - θ) turns about k the long way round, which is the turn by -θ: the question asks for "
                    "the angle θ in (0, π) of the turn about k",
                    turn_the_other_way_round,
                ),
                degrees_out([3]),
                angle_2pi([3], "(0, π)"),
                unit_axis_out(3),
                negated(
                    "range",
                    "(-k, -θ) is the same rotation as (k, θ), but the question asks for 0 < θ < π: flip both signs",
                ),
            ),
            hint="Solve R_b = K R_a for K first (lecture 01 §5: a turn about fixed axes multiplies on the left), "
            "then read K's axis and angle (§3). Check: K R_a must give R_b.",
        ),
        Question(
            "q4",
            "relative_pose",
            2,
            "the pose of one frame in another, both given in the base frame",
            public=(
                (
                    np.array([[0.0, -1, 0, 1], [1, 0, 0, 2], [0, 0, 1, 3], [0, 0, 0, 1]]),
                    np.array([[1.0, 0, 0, 0.5], [0, 0, -1, -1], [0, 1, 0, 0.25], [0, 0, 0, 1]]),
                ),
                (
                    np.array([[0.0, 0, 1, -0.5], [0, 1, 0, 1], [-1, 0, 0, 0.75], [0, 0, 0, 1]]),
                    np.array([[1.0, 0, 0, 0.5], [0, 0, -1, 2], [0, 1, 0, 1], [0, 0, 0, 1]]),
                ),
            ),
            hidden=_pose_pairs,
            reference=ref.relative_pose,
            forbidden=(*keys.KEY_INVERSE, *keys.KEY_GENERAL_INVERSE),
            mistakes=(
                matches(
                    "inverse",
                    "this is ᴮT_A, the pose of {A} in {B}: the question asks for {B} in {A}, (⁰T_A)⁻¹ ⁰T_B",
                    pose_of_a_in_b,
                ),
                matches(
                    "order",
                    "this is ⁰T_B (⁰T_A)⁻¹, the product in the other order: go from {A} back to {0}, then from "
                    "{0} to {B}",
                    pose_other_order,
                ),
                matches(
                    "translation",
                    "⁰T_A was inverted with the translation -p_A: the origin of {0} seen from {A} is -R_Aᵀ p_A "
                    "(lecture 01 §4)",
                    pose_minus_p,
                ),
                matches(
                    "frame_coordinates",
                    "the translation is p_B - p_A, written in the base frame's coordinates: the question asks "
                    "for it in {A}'s coordinates, R_Aᵀ (p_B - p_A)",
                    pose_base_difference,
                ),
            ),
            hint="Write the chain {A} → {0} → {B} as a product of two transforms, then invert the one that "
            "needs it by hand; check that ⁰T_A times your answer gives ⁰T_B.",
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
                matches(
                    "rotation_sense",
                    "your tilt turns the wrong way: a positive tilt about the head's y axis carries its z towards its "
                    "x (R_y's top row ends in +sin θ), so a positive tilt points the camera down",
                    camera_tilted_back,
                ),
                matches(
                    "rotation_sense",
                    "your pan turns the wrong way: a positive pan about z0 carries x0 towards y0 (counter-clockwise "
                    "seen from above)",
                    camera_panned_back,
                ),
                matches(
                    "frame_coordinates",
                    "the camera's offset c is along the base's x0: it is along the head's own x, which turns with "
                    "the pan and the tilt (the offset is c times the turned head's first column)",
                    camera_offset_unturned,
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
                (np.stack([_near_lock(0.5, 1.0, 1.0, True), _xyz(-0.3, 0.9, 2.0), _near_lock(-1, 2.5, -1, False)]),),
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
                    "lock_threshold",
                    "a rotation with cos b ≈ 1.5e-8 is treated as the gimbal lock: the question's threshold is "
                    "cos b < 1e-9, so there the regular formula gives a, b and c (c is not 0); your threshold is "
                    "larger than the question's",
                    lambda Rs: xyz_threshold_all(Rs, 1e-5),
                ),
                matches(
                    "lock_threshold",
                    "a rotation with cos b ≈ 1.2e-10 is below the question's threshold cos b < 1e-9, so it counts "
                    "as the gimbal lock (c = 0); your test for the lock (cos b == 0, or a smaller threshold) "
                    "misses it",
                    lambda Rs: xyz_threshold_all(Rs, 0.0),
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
