"""The three-step motion as joint paths, the wrist step on the geodesic or jointly interpolated (lecture 08).

Truths used here: the target {w, F} and the start pose the motion is asked to join (given, not computed by
the module); the forearm orientation Rz(θ0) Ry(-(θ1 + θ2)) built from the elementary rotations; the rotation
angle between two frames from its trace, arccos((tr(AᵀB) - 1) / 2); the two ZYZ solutions of a rotation checked
by rebuilding the rotation from them; and the geodesic's jump measured on the lecture's Exercise 1.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from puma_course.kinematics import ThreeStepArm
from puma_course.kinematics import three_step as ts
from puma_course.transforms import roty, rotz, wrap_angle

L1, L2 = 1.5, 1.0
W_EX = np.array([0.5, 0.5, 2.0])
TARGET_EX = np.diag([-1.0, 1.0, -1.0])
ARM = ThreeStepArm(L1, L2)


def turn(A: np.ndarray, B: np.ndarray) -> float:
    """The angle of the rotation carrying frame A onto frame B, from the trace."""
    return math.acos(min(1.0, max(-1.0, (np.trace(A.T @ B) - 1.0) / 2.0)))


def random_cases(n: int, seed: int = 2026_11_27):
    rng = np.random.default_rng(seed)
    cases = []
    while len(cases) < n:
        u = rng.normal(size=3)
        w = u / np.linalg.norm(u) * rng.uniform(0.7, 2.4)
        q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        F = q * np.sign(np.linalg.det(q))
        cases.append((w, F, "up" if len(cases) % 2 else "down"))
    return cases


def pose(F: np.ndarray, w: np.ndarray) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3], T[:3, 3] = F, w
    return T


def test_forearm_frames_are_yaw_then_pitch_up():
    rng = np.random.default_rng(7)
    j = rng.uniform(-3, 3, size=(5, 3))
    by_hand = np.stack([rotz(a) @ roty(-(b + c)) for a, b, c in j])
    assert np.allclose(ts.forearm_frames(j), by_hand, atol=1e-14)


@pytest.mark.parametrize("wrist", ts.WRIST_MOTIONS)
@pytest.mark.parametrize("case", range(12))
def test_both_motions_start_at_the_start_and_end_on_the_target(wrist, case):
    w, F, elbow = random_cases(12)[case]
    sol = ARM.three_step(w, F, elbow=elbow)
    q = ts.motion_joints(sol, steps_per_phase=5, wrist=wrist)
    assert q.shape == (16, 6)
    assert np.allclose(ARM.fk(q[0]), pose(np.eye(3), [L1 + L2, 0.0, 0.0]), atol=1e-12)  # the straight start
    assert np.allclose(ARM.fk(q[-1]), pose(F, w), atol=1e-12)  # the target {w, F}
    # steps 1 and 2 move the arm only: the wrist joints keep their start values (0 for the straight start)
    assert np.allclose(q[:11, 3:], 0.0, atol=1e-12)


@pytest.mark.parametrize("case", range(12))
def test_steps_1_and_2_agree_and_step_3_keeps_the_wrist_centre(case):
    w, F, elbow = random_cases(12)[case]
    sol = ARM.three_step(w, F, elbow=elbow)
    geo, joint = (ts.motion_joints(sol, 4, wrist=h) for h in ts.WRIST_MOTIONS)
    assert np.array_equal(geo[:9], joint[:9])
    assert np.allclose(ARM.fk(joint[8:])[:, :3, 3], w, atol=1e-12)  # the wrist turns about its centre


@pytest.mark.parametrize("case", range(12))
def test_the_joint_motion_steps_evenly_and_never_more_than_pi_over_n(case):
    w, F, elbow = random_cases(12)[case]
    sol = ARM.three_step(w, F, elbow=elbow)
    n = 6
    q = ts.motion_joints(sol, n, wrist="joint")
    steps = wrap_angle(np.diff(q[2 * n :], axis=0))
    assert np.allclose(steps, steps[0], atol=1e-12)  # a straight line in joint space, even steps
    assert np.abs(steps).max() <= math.pi / n + 1e-12  # each wrapped difference is at most π


@pytest.mark.parametrize("case", range(12))
def test_the_goal_is_the_nearer_of_the_two_wrist_solutions(case):
    w, F, elbow = random_cases(12)[case]
    sol = ARM.three_step(w, F, elbow=elbow)
    start = np.array([0.3, -0.2, 0.1])
    goal = ts.wrist_goal(sol, start)
    forearm = rotz(sol.theta0) @ roty(-(sol.theta1 + sol.theta2))
    relative = forearm.T @ F
    phi, th, psi = goal
    other = np.array([phi + math.pi, -th, psi + math.pi])
    for cand in (goal, other):  # both are wrist solutions of the target
        assert np.allclose(rotz(cand[0]) @ roty(cand[1]) @ rotz(cand[2]), relative, atol=1e-12)
    d_goal = np.linalg.norm(wrap_angle(goal - start))
    assert d_goal <= np.linalg.norm(wrap_angle(other - start)) + 1e-12


@pytest.mark.parametrize("case", range(12))
def test_the_geodesic_turns_evenly_and_is_never_longer(case):
    w, F, elbow = random_cases(12)[case]
    sol = ARM.three_step(w, F, elbow=elbow)
    n = 8
    frames = {h: ARM.fk(ts.motion_joints(sol, n, wrist=h)[2 * n :])[:, :3, :3] for h in ts.WRIST_MOTIONS}
    geo = [turn(a, b) for a, b in zip(frames["geodesic"][:-1], frames["geodesic"][1:], strict=True)]
    assert np.allclose(geo, sol.angle / n, atol=1e-7)  # one fixed axis, a steady rate, the angle of 𝒦 in all
    joint = sum(turn(a, b) for a, b in zip(frames["joint"][:-1], frames["joint"][1:], strict=True))
    assert joint >= sol.angle - 1e-7  # no path of the frame is shorter than the geodesic


def test_exercise_1_the_geodesic_jumps_159_degrees_and_the_joint_motion_25():
    sol = ARM.three_step(W_EX, TARGET_EX, elbow="up")
    n = 6
    geo = ts.motion_joints(sol, n)
    joint = ts.motion_joints(sol, n, wrist="joint")
    jump_geo = np.degrees(np.abs(wrap_angle(np.diff(geo, axis=0))).max())
    jump_joint = np.degrees(np.abs(wrap_angle(np.diff(joint, axis=0))).max())
    # the geodesic: at sample 12 ϑ = 0 (the ZYZ angles' singularity), then φ leaps to about 159°, ψ to -156°
    assert 155 < jump_geo < 162
    assert np.argmax(np.abs(wrap_angle(np.diff(geo, axis=0))).max(axis=1)) == 2 * n  # between samples 12 and 13
    # jointly: the goal's wrist (0°, -149.47°, 45°) is nearer (0, 0, 0) than (180°, 149.47°, -135°); ϑ moves 149.47/6
    assert np.allclose(np.degrees(joint[-1, 3:]), [0.0, -149.4723, 45.0], atol=1e-4)
    assert abs(jump_joint - 149.4723 / 6) < 1e-3
    # the trade-off: the frame turns a little farther than the geodesic, and not about one axis
    frames = ARM.fk(joint[2 * n :])[:, :3, :3]
    total = np.degrees(sum(turn(a, b) for a, b in zip(frames[:-1], frames[1:], strict=True)))
    assert np.degrees(sol.angle) + 2 < total < np.degrees(sol.angle) + 8  # 156.0° against 151.85°


def test_bad_input_is_refused_with_the_argument_named():
    sol = ARM.three_step(W_EX, TARGET_EX)
    with pytest.raises(ValueError, match="wrist: expected one of"):
        ts.motion_joints(sol, 4, wrist="cartesian")
    with pytest.raises(ValueError, match="result: expected the ThreeStepSolution"):
        ts.motion_joints("not a solution")
    with pytest.raises(ValueError, match="steps_per_phase"):
        ts.motion_joints(sol, 0)
    with pytest.raises(ValueError, match="start: expected three finite wrist angles"):
        ts.wrist_goal(sol, [0.0, np.nan, 0.0])


def test_finer_sampling_does_not_shrink_the_first_wrist_step_lecture_08_section_6():
    """The first step of φ and ψ on the geodesic tends to ±(the tilt's direction), not to 0, as n grows.

    Independent truth: near the start the wrist's relative rotation is I + s [ω]x, ω = axis · angle of
    Fa^T F (Fa the forearm frame at the end of step 2); its third column (s ω_y, -s ω_x, 1) gives
    φ -> atan2(-ω_x, ω_y), and φ + ψ -> 0. The lecture's numbers: 157.63° and -157.37° at 60 samples.
    """
    from puma_course.kinematics.three_step.wrist_paths import forearm_frames
    from puma_course.transforms import axis_angle

    sol = ARM.three_step(W_EX, TARGET_EX, elbow="up")
    q6 = ts.motion_joints(sol, 6)
    axis, _ = axis_angle(forearm_frames(q6[12, :3]).T @ sol.target)
    limit = math.degrees(math.atan2(-axis[0], axis[1]))
    assert limit == pytest.approx(157.5, abs=1e-9)
    firsts = {}
    for n in (6, 60, 600, 6000):
        q = ts.motion_joints(sol, n)
        firsts[n] = np.degrees(q[2 * n + 1, 3:] - q[2 * n, 3:])
    np.testing.assert_allclose(firsts[60][[0, 2]], [157.63, -157.37], atol=0.005)  # not "still 157.5"
    np.testing.assert_allclose(firsts[600][[0, 2]], [157.51, -157.49], atol=0.005)
    gaps = [abs(firsts[n][0] - limit) for n in (6, 60, 600, 6000)]
    assert all(b < a / 5 for a, b in zip(gaps, gaps[1:], strict=False))  # it settles on the limit ...
    assert gaps[-1] < 0.01
    assert firsts[6000][0] + firsts[6000][2] == pytest.approx(0.0, abs=0.01)  # ... with ψ = -φ
    assert abs(firsts[6000][1]) < 0.03  # while ϑ's first step shrinks with the sample period
