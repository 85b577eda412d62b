"""The references of ex01 q1-q4 (issue 22's changed questions) and their mistaken answers, against independent truths.

q1 a turn about a signed axis: quarter turns worked by hand, and Rodrigues' formula about ±e. q2 the smallest turn
carrying u onto v: u lands on v, u × v stays put, the angle between them is the turn's (no smaller turn does it),
and sympy's exact matrix on one worked pair. q3 the fixed-axis turn K: R_b = K R_a rebuilt, and the axis is fixed in
the base frame. q4 ᴬT_B: a point with coordinates x in {B} has ⁰T_A ᴬT_B x = ⁰T_B x in the base frame, and points
mapped by hand. The mistaken formulas of the feedback are checked against what each mistake is.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from puma_course.grading import EXERCISES

EXERCISES["ex01_rotations"]  # loads the bank
import puma_course_bank._formulas as formulas  # noqa: E402
import puma_course_bank._reference.chains as chains  # noqa: E402

EX, EY, EZ = np.eye(3)
E = {"x": EX, "y": EY, "z": EZ}


def _rodrigues_by_hand(k: np.ndarray, t: float) -> np.ndarray:
    """v ↦ v cos θ + (k × v) sin θ + k (k · v)(1 - cos θ), applied to e_x, e_y, e_z (the columns)."""
    k = k / np.linalg.norm(k)
    return np.column_stack(
        [v * np.cos(t) + np.cross(k, v) * np.sin(t) + k * (k @ v) * (1 - np.cos(t)) for v in np.eye(3)]
    )


# ------------------------------------------------------------------ q1
@pytest.mark.parametrize(
    ("axis", "images"),
    [
        # a quarter turn about +z carries x to y and y to -x; about -z the other way, and so on
        ("z", (EY, -EX, EZ)),
        ("-z", (-EY, EX, EZ)),
        ("x", (EX, EZ, -EY)),
        ("-x", (EX, -EZ, EY)),
        ("y", (-EZ, EY, EX)),
        ("-y", (EZ, EY, -EX)),
    ],
)
def test_q1_quarter_turns_about_signed_axes_worked_by_hand(axis, images):
    R = chains.signed_rotation(axis, np.pi / 2)
    for col, image in enumerate(images):
        assert np.allclose(R[:, col], image, atol=1e-15), (axis, col)


def test_q1_is_rodrigues_about_plus_or_minus_e():
    rng = np.random.default_rng(0)
    for axis in chains.SIGNED_AXES:
        e = E[axis[-1]] * (-1.0 if axis[0] == "-" else 1.0)
        for t in rng.uniform(-np.pi, np.pi, 5):
            assert np.allclose(chains.signed_rotation(axis, t), _rodrigues_by_hand(e, t), atol=1e-14)


def test_q1_refuses_an_unknown_axis_naming_the_argument():
    with pytest.raises(ValueError, match="axis"):
        chains.signed_rotation("+x", 0.3)


def test_q1_mistakes_are_the_turn_the_other_way():
    for axis in chains.SIGNED_AXES:
        assert np.allclose(formulas.turned_other_way(axis, 0.7), chains.signed_rotation(axis, -0.7))
    # the axis's sign ignored gives R about the positive axis by +θ: the same matrix
    assert np.allclose(formulas.turned_other_way("-x", 0.7), chains.signed_rotation("x", 0.7))
    assert np.isnan(formulas.turned_other_way_about_y("-y", 0.7)).all()
    assert np.isnan(formulas.turned_other_way_about_minus_y("y", 0.7)).all()


# ------------------------------------------------------------------ q2
def _pairs(rng: np.random.Generator, n: int) -> list[tuple[np.ndarray, np.ndarray]]:
    return [(rng.normal(size=3) * rng.uniform(0.2, 4), rng.normal(size=3) * rng.uniform(0.2, 4)) for _ in range(n)]


def test_q2_carries_u_onto_v_keeps_u_cross_v_and_turns_by_the_angle_between():
    rng = np.random.default_rng(1)
    for u, v in _pairs(rng, 200):
        R = chains.rotation_between(u, v)
        uh, vh = u / np.linalg.norm(u), v / np.linalg.norm(v)
        assert np.allclose(R @ uh, vh, atol=1e-12)
        w = np.cross(u, v)
        assert np.allclose(R @ w, w, atol=1e-12)  # the axis u × v does not move
        between = np.arccos(np.clip(uh @ vh, -1, 1))
        turn = np.arccos(np.clip((np.trace(R) - 1) / 2, -1, 1))
        # no smaller turn: any rotation carrying û onto v̂ turns by at least the angle between them
        assert np.isclose(turn, between, atol=1e-7)
        assert np.allclose(R.T @ R, np.eye(3), atol=1e-12) and np.isclose(np.linalg.det(R), 1.0)


def test_q2_identity_for_parallel_and_refusal_for_opposite_vectors():
    assert np.allclose(chains.rotation_between([1.0, 2.0, -1.0], [0.5, 1.0, -0.5]), np.eye(3))
    with pytest.raises(ValueError, match="v"):
        chains.rotation_between([1.0, 2.0, -1.0], [-2.0, -4.0, 2.0])
    with pytest.raises(ValueError, match="u"):
        chains.rotation_between([0.0, 0.0, 0.0], [1.0, 0.0, 0.0])


def test_q2_matches_sympy_exactly_on_a_worked_pair():
    # u = (2, 0, 0), v = (-1, 1, 0): 135° about +z
    t = sp.Rational(3, 4) * sp.pi
    Rz = sp.Matrix([[sp.cos(t), -sp.sin(t), 0], [sp.sin(t), sp.cos(t), 0], [0, 0, 1]])
    assert np.allclose(chains.rotation_between([2.0, 0, 0], [-1.0, 1, 0]), np.array(Rz.evalf(), dtype=float))
    # u = (0, 0, 3), v = (1, 0, 1): 45° about u × v = (0, 3, 0), +y
    t = sp.pi / 4
    Ry = sp.Matrix([[sp.cos(t), 0, sp.sin(t)], [0, 1, 0], [-sp.sin(t), 0, sp.cos(t)]])
    assert np.allclose(chains.rotation_between([0.0, 0, 3], [1.0, 0, 1]), np.array(Ry.evalf(), dtype=float))


def test_q2_mistakes_are_what_they_say():
    u, v = np.array([0.0, 1.0, 1.0]), np.array([0.5, -1.0, -0.2])
    R = chains.rotation_between(u, v)
    assert np.allclose(formulas.carried_back(u, v), R.T)
    assert np.allclose(formulas.carried_back(u, v), chains.rotation_between(v, u))
    # the unnormalised axis: Rodrigues' sum with k replaced by u × v itself
    w, t = np.cross(u, v), np.arccos(u @ v / np.linalg.norm(u) / np.linalg.norm(v))
    S = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
    assert np.allclose(formulas.carried_unnormalised_axis(u, v), np.eye(3) + np.sin(t) * S + (1 - np.cos(t)) * S @ S)
    raw = np.arccos(np.clip(u @ v, -1, 1))
    assert np.allclose(formulas.carried_unnormalised_angle(u, v), _rodrigues_by_hand(w, raw))


def test_q2_cases_defeat_an_arcsin_angle():
    q = EXERCISES["ex01_rotations"].question("q2")
    for seed in range(10):
        cases = q.cases(np.random.default_rng(seed))
        obtuse = [c for c in cases if np.dot(*np.asarray(c, dtype=float)) < -1e-9]
        assert len(obtuse) >= 8, seed  # two public and six hidden pairs more than a right angle apart


# ------------------------------------------------------------------ q3
def test_q3_k_carries_r_a_onto_r_b_about_an_axis_fixed_in_the_base_frame():
    rng = np.random.default_rng(2)
    for R_a, K in zip(chains.random_rotations(rng, 50), chains.random_rotations(rng, 50), strict=True):
        R_b = K @ R_a
        k, t = (x := chains.axis_angle_between(R_a, R_b))[:3], x[3]
        assert np.isclose(np.linalg.norm(k), 1.0) and 0 < t < np.pi
        assert np.allclose(_rodrigues_by_hand(k, t) @ R_a, R_b, atol=1e-12)
        assert np.allclose(K @ k, k, atol=1e-12)  # the axis in base coordinates: K leaves it where it is


def test_q3_worked_by_hand():
    # R_a = R_x(90°), R_b = R_z(90°) R_x(90°): a quarter turn about the base's z
    Rx = np.array([[1.0, 0, 0], [0, 0, -1], [0, 1, 0]])
    Rz = np.array([[0.0, -1, 0], [1, 0, 0], [0, 0, 1]])
    assert np.allclose(chains.axis_angle_between(Rx, Rz @ Rx), [0, 0, 1, np.pi / 2])
    # in {A}'s coordinates the same axis is R_aᵀ e_z = (0, 1, 0): the frame_coordinates mistake
    assert np.allclose(formulas.turn_in_a_frame(Rx, Rz @ Rx), [0, 1, 0, np.pi / 2])
    # {B} back onto {A}: the turn about -z, written with 0 < θ < π
    assert np.allclose(formulas.turn_b_onto_a(Rx, Rz @ Rx), [0, 0, -1, np.pi / 2])


# ------------------------------------------------------------------ q4
def test_q4_maps_points_through_the_base_frame():
    rng = np.random.default_rng(3)
    for (T_a,), (T_b,) in zip(chains.random_transforms(rng, 30), chains.random_transforms(rng, 30), strict=True):
        X = chains.relative_pose(T_a, T_b)
        for x in rng.normal(size=(5, 3)):
            xh = np.append(x, 1.0)
            assert np.allclose(T_a @ (X @ xh), T_b @ xh, atol=1e-12)  # the same point, reached both ways
        assert np.allclose(X[3], [0, 0, 0, 1]) and np.allclose(X[:3, :3].T @ X[:3, :3], np.eye(3))


def test_q4_worked_by_hand():
    # {A}: turned 90° about z, origin (1, 2, 3); {B}: not turned, origin (1, 3, 3), one step along y_0 = x_A
    T_a = np.array([[0.0, -1, 0, 1], [1, 0, 0, 2], [0, 0, 1, 3], [0, 0, 0, 1]])
    T_b = np.array([[1.0, 0, 0, 1], [0, 1, 0, 3], [0, 0, 1, 3], [0, 0, 0, 1]])
    expected = np.array([[0.0, 1, 0, 1], [-1, 0, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])  # x_B = -y_A, origin at x_A = 1
    assert np.allclose(chains.relative_pose(T_a, T_b), expected)
    assert np.allclose(formulas.pose_base_difference(T_a, T_b)[:3, 3], [0, 1, 0])
    assert np.allclose(formulas.pose_minus_p(T_a, T_b)[:3, 3], [2, -3, 0])  # R_aᵀ p_b - p_a = (3, -1, 3) - (1, 2, 3)


def test_q4_mistakes_are_the_swapped_frames_and_the_other_order():
    rng = np.random.default_rng(4)
    (T_a,), (T_b,) = chains.random_transforms(rng, 2)
    X = chains.relative_pose(T_a, T_b)
    assert np.allclose(formulas.pose_of_a_in_b(T_a, T_b) @ X, np.eye(4))
    assert np.allclose(formulas.pose_other_order(T_a, T_b) @ T_a, T_b)
