"""The fast Jacobians (issue 33): the PUMA-560's closed form and the one-walk column formula for any DH chain,
each against an independent truth on thousands of random poses, with the tolerance written down."""

from __future__ import annotations

import math

import numpy as np
import pytest

from puma_course.kinematics import MK3, DHChain, Link, Puma560
from puma_course.kinematics.jacobian import geometric_jacobian, jacobian_from_axes
from puma_course.kinematics.puma560_jacobian import puma560_jacobian_rows

#: Entries are lengths (m) or unit-vector components, all of magnitude <= 1.5 here: two computations of the
#: same expression in double precision differ by a few 1e-16; 1e-12 leaves room without hiding a wrong term.
TOL = 1e-12


def _random_q(n, count, seed):
    return np.random.default_rng(seed).uniform(-math.pi, math.pi, (count, n))


ARMS = [Puma560(), Puma560(a2=0.7, a3=-0.05, d3=0.0, d4=0.3), Puma560(a2=1.0, a3=0.2, d3=-0.3, d4=0.0)]


@pytest.mark.parametrize("arm", ARMS, ids=["lecture", "d3=0", "d4=0"])
def test_closed_form_equals_the_generic_column_walk_on_thousands_of_poses(arm):
    """Puma560.jacobian (closed form) against geometric_jacobian (cross products of the walked frames)."""
    Q = _random_q(6, 5000, 33)
    generic = geometric_jacobian(arm, Q)
    assert np.abs(arm.jacobian(Q) - generic).max() < TOL
    for q in Q[:500]:  # the one-pose path (plain floats) too
        assert np.abs(arm.jacobian(q) - geometric_jacobian(arm, q)).max() < TOL


def test_closed_form_equals_jacobian_from_axes_of_the_frames():
    """A third computation: the validated, array-based jacobian_from_axes on arm.frames (4 x 4 arrays)."""
    arm = Puma560()
    Q = _random_q(6, 3000, 34)
    F = arm.frames(Q)
    J = jacobian_from_axes(F[:, 1:7, :3, 2], F[:, 1:7, :3, 3], F[:, 6, :3, 3], arm.revolute)
    assert np.abs(arm.jacobian(Q) - J).max() < TOL


def _fd_jacobian(fk, Q, h=1e-6):
    """Central differences of fk, batched: dp/dq_i, and ω_i from the skew part of R(q + h e_i) R(q - h e_i)ᵀ.

    The skew part is sin(φ) k for the small rotation φ k between the two (φ ≈ 2h |ω_i|), so ω_i is
    vee((M - Mᵀ)/2) / 2h with a relative error of φ²/6 < 1e-11."""
    N, n = Q.shape
    J = np.zeros((N, 6, n))
    for i in range(n):
        dq = np.zeros(n)
        dq[i] = h
        Tp, Tm = fk(Q + dq), fk(Q - dq)
        J[:, :3, i] = (Tp[:, :3, 3] - Tm[:, :3, 3]) / (2 * h)
        M = Tp[:, :3, :3] @ np.swapaxes(Tm[:, :3, :3], -1, -2)
        vee = np.stack([M[:, 2, 1] - M[:, 1, 2], M[:, 0, 2] - M[:, 2, 0], M[:, 1, 0] - M[:, 0, 1]], -1)
        J[:, 3:, i] = vee / (4 * h)
    return J


#: Central differences with h = 1e-6: truncation ~h² |fk'''| < 1e-11, rounding ~1e-16 / h = 1e-10 per entry.
FD_TOL = 1e-8


@pytest.mark.parametrize("arm", ARMS, ids=["lecture", "d3=0", "d4=0"])
def test_closed_form_equals_finite_differences_of_fk_on_thousands_of_poses(arm):
    Q = _random_q(6, 3000, 35)
    assert np.abs(arm.jacobian(Q) - _fd_jacobian(arm.fk, Q)).max() < FD_TOL
    # and of the other fk (the column walk of DHChain), so no shared code decides the answer
    assert np.abs(arm.jacobian(Q[:500]) - _fd_jacobian(lambda X: DHChain.fk(arm, X), Q[:500])).max() < FD_TOL


