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
