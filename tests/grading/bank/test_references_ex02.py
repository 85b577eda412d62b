"""The references of ex02 q1-q2 (as issue 22 changed them) against independent truths.

q1 reads a link's four parameters off the world poses of its two frames: poses built by hand and from
sympy's link matrix with known parameters are read back, and the frames' geometry (the twist from z_{i-1} to
z_i about x_{i-1}, ...) gives the same numbers. q2 is ⁱT_{i-1}: sympy's ``mdh_sym(...).inv()``, the product
with the link matrix (the identity on either side), and a link worked by hand. The mistaken matrices q2
names are checked against what their messages say they are (the standard-DH matrix, multiplied by sympy).
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from puma_course.grading import EXERCISES
from puma_course.symbolic import mdh_sym, rot, trans
from puma_course.transforms import rotz

EX = EXERCISES["ex02_dh_frames"]  # loads the bank
import puma_course_bank._formulas as formulas  # noqa: E402
import puma_course_bank._reference.chains as chains  # noqa: E402

AL, A, TH, D = sp.symbols("alpha a theta d", real=True)
LINK = sp.lambdify((AL, A, TH, D), mdh_sym(AL, A, TH, D), modules="numpy")
STANDARD = sp.lambdify((AL, A, TH, D), rot("z", TH) * trans("z", D) * trans("x", A) * rot("x", AL), modules="numpy")


def link(*params: float) -> np.ndarray:
    return np.array(LINK(*params), dtype=float)


def test_q1_reads_a_pose_worked_by_hand():
    # {i-1} at (1, 2, 3) turned a quarter about z: x_{i-1} = y0, y_{i-1} = -x0. The link α = 90°, a = 0.5, θ = 0,
    # d = 0.2 puts {i} at a x_{i-1} - d y_{i-1} (z_i = -y_{i-1}) with x_i = x_{i-1}: at (1.2, 2.5, 3), axes
    # x_i = y0, y_i = z0, z_i = x0.
    T_prev = np.eye(4)
    T_prev[:3, :3], T_prev[:3, 3] = rotz(np.pi / 2), [1.0, 2.0, 3.0]
    T = np.array([[0.0, 0.0, 1.0, 1.2], [1.0, 0.0, 0.0, 2.5], [0.0, 1.0, 0.0, 3.0], [0.0, 0.0, 0.0, 1.0]])
    assert np.allclose(EX.question("q1").reference(T_prev, T), [np.pi / 2, 0.5, 0.0, 0.2])


def geometry(T_prev: np.ndarray, T: np.ndarray) -> np.ndarray:
    """The four parameters from the frames' axes in the world (lecture 02 §3's definitions)."""
    x0, z0, x1, z1, step = T_prev[:3, 0], T_prev[:3, 2], T[:3, 0], T[:3, 2], T[:3, 3] - T_prev[:3, 3]
    return np.array(
        [np.arctan2(np.cross(z0, z1) @ x0, z0 @ z1), step @ x0, np.arctan2(np.cross(x0, x1) @ z1, x0 @ x1), step @ z1]
    )


def test_q1_reads_back_the_parameters_the_poses_were_built_from():
    rng = np.random.default_rng(22)
    q = EX.question("q1")
    for _ in range(200):
        params = [rng.uniform(-3.0, 3.0), rng.uniform(-1, 1), rng.uniform(-3.0, 3.0), rng.uniform(-1, 1)]
        M, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        T_prev = np.eye(4)
        T_prev[:3, :3], T_prev[:3, 3] = M * np.sign(np.linalg.det(M)), rng.uniform(-2, 2, 3)
        T = T_prev @ link(*params)
        got = q.reference(T_prev, T)
        assert np.allclose(got, params) and np.allclose(got, geometry(T_prev, T))


@pytest.mark.parametrize("seed", range(10))
def test_q1_cases_rebuild_and_separate_the_sign_of_alpha(seed):
    q = EX.question("q1")
    cases = q.cases(np.random.default_rng(seed))
    untwisted = 0
    for T_prev, T in cases:
        p = q.reference(T_prev, T)
        assert np.allclose(T_prev @ link(*p), T)
        assert not np.allclose(T_prev, np.eye(4))  # ⁰T_i differs from the link matrix
        untwisted += abs(np.sin(p[0])) < 1e-9
    assert untwisted == 1  # the one case where -α is the same twist


def test_q2_is_sympys_inverse_of_the_link_matrix():
    inverse = sp.lambdify((AL, A, TH, D), sp.simplify(mdh_sym(AL, A, TH, D).inv()), modules="numpy")
    rng = np.random.default_rng(2)
    q = EX.question("q2")
    for params in rng.uniform(-3, 3, size=(50, 4)):
        ref = q.reference(*params)
        assert np.allclose(ref, np.array(inverse(*params), dtype=float))
        assert np.allclose(ref @ link(*params), np.eye(4)) and np.allclose(link(*params) @ ref, np.eye(4))


def test_q2_worked_by_hand():
    # α = 90°, a = 1, θ = 0, d = 0: {i} sits at x = 1 of {i-1}, its z along -y_{i-1}. The origin of {i-1} is one
    # unit back along x_i, and y_{i-1} (= -z_i) is -z in {i}.
    T = EX.question("q2").reference(np.pi / 2, 1.0, 0.0, 0.0)
    assert np.allclose(T @ [0.0, 0.0, 0.0, 1.0], [-1.0, 0.0, 0.0, 1.0])
    assert np.allclose(T[:3, :3] @ [0.0, 1.0, 0.0], [0.0, 0.0, -1.0])


def test_q2_s_mistaken_matrices_are_what_their_messages_say():
    rng = np.random.default_rng(3)
    for params in rng.uniform(-3, 3, size=(20, 4)):
        std = np.array(STANDARD(*params), dtype=float)
        assert np.allclose(chains.mdh_reversed(*params), std)  # reversed, not negated: the standard-DH matrix
        assert np.allclose(chains.mdh_negated(*params), np.linalg.inv(std))  # negated in order: standard inverted
        assert np.allclose(chains.mdh_transposed(*params), link(*params).T)
        R, p = link(*params)[:3, :3], link(*params)[:3, 3]
        assert np.allclose(chains.mdh_inverse_minus_p(*params)[:3], np.column_stack([R.T, -p]))
        assert np.allclose(chains.mdh_inverse_plus_p(*params)[:3], np.column_stack([R.T, p]))


def test_q1_s_mistaken_readings_read_the_matrices_their_messages_name():
    rng = np.random.default_rng(4)
    for _ in range(20):
        params = rng.uniform(-2.5, 2.5, 4)
        T_prev = np.eye(4)
        T_prev[:3, :3], T_prev[:3, 3] = rotz(rng.uniform(0.3, 3.0)), rng.uniform(-1, 1, 3)
        L = link(*params)
        T = T_prev @ L
        # off ⁱT_{i-1} = (⁰T_i)⁻¹ ⁰T_{i-1} = L⁻¹, and off ⁰T_i (⁰T_{i-1})⁻¹ = ⁰T_{i-1} L (⁰T_{i-1})⁻¹
        assert np.allclose(formulas.parameters_of_inverse(T_prev, T), formulas.link_parameters(np.linalg.inv(L)))
        conj = T_prev @ L @ np.linalg.inv(T_prev)
        assert np.allclose(formulas.parameters_in_order(T_prev, T), formulas.link_parameters(conj))
        assert np.allclose(formulas.parameters_of_pose(T_prev, T), formulas.link_parameters(T))
        assert np.allclose(formulas.standard_reading_between(T_prev, T), formulas.standard_reading(L))


def _craig_link(L: np.ndarray) -> float:
    """a of L after checking that L is a link matrix of Craig's convention (lecture 02 §2-§3): a rigid pose whose
    z_i is normal to x_{i-1} (x_{i-1} lies along the common normal) and whose origin is a x_{i-1} + d z_i."""
    R, p = L[:3, :3], L[:3, 3]
    assert np.allclose(L[3], [0.0, 0.0, 0.0, 1.0]) and np.allclose(R.T @ R, np.eye(3))
    assert np.isclose(np.linalg.det(R), 1.0)
    assert abs(R[0, 2]) < 1e-9  # z_i ⟂ x_{i-1}
    assert np.allclose(np.cross(p - [p[0], 0.0, 0.0], R[:, 2]), 0.0)  # the rest of the step lies along z_i
    return float(p[0])


@pytest.mark.parametrize("seed", range(10))
def test_every_q1_and_q2_case_is_a_valid_craig_link_with_a_distance_a(seed):
    """Craig's a_{i-1} is the distance between the z axes (a >= 0): every case of q1 (public and hidden) is a pair of
    frames whose link matrix, computed here with numpy's inverse, is a valid link with a > 0; every case of q2 has
    a > 0 and gives such a matrix."""
    for T_prev, T in EX.question("q1").cases(np.random.default_rng(seed)):
        T_prev, T = np.asarray(T_prev, dtype=float), np.asarray(T, dtype=float)
        R = T_prev[:3, :3]
        assert np.allclose(T_prev[3], [0.0, 0.0, 0.0, 1.0]) and np.allclose(R.T @ R, np.eye(3))
        assert _craig_link(np.linalg.inv(T_prev) @ T) > 0.05
    for alpha, a, theta, d in EX.question("q2").cases(np.random.default_rng(seed)):
        assert a > 0.05
        assert np.isclose(_craig_link(link(alpha, a, theta, d)), a)