CHAINS = {
    "MK3": MK3(),
    "RPRR": DHChain(
        [Link(0, 0, 0.3), Link(-np.pi / 2, 0.2, 0.1, kind="P"), Link(0.7, 0.4, -0.2), Link(np.pi / 2, 0.1, 0.3)]
    ),
    "tool": DHChain([Link(0, 0, 0.2), Link(np.pi / 2, 0.3, 0.0), Link(0.0, 0.5, 0.1)], tool=np.diag([1, -1, -1, 1.0])),
}


@pytest.mark.parametrize("name", list(CHAINS))
def test_one_walk_jacobian_equals_the_array_formula_and_finite_differences(name):
    """geometric_jacobian (one walk, written-out cross products) against jacobian_from_axes on frames()
    and against finite differences of the chain's fk; the tool transform is not part of the Jacobian."""
    chain = CHAINS[name]
    size = 1e3 if chain.units == "mm" else 1.0
    Q = _random_q(chain.n, 2000, 36)
    J = geometric_jacobian(chain, Q)
    F = chain.frames(Q)[:, : chain.n + 1]
    ref = jacobian_from_axes(F[:, 1:, :3, 2], F[:, 1:, :3, 3], F[:, -1, :3, 3], chain.revolute)
    assert np.abs(J - ref).max() < TOL * size
    untooled = DHChain(chain.links)
    assert np.abs(J - _fd_jacobian(untooled.fk, Q)).max() < FD_TOL * size
    for k in range(200):  # the one-pose path (plain floats)
        assert np.abs(geometric_jacobian(chain, Q[k]) - ref[k]).max() < TOL * size


def test_the_closed_form_is_sympys_jacobian_symbolically():
    """puma560_jacobian_rows on sympy symbols equals the geometric Jacobian sympy builds from the DH table:
    ∂w/∂θ of the symbolic wrist centre (the origin of frame {6}) over the z axes of the symbolic frames {1}..{6}.
    Every entry of the difference expands to the polynomial 0: an identity, not a sample of poses."""
    sp = pytest.importorskip("sympy")
    from types import SimpleNamespace

    from puma_course import symbolic

    thetas = symbolic.theta_symbols(6)
    mats, _ = symbolic.chain_sym(symbolic.puma560_table_sym(), simplify=False)
    F = [sp.eye(4)]
    for m in mats:
        F.append(F[-1] * m)
    S = sp.Matrix.vstack(F[6][:3, 3].jacobian(sp.Matrix(thetas)), sp.Matrix.hstack(*(F[i][:3, 2] for i in range(1, 7))))
    o = SimpleNamespace(cos=sp.cos, sin=sp.sin)
    C = sp.Matrix(6, 6, puma560_jacobian_rows(o, list(thetas), *symbolic.PUMA560_LENGTHS))
    for i in range(6):
        for k in range(6):
            assert sp.expand(sp.expand_trig(S[i, k] - C[i, k])) == 0, (i, k)
    # the check can fail: one wrong sign in the closed form leaves a non-zero difference
    assert sp.expand(sp.expand_trig(S[2, 1] + C[2, 1])) != 0


def test_one_pose_and_batch_agree_and_inputs_are_checked_once_at_the_entry():
    arm = Puma560()
    Q = _random_q(6, 50, 37)
    J = arm.jacobian(Q)
    assert J.shape == (50, 6, 6) and J.dtype == np.float64 and J.flags.c_contiguous
    one = arm.jacobian(Q[3])
    assert one.shape == (6, 6) and one.flags.c_contiguous and np.abs(one - J[3]).max() < 1e-15
    assert np.array_equal(arm.jacobian(Q[3].tolist()), one)  # a list: the general check, same numbers
    assert arm.jacobian(np.zeros((0, 6))).shape == (0, 6, 6)
    assert np.array_equal(arm.jacobian(np.zeros(6, dtype=int)), arm.jacobian(np.zeros(6)))
    for bad in (np.full(6, np.nan), np.zeros(5), np.zeros((2, 7)), "q", None, np.full(6, 1e200)):
        with pytest.raises(ValueError, match="q"):
            arm.jacobian(bad)
    for bad in (np.zeros(3), [np.inf, 0, 0, 0, 0, 0]):
        with pytest.raises(ValueError, match="q"):
            geometric_jacobian(CHAINS["MK3"] if len(bad) != 6 else arm, bad)
