"""The geometric Jacobian against finite differences of the forward kinematics (an independent truth)."""

from __future__ import annotations

import numpy as np
import pytest

from puma_course.kinematics import MK3, DHChain, Link, Puma560
from puma_course.transforms import axis_angle


def _numeric_jacobian(chain, q, h=1e-6):
    """Central differences of fk: dp/dq_i and the rotation vector of R(q + h e_i) R(q - h e_i)^T / 2h."""
    J = np.zeros((6, chain.n))
    for i in range(chain.n):
        dq = np.zeros(chain.n)
        dq[i] = h
        Tp, Tm = DHChain.fk(chain, q + dq), DHChain.fk(chain, q - dq)
        J[:3, i] = (Tp[:3, 3] - Tm[:3, 3]) / (2 * h)
        k, t = axis_angle(Tp[:3, :3] @ Tm[:3, :3].T)
        J[3:, i] = k * t / (2 * h)
    return J


CHAINS = [
    Puma560(),
    MK3(),
    DHChain([Link(0, 0, 0.3), Link(-np.pi / 2, 0.2, 0.1, kind="P"), Link(0.7, 0.4, -0.2), Link(np.pi / 2, 0.1, 0.3)]),
]


@pytest.mark.parametrize("chain", CHAINS, ids=["PUMA-560", "MK3", "RPRR"])
def test_geometric_jacobian_equals_finite_differences(chain):
    rng = np.random.default_rng(5)
    for q in rng.uniform(-2.5, 2.5, (20, chain.n)):
        J = chain.jacobian(q)
        size = 1e3 if chain.units == "mm" else 1.0  # the MK3's linear columns are in mm per radian
        N = _numeric_jacobian(chain, q)
        assert np.allclose(J[:3], N[:3], atol=1e-6 * size) and np.allclose(J[3:], N[3:], atol=1e-6)


def test_batch_equals_rows_and_shapes():
    arm = Puma560()
    q = np.random.default_rng(6).uniform(-3, 3, (7, 6))
    J = arm.jacobian(q)
    assert J.shape == (7, 6, 6)
    assert np.allclose(J, np.stack([arm.jacobian(r) for r in q]))


def test_planar_two_link_by_hand():
    # two unit links at θ = (0, 90°): the tip is at (1, 1); J_v columns are z × (p_e - p_i)
    planar = DHChain([Link(0, 0), Link(0, 1.0), Link(0, 1.0)])
    J = planar.jacobian([0.0, np.pi / 2, 0.0])
    assert np.allclose(J[:3, 0], [-1.0, 1.0, 0.0]) and np.allclose(J[:3, 1], [-1.0, 0.0, 0.0])
    assert np.allclose(J[3:], [[0, 0, 0], [0, 0, 0], [1, 1, 1]])


def test_a_prismatic_column_is_its_axis():
    chain = CHAINS[2]
    q = np.array([0.3, 0.4, -0.2, 0.1])
    J = chain.jacobian(q)
    z2 = chain.frames(q)[2, :3, 2]
    assert np.allclose(J[:3, 1], z2) and np.allclose(J[3:, 1], 0.0)


# ---- issue 25: every arm against finite differences, and sympy's derivatives as a second truth --------------------


def _numeric_robot_jacobian(robot, q, h=1e-6):
    """Central differences of robot.fk (any arm): the same construction as ``_numeric_jacobian``."""
    J = np.zeros((6, robot.n))
    for i in range(robot.n):
        dq = np.zeros(robot.n)
        dq[i] = h
        Tp, Tm = robot.fk(q + dq), robot.fk(q - dq)
        J[:3, i] = (Tp[:3, 3] - Tm[:3, 3]) / (2 * h)
        k, t = axis_angle(Tp[:3, :3] @ Tm[:3, :3].T)
        J[3:, i] = k * t / (2 * h)
    return J


