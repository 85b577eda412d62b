"""Base, tool and station frames (issue 25, 1c): world = base · arm · tool, by hand and by round trips."""

from __future__ import annotations

import numpy as np
import pytest

from puma_course.kinematics import MK3, Puma560, arm_target, world_pose
from puma_course.transforms import homogeneous, rodrigues


def _random_frame(rng, scale=1.0):
    axis = rng.normal(size=3)
    return homogeneous(rodrigues(axis / np.linalg.norm(axis), rng.uniform(-3, 3)), rng.uniform(-scale, scale, 3))


def test_world_pose_maps_the_tool_point_as_the_frames_say():
    # the tool's origin, followed by hand: flange coordinates -> base -> world
    rng = np.random.default_rng(250)
    arm = Puma560()
    for _ in range(10):
        base, tool = _random_frame(rng), _random_frame(rng, 0.2)
        A = arm.fk(rng.uniform(-np.pi, np.pi, 6))
        in_base = A[:3, :3] @ tool[:3, 3] + A[:3, 3]
        in_world = base[:3, :3] @ in_base + base[:3, 3]
        W = world_pose(base, A, tool)
        assert np.allclose(W[:3, 3], in_world)
        assert np.allclose(W[:3, :3], base[:3, :3] @ A[:3, :3] @ tool[:3, :3])


def test_round_trips_and_batches():
    rng = np.random.default_rng(251)
    base, tool = _random_frame(rng), _random_frame(rng, 0.2)
    A = Puma560().fk(rng.uniform(-np.pi, np.pi, (5, 6)))
    W = world_pose(base, A, tool)
    assert W.shape == (5, 4, 4) and np.allclose(arm_target(W, base, tool), A)
    assert np.allclose(world_pose(base, arm_target(W, base, tool), tool), W)
    assert np.allclose(world_pose(None, A[0]), A[0]) and np.allclose(arm_target(A[0]), A[0])


@pytest.mark.parametrize("arm", [Puma560(), MK3()], ids=["PUMA-560", "MK3"])
def test_ik_of_the_arm_target_puts_the_tool_on_the_world_goal(arm):
    rng = np.random.default_rng(252)
    size = 1e3 if arm.units == "mm" else 1.0
    base, tool = _random_frame(rng, size), _random_frame(rng, 0.1 * size)
    q0 = rng.uniform(-2.0, 2.0, arm.n)
    goal = world_pose(base, arm.fk(q0), tool)  # a reachable goal for the tool, named in the world
    sol = arm.ik(arm_target(goal, base, tool), near=q0)
    assert sol.success and np.allclose(sol[0], q0, atol=1e-7)
    for q in sol:
        assert np.allclose(world_pose(base, arm.fk(q), tool), goal, atol=1e-8 * size)


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda: world_pose(np.ones((4, 4)), np.eye(4)), "base"),
        (lambda: world_pose(None, np.eye(3)), "arm_pose"),
        (lambda: world_pose(None, np.eye(4), 2 * np.eye(4)), "tool"),
        (lambda: arm_target(np.full((4, 4), np.nan)), "world_T"),
    ],
)
def test_bad_frames_are_named(call, name):
    with pytest.raises(ValueError, match=name):
        call()
