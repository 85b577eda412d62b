"""The one robot API: every arm of the course answers the same calls, with the same result type, the
same policy for unreachable poses, the same angle range and the same warning hierarchy."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from puma_course.kinematics import (
    MK3,
    DHChain,
    IKBatch,
    IKSolutions,
    KinematicsWarning,
    Link,
    Porter,
    Puma560,
    Robot,
    SingularityWarning,
    ThreeStepArm,
)
from puma_course.kinematics.ik import dedupe_mask, joint_distance, keys_from_bits, nearest_index
from puma_course.kinematics.three_step import ThreeStepWarning

ROBOTS = [Puma560(), MK3(), Porter(1.0, 0.5, 0.3), ThreeStepArm(1.5, 1.0)]
IDS = [type(r).__name__ for r in ROBOTS]


def _qs(robot: Robot, n: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    lo, hi = robot.qlim[:, 0], robot.qlim[:, 1]
    return rng.uniform(lo, hi, (n, robot.n))


@pytest.mark.parametrize("robot", ROBOTS, ids=IDS)
def test_every_robot_answers_the_api(robot):
    assert isinstance(robot, Robot)
    assert robot.revolute.dtype == bool and robot.revolute.shape == (robot.n,)
    assert robot.qlim.shape == (robot.n, 2) and (robot.qlim[:, 0] < robot.qlim[:, 1]).all()
    assert len(robot.joint_symbols) == robot.n and robot.configurations
    q = _qs(robot, 5, 1)
    assert robot.fk(q).shape == (5, 4, 4) and robot.fk(q[0]).shape == (4, 4)
    F = robot.frames(q)
    assert F.shape[0] == 5 and F.shape[2:] == (4, 4) and np.allclose(F[:, -1], robot.fk(q))
    assert robot.points(q).shape[0] == 5 and robot.points(q).shape[-1] == 3
    sol = robot.ik(robot.fk(q[0]))
    assert isinstance(sol, IKSolutions) and sol.success and sol.q.shape[1] == robot.n
    b = robot.ik_batch(robot.fk(q))
    assert isinstance(b, IKBatch) and b.q.shape[0] == 5 and b.q.shape[2] == robot.n
    html = robot._repr_html_()
    assert "<table" in html and robot.name.split()[0] in html
    for name in robot.configurations:
        assert robot.q(name).shape == (robot.n,)


@pytest.mark.parametrize("robot", ROBOTS, ids=IDS)
def test_one_pose_ik_equals_the_batch_for_that_pose(robot):
    q = _qs(robot, 40, 2)
    T = robot.fk(q)
    b = robot.ik_batch(T)
    for i in range(len(q)):
        s = robot.ik(T[i])
        bi = b.solutions(i)
        assert s.labels == bi.labels and s.flags == bi.flags
        assert np.abs(joint_distance(s.q, bi.q, robot.revolute)).max() < 1e-9


@pytest.mark.parametrize("robot", ROBOTS, ids=IDS)
def test_fk_of_every_solution_reaches_the_pose_and_angles_are_wrapped(robot):
    q = _qs(robot, 300, 3)
    T = robot.fk(q)
    b = robot.ik_batch(T)
    scale = max(1.0, float(np.abs(T[:, :3, 3]).max()))
    Tq = robot.fk(b.q.reshape(-1, robot.n)).reshape(b.q.shape[:2] + (4, 4))
    err = np.abs(Tq - T[:, None]).max(axis=(2, 3)) / scale
    assert err[b.valid].max() < 1e-9
    ang = b.q[..., robot.revolute]
    assert (ang > -np.pi).all() and (ang <= np.pi).all()
    assert np.isfinite(b.q).all()


@pytest.mark.parametrize("robot", ROBOTS, ids=IDS)
def test_one_policy_for_unreachable_poses(robot):
    """Never a raise, never NaN: success False, no rows, a reason in words (Porter needs a stroke limit)."""
    if isinstance(robot, Porter):
        robot = Porter(1.0, 0.5, 0.3, q2_max=1.0)
    T = np.eye(4)
    T[:3, :3] = np.diag([1.0, -1.0, -1.0])
    T[:3, 3] = [1e4, 0.0, 0.0]
    sol = robot.ik(T)
    assert not sol.success and sol.q.shape == (0, robot.n) and sol.reason
    assert "unreachable" in repr(sol)
    b = robot.ik_batch(np.stack([T, robot.fk(robot.q(next(iter(robot.configurations))))]))
    assert b.reachable.tolist() == [False, True] and b.reason[0] and not b.valid[0].any()
    assert np.isfinite(b.q).all() and (b.q[0] == 0).all()


def test_warning_hierarchy_is_one_tree():
    assert issubclass(SingularityWarning, KinematicsWarning) and issubclass(KinematicsWarning, UserWarning)
    assert issubclass(ThreeStepWarning, KinematicsWarning)
    arm = Puma560()
    q = np.array([0.3, -0.6, 0.2, 0.9, 0.0, 0.4])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        arm.ik(arm.fk(q))
    assert [w.category for w in caught] == [SingularityWarning]
    assert "wrist" in str(caught[0].message)


def test_a_general_dh_chain_is_a_robot_without_closed_form_ik():
    chain = DHChain([Link(0, 0, 0), Link(0, 1.0, 0)], name="planar")
    assert isinstance(chain, Robot) and chain.fk([0.1, 0.2]).shape == (4, 4)
    with pytest.raises(NotImplementedError):
        chain.ik(np.eye(4))


# ---------------------------------------------------------------- the result type and its helpers
def test_ik_solutions_checks_its_fields_and_is_read_only():
    with pytest.raises(ValueError, match="labels, flags: expected one per solution"):
        IKSolutions(np.zeros((2, 3)), labels=("a",))
    with pytest.raises(ValueError, match="q: expected solutions of shape"):
        IKSolutions(np.zeros(3))
    with pytest.raises(ValueError, match="revolute: expected a boolean mask"):
        IKSolutions(np.zeros((1, 3)), revolute=[1, 1, 1])
    sol = IKSolutions(np.zeros((2, 3)))
    assert sol.labels == ("solution 1", "solution 2") and sol.flags == ((), ())
    with pytest.raises(ValueError):
        sol.q[0, 0] = 1.0


def test_sorted_by_and_nearest_by_hand():
    Q = np.array([[3.0, 0.0], [0.0, 0.0], [-3.1, 1.0]])
    sol = IKSolutions(Q, ("a", "b", "c"), ((), ("wrist",), ()), {"wrist": "aligned"})
    s = sol.sorted_by([3.1, 0.0])  # 0.04 from a, 0.08 + 1 from c (across ±π), 3.1 from b
    assert s.labels == ("a", "c", "b") and s.flags == ((), (), ("wrist",))
    assert np.allclose(sol.nearest([-3.0, 0.0]), [3.0, 0.0])  # 0.28 across ±π beats 0.1 + 1
    assert s.messages == {"wrist": "aligned"} and s.singular == ("wrist",)


def test_helpers_by_hand():
    rev = np.array([True, False])
    assert int(nearest_index(np.array([[0.0, 5.0], [3.0, 0.0]]), np.array([-3.0, 0.0]), rev)) == 1
    assert int(nearest_index(np.array([[0.0, 5.0], [3.0, 0.0]]), np.array([-3.0, 0.0]), rev,
                             np.array([True, False]))) == 0  # fmt: skip
    assert dedupe_mask(np.array([[1.0, 2.0], [1.0 + 2 * np.pi, 2.0], [1.0, 2.0 + 2 * np.pi]]), rev).tolist() == [
        True, False, True  # a length is not wrapped: 2 and 2 + 2π differ
    ]  # fmt: skip
    assert keys_from_bits(6, ("a", "b", "c")) == ("b", "c") and keys_from_bits(0, ("a",)) == ()


# ---- issue 25: joint limits in IK selection ------------------------------------------------------------------------


def test_within_limits_keeps_exactly_the_rows_inside_every_range():
    from puma_course.kinematics import Puma560

    arm = Puma560()
    q0 = np.radians([30.0, -50.0, 20.0, 40.0, 60.0, -30.0])
    sol = arm.ik(arm.fk(q0))
    qlim = np.radians([[-160, 160], [-225, 45], [-45, 225], [-110, 170], [-100, 100], [-266, 266]])
    kept = sol.within_limits(qlim)
    inside = [bool(np.all((q >= qlim[:, 0]) & (q <= qlim[:, 1]))) for q in sol.q]  # the rule, row by row
    assert len(kept) == sum(inside) and kept.labels == tuple(lb for lb, i in zip(sol.labels, inside, strict=True) if i)
    assert any(np.allclose(q, q0) for q in kept)  # the configuration we started from is inside
    for q in kept:
        assert np.allclose(arm.fk(q), arm.fk(q0), atol=1e-9)


def test_within_limits_with_nothing_left_is_a_failure_with_a_reason():
    from puma_course.kinematics import Puma560

    arm = Puma560()
    sol = arm.ik(arm.fk(np.radians([30.0, -50.0, 20.0, 40.0, 60.0, -30.0])))
    tight = np.zeros((6, 2))  # every joint must be exactly zero
    none = sol.within_limits(tight)
    assert not none.success and len(none) == 0 and "joint limits" in none.reason and "θ1" in none.reason
    with pytest.raises(IndexError):
        none[0]


@pytest.mark.parametrize("bad", [np.zeros((5, 2)), [[1.0, 0.0]] * 6, [[0.0, np.nan]] * 6])
def test_within_limits_rejects_bad_limits_naming_qlim(bad):
    from puma_course.kinematics import Puma560

    arm = Puma560()
    sol = arm.ik(arm.fk(np.zeros(6) + 0.3))
    with pytest.raises(ValueError, match="qlim"):
        sol.within_limits(bad)
