"""Rotations, Rodrigues' formula and homogeneous transforms against independent truths."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from puma_course import euler as eu
from puma_course import transforms as tf

RNG_SEED = 20261122
finite = st.floats(-10.0, 10.0, allow_nan=False, allow_infinity=False)
axis_st = st.tuples(finite, finite, finite).filter(lambda v: np.linalg.norm(v) > 1e-3)


def expm_series(A: np.ndarray, terms: int = 40) -> np.ndarray:
    """Matrix exponential by its power series (an independent truth for Rodrigues)."""
    out = np.eye(A.shape[0])
    term = np.eye(A.shape[0])
    for k in range(1, terms):
        term = term @ A / k
        out = out + term
    return out


@pytest.mark.parametrize("fn", [tf.rotx, tf.roty, tf.rotz])
def test_elementary_rotations_are_orthonormal_with_det_one(fn):
    angles = np.random.default_rng(RNG_SEED).uniform(-7, 7, 200)
    R = fn(angles)
    assert R.shape == (200, 3, 3)
    assert np.allclose(np.swapaxes(R, 1, 2) @ R, np.eye(3), atol=1e-12)
    assert np.allclose(np.linalg.det(R), 1.0, atol=1e-12)


def test_elementary_rotations_hand_worked():
    # A quarter turn about z takes x to y; about x takes y to z; about y takes z to x.
    assert np.allclose(tf.rotz(math.pi / 2) @ [1, 0, 0], [0, 1, 0])
    assert np.allclose(tf.rotx(math.pi / 2) @ [0, 1, 0], [0, 0, 1])
    assert np.allclose(tf.roty(math.pi / 2) @ [0, 0, 1], [1, 0, 0])
    c, s = math.cos(0.3), math.sin(0.3)
    assert np.allclose(tf.rotz(0.3), [[c, -s, 0], [s, c, 0], [0, 0, 1]])


@settings(derandomize=True, max_examples=200, deadline=None)
@given(axis=axis_st, angle=st.floats(-7, 7))
def test_rodrigues_is_the_exponential_of_the_skew_matrix(axis, angle):
    k = np.asarray(axis) / np.linalg.norm(axis)
    expected = expm_series(angle * tf.skew(k))
    assert np.allclose(tf.rodrigues(axis, angle), expected, atol=1e-10)


def test_rodrigues_normalises_the_axis_and_matches_elementary_rotations():
    assert np.allclose(tf.rodrigues([0, 0, 5], 0.7), tf.rotz(0.7))
    assert np.allclose(tf.rodrigues([3, 0, 0], -1.1), tf.rotx(-1.1))
    assert np.allclose(tf.rodrigues([0, 0.2, 0], 2.0), tf.roty(2.0))


def test_rodrigues_batch_equals_each_row():
    rng = np.random.default_rng(RNG_SEED)
    axes, angles = rng.normal(size=(50, 3)), rng.uniform(-4, 4, 50)
    batch = tf.rodrigues(axes, angles)
    for i in range(50):
        assert np.allclose(batch[i], tf.rodrigues(axes[i], angles[i]))


def test_rodrigues_fixes_its_axis():
    a = np.array([1.0, -2.0, 0.5])
    assert np.allclose(tf.rodrigues(a, 1.234) @ a, a)


@settings(derandomize=True, max_examples=200, deadline=None)
@given(axis=axis_st, angle=st.floats(-7, 7))
def test_axis_angle_round_trip(axis, angle):
    R = tf.rodrigues(axis, angle)
    k, t = tf.axis_angle(R)
    assert 0.0 <= t <= math.pi + 1e-12
    assert np.isclose(np.linalg.norm(k), 1.0)
    assert np.allclose(tf.rodrigues(k, t), R, atol=1e-9)


@pytest.mark.parametrize(
    "R",
    [np.eye(3), tf.rotx(math.pi), tf.roty(math.pi), tf.rodrigues([1, 1, 0], math.pi), tf.rodrigues([1, -2, 3], 1e-8)],
    ids=["identity", "half-x", "half-y", "half-diag", "tiny"],
)
def test_axis_angle_singular_cases(R):
    k, t = tf.axis_angle(R)
    assert np.all(np.isfinite(k)) and np.isfinite(t)
    assert np.allclose(tf.rodrigues(k, t), R, atol=1e-7)


def test_homogeneous_maps_child_into_parent_and_inverts():
    # Hand-worked: child frame turned 90 deg about z and moved to (1, 2, 3);
    # the child's point (1, 0, 0) is the parent's (1, 3, 3).
    T = tf.homogeneous(tf.rotz(math.pi / 2), [1, 2, 3])
    assert np.allclose(T @ [1, 0, 0, 1], [1, 3, 3, 1])
    assert np.allclose(tf.inverse_transform(T) @ T, np.eye(4))
    assert np.allclose(np.linalg.inv(T), tf.inverse_transform(T))
    # by hand: R^T = Rz(-90°) and -R^T p = -(2, -1, 3), so the parent's origin sits at (-2, 1, -3) in the child
    assert np.allclose(tf.inverse_transform(T)[:3, 3], [-2, 1, -3])
    # a batch of rigid transforms: each inverse undoes its own transform
    rng = np.random.default_rng(RNG_SEED)
    Tb = tf.homogeneous(tf.rodrigues(rng.normal(size=(20, 3)), rng.uniform(-3, 3, 20)), rng.normal(size=(20, 3)))
    assert np.allclose(tf.inverse_transform(Tb) @ Tb, np.eye(4), atol=1e-12)


def test_translation_helpers():
    assert np.allclose(tf.transx(2.0) @ [0, 0, 0, 1], [2, 0, 0, 1])
    assert np.allclose(tf.transy(-1.0) @ [0, 0, 0, 1], [0, -1, 0, 1])
    assert np.allclose(tf.transz(0.5) @ [1, 1, 1, 1], [1, 1, 1.5, 1])
    assert np.allclose(tf.transl([1, 2, 3])[:3, 3], [1, 2, 3])
    assert tf.transx(np.arange(4.0)).shape == (4, 4, 4)


def test_trot_about_a_line_keeps_points_on_the_line():
    c = np.array([1.0, 2.0, 0.0])
    T = tf.trot([0, 0, 1], 0.8, point=c)
    assert np.allclose(T @ [*c, 1], [*c, 1])
    assert np.allclose(T @ [*(c + [0, 0, 3]), 1], [*(c + [0, 0, 3]), 1])
    # a point one unit from the line along x goes round the circle
    assert np.allclose(T @ [2, 2, 0, 1], [1 + math.cos(0.8), 2 + math.sin(0.8), 0, 1])


def test_fixed_and_moving_composition_rule():
    """Motions about the fixed axes compose in the reverse order of moving-frame motions.

    Independent check: turn a vector by hand, step by step.
    """
    A, B = tf.trotx(math.pi / 2), tf.trotz(math.pi / 2)
    v = np.array([0.0, 1.0, 0.0, 0.0])
    # Fixed frame: first about x (y -> z), then about the fixed z (z stays z).
    assert np.allclose(tf.compose_fixed(A, B) @ v, [0, 0, 1, 0])
    # Moving frame: first about x, then about the NEW z (the old -y): (0,1,0) ends at (-1,0,0).
    assert np.allclose(tf.compose_moving(A, B) @ v, [-1, 0, 0, 0])
    assert np.allclose(tf.compose_fixed(A, B), B @ A)
    assert np.allclose(tf.compose_moving(A, B), A @ B)


def test_zyz_round_trip_and_gimbal_cases():
    rng = np.random.default_rng(RNG_SEED)
    for _ in range(200):
        R = tf.rodrigues(rng.normal(size=3), rng.uniform(-3, 3))
        ang = eu.zyz_from_rotation(R)
        assert 0 <= ang[1] <= math.pi
        assert np.allclose(eu.rotation_from_zyz(*ang), R, atol=1e-9)
    for R in (np.eye(3), tf.rotz(0.4), tf.roty(math.pi), tf.rotz(0.3) @ tf.roty(math.pi)):
        ang = eu.zyz_from_rotation(R)
        assert np.allclose(eu.rotation_from_zyz(*ang), R, atol=1e-12)


def test_is_rotation():
    assert tf.is_rotation(tf.rotx(0.2))
    assert not tf.is_rotation(np.diag([1.0, 1.0, -1.0]))
    assert not tf.is_rotation(2 * np.eye(3))


@pytest.mark.parametrize(
    "call, fragment",
    [
        (lambda: tf.rodrigues([0, 0, 0], 1.0), "axis: expected a non-zero"),
        (lambda: tf.rodrigues([1, 0], 1.0), "axis: expected shape (3,)"),
        (lambda: tf.rodrigues([1, 0, 0], float("nan")), "angle: expected finite"),
        (lambda: tf.rotx("ninety"), "angle: expected"),
        (lambda: tf.rotz([[1.0, 2.0]]), "angle: expected"),
        (
            lambda: tf.homogeneous(np.eye(2), [0, 0, 0]),
            "R: expected a 3x3 rotation matrix or (N, 3, 3), got an array of shape (2, 2)",
        ),
        (lambda: tf.homogeneous(2 * np.eye(3), [0, 0, 0]), "R: expected a rotation matrix"),
        (lambda: tf.axis_angle(np.diag([1.0, 1.0, -1.0])), "R: expected a rotation"),
        (lambda: tf.axis_angle(np.ones((3, 3))), "R: expected a rotation matrix"),
        (lambda: tf.transl([1, 2, None]), "p: expected"),
        (lambda: tf.compose_moving(), "transforms: expected at least one"),
        (lambda: tf.compose_fixed(np.eye(3)), "transforms[0]: expected a 4x4 homogeneous transform"),
        (lambda: tf.compose_moving(np.eye(4), np.ones((4, 4))), "transforms[1]: expected the last row"),
        # [[R^T, -R^T p], [0, 1]] is the inverse only of a rigid transform: anything else is refused
        (lambda: tf.inverse_transform(np.ones((4, 4))), "T: expected the last row"),
        (lambda: tf.inverse_transform(np.diag([2.0, 1.0, 1.0, 1.0])), "T (rotation part): expected a rotation"),
        (lambda: tf.inverse_transform(np.diag([1.0, 1.0, -1.0, 1.0])), "reflection"),
        (lambda: tf.trot([0, 0, 0], 1.0), "axis: expected a non-zero"),
        (lambda: tf.trot([0, 0, 1], 1.0, point=[1, 2]), "point: expected shape (3,)"),
        (lambda: tf.skew([1, 2]), "v: expected shape (3,)"),
        (lambda: eu.zyz_from_rotation(np.ones((3, 3))), "R: expected a rotation matrix"),
        (lambda: eu.rotation_from_zyz(float("nan"), 0.0, 0.0), "phi: expected finite"),
        (lambda: eu.rotation_from_zyz(0.0, 1j, 0.0), "theta: expected"),
        (lambda: eu.rotation_from_rpy(0.0, 0.0, None), "yaw: expected"),
    ],
)
def test_bad_input_raises_value_error_naming_the_argument(call, fragment):
    with pytest.raises(ValueError) as err:
        call()
    assert fragment in str(err.value)


@pytest.mark.parametrize("angle", [1e-12, 1e-9, 1e-7, 1e-5, math.pi - 1e-9, math.pi - 1e-7, math.pi - 1e-4])
def test_axis_angle_near_identity_and_half_turn(angle):
    axis = np.array([0.3, -0.5, 0.8])
    R = tf.rodrigues(axis, angle)
    k, t = tf.axis_angle(R)
    assert np.allclose(tf.rodrigues(k, t), R, atol=1e-12)


def test_axis_angle_batch_equals_each_row_including_special_cases():
    rng = np.random.default_rng(RNG_SEED)
    Rs = list(tf.rodrigues(rng.normal(size=(40, 3)), rng.uniform(-4, 4, 40)))
    Rs += [np.eye(3), tf.rotx(math.pi), tf.rodrigues([1, 1, 0], math.pi), tf.rodrigues([1, 2, 3], 1e-9)]
    R = np.stack(Rs)
    axes, angles = tf.axis_angle(R)
    assert axes.shape == (len(Rs), 3) and angles.shape == (len(Rs),)
    assert np.allclose(tf.rodrigues(axes, angles), R, atol=1e-9)
    for i, Ri in enumerate(Rs):
        k, t = tf.axis_angle(Ri)
        assert np.isclose(t, angles[i]) and np.allclose(k, axes[i])


# ---------------------------------------------------------------- Euler angles: ZYZ and roll-pitch-yaw
def test_rpy_is_the_fixed_axis_product_and_round_trips():
    rng = np.random.default_rng(RNG_SEED)
    angles = np.column_stack([rng.uniform(-3, 3, 50), rng.uniform(-1.5, 1.5, 50), rng.uniform(-3, 3, 50)])
    R = eu.rotation_from_rpy(angles[:, 0], angles[:, 1], angles[:, 2])
    # second derivation: roll about fixed x, then pitch about fixed y, then yaw about fixed z
    for (r, p, y), Ri in zip(angles, R, strict=True):
        assert np.allclose(Ri, tf.compose_fixed(tf.trotx(r), tf.troty(p), tf.trotz(y))[:3, :3], atol=1e-14)
    back = eu.rpy_from_rotation(R)
    assert back.shape == (50, 3)
    assert np.allclose(back, angles, atol=1e-12)  # pitch in (-π/2, π/2): the representation is unique


def test_zyz_batch_round_trips_and_theta_in_0_pi():
    rng = np.random.default_rng(RNG_SEED + 1)
    R = tf.rodrigues(rng.normal(size=(200, 3)), rng.uniform(-3, 3, 200))
    zyz = eu.zyz_from_rotation(R)
    assert zyz.shape == (200, 3) and (zyz[:, 1] >= 0).all() and (zyz[:, 1] <= math.pi).all()
    assert np.allclose(eu.rotation_from_zyz(zyz[:, 0], zyz[:, 1], zyz[:, 2]), R, atol=1e-12)


@pytest.mark.parametrize("rep", [0.0, 0.7])
def test_euler_gimbal_lock_is_snapped_and_still_reproduces_R(rep):
    # ZYZ at θ = 0 and θ = π: θ exactly 0 / π (snapped), ψ = the representative, R reproduced
    for R, theta in [(tf.rotz(0.5), 0.0), (tf.rotz(0.5) @ tf.roty(math.pi) @ tf.rotz(-0.2), math.pi)]:
        phi, th, psi = eu.zyz_from_rotation(R, psi=rep)
        assert th == theta and psi == rep  # exact by design
        assert np.allclose(eu.rotation_from_zyz(phi, th, psi), R, atol=1e-12)
    # RPY at pitch = ±90°: pitch exactly ±π/2 (snapped), roll = the representative, R reproduced
    for R, pitch in [
        (tf.roty(math.pi / 2) @ tf.rotx(0.4), math.pi / 2),
        (tf.rotz(0.3) @ tf.roty(-math.pi / 2), -math.pi / 2),
    ]:
        roll, p, yaw = eu.rpy_from_rotation(R, roll=rep)
        assert p == pitch and roll == rep
        assert np.allclose(eu.rotation_from_rpy(roll, p, yaw), R, atol=1e-12)


def test_euler_hand_worked():
    # a quarter turn about z is ZYZ (π/2, 0, 0) and RPY (0, 0, π/2); about y it is RPY (0, π/2, 0)
    assert np.allclose(eu.zyz_from_rotation(tf.rotz(math.pi / 2)), [math.pi / 2, 0, 0])
    assert np.allclose(eu.rpy_from_rotation(tf.rotz(math.pi / 2)), [0, 0, math.pi / 2])
    assert np.allclose(eu.rpy_from_rotation(tf.roty(0.3)), [0, 0.3, 0])
    # Rz(φ) Ry(θ) Rz(ψ) applied to e_z: the third column is (cφ sθ, sφ sθ, cθ)
    R = eu.rotation_from_zyz(0.4, 0.9, -1.3)
    assert np.allclose(R[:, 2], [math.cos(0.4) * math.sin(0.9), math.sin(0.4) * math.sin(0.9), math.cos(0.9)])


def test_wrap_angle_is_in_minus_pi_pi_for_floats_and_arrays():
    values = [math.pi, -math.pi, 3 * math.pi, -3 * math.pi, 0.0, -1e-17, 7.0, -7.0, math.pi + 1e-16]
    arr = tf.wrap_angle(np.array(values))
    for v, a in zip(values, arr, strict=True):
        w = tf.wrap_angle(float(v))
        assert isinstance(w, float) and -math.pi < w <= math.pi and w == a
        assert math.isclose(math.cos(w), math.cos(v), abs_tol=1e-12) and math.isclose(
            math.sin(w), math.sin(v), abs_tol=1e-12
        )


@pytest.mark.parametrize("delta", [0.0, 1e-9, 1e-7, 1e-6, 2e-6, 1e-5, 1e-3])
@pytest.mark.parametrize("seed", range(20))
def test_axis_angle_near_a_half_turn_reproduces_the_rotation(delta, seed):
    # issue 21: axis_angle at θ = π - 1e-6 was off by 5.3e-7 (its axis came from R + I)
    from puma_course.transforms import axis_angle, rodrigues

    rng = np.random.default_rng(seed)
    k = rng.normal(size=3)
    k /= np.linalg.norm(k)
    R = rodrigues(k, np.pi - delta)
    axis, angle = axis_angle(R)
    assert np.abs(rodrigues(axis, angle) - R).max() <= 1e-12
    assert abs(angle - (np.pi - delta)) <= 1e-12