def test_porter_jacobian_equals_finite_differences():
    from puma_course.kinematics import Porter

    arm = Porter(1.0, 0.5, 0.3)
    rng = np.random.default_rng(25)
    Q = rng.uniform(-2.5, 2.5, (20, 6))
    Q[:, 2] = rng.uniform(0.1, 2.0, 20)  # the stroke
    for q in Q:
        assert np.allclose(arm.jacobian(q), _numeric_robot_jacobian(arm, q), atol=1e-6)
    assert np.allclose(arm.jacobian(Q), np.stack([arm.jacobian(q) for q in Q]))


def _sympy_jacobian(rows, thetas):
    """[∂p/∂θ; ω] by sympy: p is 0T_n's last column, ω_i read off skew(ω_i) = (∂R/∂θ_i) Rᵀ."""
    import sympy as sp

    from puma_course.symbolic import chain_sym

    _, T = chain_sym(rows, simplify=False)
    p, R = T[:3, 3], T[:3, :3]
    cols = []
    for t in thetas:
        W = R.diff(t) * R.T
        cols.append(list(p.diff(t)) + [W[2, 1], W[0, 2], W[1, 0]])
    return sp.Matrix(cols).T


@pytest.mark.parametrize("which", ["PUMA-560", "MK3"])
def test_geometric_jacobian_equals_sympy_derivatives(which):
    import sympy as sp

    from puma_course import symbolic

    if which == "PUMA-560":
        arm, rows, lengths = Puma560(), symbolic.puma560_table_sym(), symbolic.PUMA560_LENGTHS
    else:
        arm, rows, lengths = MK3(), symbolic.mk3_table_sym(), symbolic.MK3_LENGTHS
    thetas = symbolic.theta_symbols(arm.n)
    f = sp.lambdify((thetas, lengths), _sympy_jacobian(rows, thetas), "numpy")
    values = [arm.lengths[str(s)] for s in lengths]
    size = 1e3 if arm.units == "mm" else 1.0
    for q in np.random.default_rng(26).uniform(-np.pi, np.pi, (10, arm.n)):
        S = np.array(f(q, values), dtype=float)
        J = arm.jacobian(q)
        assert np.allclose(J[:3], S[:3], atol=1e-10 * size) and np.allclose(J[3:], S[3:], atol=1e-12)


def test_moving_the_reference_point_adds_omega_cross_r():
    # v at p' = v at p + ω × (p' - p): columns built about the shifted point agree with the rule
    from puma_course.kinematics.jacobian import jacobian_from_axes

    arm = Puma560()
    q = np.radians([30.0, -50.0, 20.0, 40.0, 60.0, -30.0])
    F = arm.frames(q)[:7]
    z, o, pe = F[1:, :3, 2], F[1:, :3, 3], F[6, :3, 3]
    r = np.array([0.0, 0.0, 0.1])
    J, Js = arm.jacobian(q), jacobian_from_axes(z, o, pe + F[6, :3, :3] @ r, arm.revolute)
    assert np.allclose(Js[:3], J[:3] + np.cross(J[3:].T, F[6, :3, :3] @ r).T) and np.allclose(Js[3:], J[3:])


@pytest.mark.parametrize(
    ("args", "name"),
    [
        ((np.zeros(3), np.zeros(3), np.zeros(3), [True]), "axes"),
        ((np.zeros((2, 3)), np.zeros((3, 3)), np.zeros(3), [True, True]), "points"),
        ((np.zeros((2, 3)), np.zeros((2, 3)), np.zeros(2), [True, True]), "pe"),
        ((np.zeros((2, 3)), np.zeros((2, 3)), np.zeros(3), [1, 0]), "revolute"),
        ((np.full((1, 3), np.nan), np.zeros((1, 3)), np.zeros(3), [True]), "axes"),
    ],
)
def test_jacobian_from_axes_rejects_bad_input_naming_it(args, name):
    from puma_course.kinematics.jacobian import jacobian_from_axes

    with pytest.raises(ValueError, match=name):
        jacobian_from_axes(*args)
