"""Damped-least-squares IK (issue 25, 1d) against the closed forms: it lands on the pose and in the closed-form set."""

from __future__ import annotations

import numpy as np
import pytest

from puma_course.kinematics import MK3, Porter, Puma560, ik_dls, joint_distance


def _start(arm, rng):
    q = rng.uniform(-2.0, 2.0, arm.n)
    if isinstance(arm, Porter):
        q[2] = rng.uniform(0.5, 1.5)
    return q


@pytest.mark.parametrize("arm", [Puma560(), MK3(), Porter(1.0, 0.5, 0.3)], ids=["PUMA-560", "MK3", "Porter"])
def test_dls_reaches_the_pose_and_lands_in_the_closed_form_set(arm):
    rng = np.random.default_rng(253)
    size = 1e3 if arm.units == "mm" else 1.0
    for _ in range(8):
        q_star = _start(arm, rng)
        T = arm.fk(q_star)
        res = ik_dls(arm, T, q_star + rng.uniform(-0.2, 0.2, arm.n))
        assert res.success and np.all(np.isfinite(res.q))
        assert np.allclose(arm.fk(res.q), T, atol=1e-9 * size)
        closed = arm.ik(T)
        assert min(float(joint_distance(res.q, q)) for q in closed) < 1e-6


def test_dls_from_near_each_branch_converges_to_that_branch():
    arm = Puma560()
    rng = np.random.default_rng(254)
    T = arm.fk(np.radians([30.0, -50.0, 20.0, 40.0, 60.0, -30.0]))
    closed = arm.ik(T)
    for label, q_branch in zip(closed.labels, closed, strict=True):
        res = ik_dls(arm, T, q_branch + rng.uniform(-0.1, 0.1, 6))
        d = [float(joint_distance(res.q, q)) for q in closed]
        assert res.success and closed.labels[int(np.argmin(d))] == label and min(d) < 1e-6


def test_an_unreachable_pose_is_a_failure_with_finite_numbers():
    arm = Puma560()
    T = np.eye(4)
    T[:3, 3] = [2.0, 0.0, 0.0]  # beyond the reach of 0.877 m
    res = ik_dls(arm, T, arm.q("qn"), max_iter=50)
    assert not res.success and res.residual > 0.5 and np.all(np.isfinite(res.q)) and res.iterations == 50


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"robot": object()}, "robot"),
        ({"T": np.eye(3)}, "T"),
        ({"q0": np.zeros(5)}, "q0"),
        ({"q0": np.zeros((2, 6))}, "q0"),
        ({"damping": 0.0}, "damping"),
        ({"tol": float("nan")}, "tol"),
        ({"length": -1.0}, "length"),
        ({"max_iter": 0}, "max_iter"),
    ],
)
def test_bad_input_is_named(kwargs, name):
    arm = Puma560()
    args = {"robot": arm, "T": arm.fk(arm.q("qn")), "q0": arm.q("qz")} | kwargs
    with pytest.raises(ValueError, match=name):
        ik_dls(args.pop("robot"), args.pop("T"), args.pop("q0"), **args)
