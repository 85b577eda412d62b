"""The three-step wrist-frame inverse kinematics against independent truths.

Truths used here: the exercise's numbers worked by hand from the law of cosines;
eq. (1) written out again in this file (``eq1`` below), not the module's; the
physical forearm orientation Rz(θ0) Ry(-(θ1 + θ2)) derived by hand; matrix
properties (orthonormal, det 1, K a = a); and round trips on random targets.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from puma_course import three_step as ts
from puma_course.transforms import rotx, roty, rotz

SEED = 20261122
L1, L2 = 1.5, 1.0
W_EX = np.array([0.5, 0.5, 2.0])
TARGET_EX = np.column_stack([[-1.0, 0, 0], [0, 1.0, 0], [0, 0, -1.0]])  # (f1, f2, f3) = (-e_x, e_y, -e_z)


def eq1(t0: float, t1: float, t2: float, l1: float, l2: float) -> np.ndarray:
    """Eq. (1) of the source, typed in again component by component."""
    return np.array(
        [
            l1 * math.cos(t0) * math.cos(t1) + l2 * math.cos(t0) * math.cos(t1 + t2),
            l1 * math.sin(t0) * math.cos(t1) + l2 * math.sin(t0) * math.cos(t1 + t2),
            l1 * math.sin(t1) + l2 * math.sin(t1 + t2),
        ]
    )


def elbow_eq1(t0: float, t1: float, l1: float) -> np.ndarray:
    return np.array([l1 * math.cos(t0) * math.cos(t1), l1 * math.sin(t0) * math.cos(t1), l1 * math.sin(t1)])


def forearm_orientation(t0: float, t1: float, t2: float) -> np.ndarray:
    """Orientation of a frame carried by the forearm: yaw θ0 about z, then pitch θ1 + θ2 up.

    Pitching up by σ about the horizontal y axis of the arm plane is Ry(-σ)
    (Ry(+σ) would tip x downwards), so R = Rz(θ0) Ry(-(θ1 + θ2)).
    """
    return rotz(t0) @ roty(-(t1 + t2))


def random_rotation(rng: np.random.Generator) -> np.ndarray:
    Q, R = np.linalg.qr(rng.normal(size=(3, 3)))
    Q = Q * np.sign(np.diag(R))
    if np.linalg.det(Q) < 0:
        Q[:, 0] = -Q[:, 0]
    return Q


def assert_rotation(R: np.ndarray, atol: float = 1e-12) -> None:
    assert np.allclose(R.T @ R, np.eye(3), atol=atol)
    assert math.isclose(np.linalg.det(R), 1.0, abs_tol=atol)


# ---------------------------------------------------------------------------------------------
# Exercise 1, worked by hand
# ---------------------------------------------------------------------------------------------


def hand_numbers() -> dict[str, float]:
    l3 = math.sqrt(0.5**2 + 0.5**2 + 2.0**2)  # sqrt(4.5)
    cos_theta = (4.5 + 2.25 - 1.0) / (2 * 1.5 * math.sqrt(4.5))  # eq. (5)
    cos_beta = (2.25 + 1.0 - 4.5) / (2 * 1.5 * 1.0)  # interior angle at the elbow
    phi = math.atan(2.0 / math.sqrt(0.5))  # elevation of w above the floor
    return {
        "l3": l3,
        "theta0": math.pi / 4,  # w_x = w_y > 0
        "theta": math.acos(cos_theta),
        "beta": math.acos(cos_beta),
        "phi": phi,
    }


def test_hand_numbers_themselves():
    h = hand_numbers()
    assert math.isclose(h["l3"] ** 2, 4.5)
    assert math.isclose(math.cos(h["theta"]), 5.75 / (3 * math.sqrt(4.5)))
    assert math.isclose(math.degrees(h["theta"]), 25.3746, abs_tol=1e-4)
    assert math.isclose(math.degrees(h["phi"]), 70.5288, abs_tol=1e-4)
    assert math.isclose(math.degrees(h["beta"]), 114.6243, abs_tol=1e-4)
    # the triangle's angles: θ at the shoulder, β at the elbow, the rest at the wrist
    gamma = math.acos((1.0 + 4.5 - 2.25) / (2 * 1.0 * math.sqrt(4.5)))
    assert math.isclose(h["theta"] + h["beta"] + gamma, math.pi)


@pytest.mark.parametrize("elbow, sign", [("up", 1.0), ("down", -1.0)])
def test_exercise_1_angles_by_hand(elbow, sign):
    h = hand_numbers()
    sol = ts.solve(W_EX, TARGET_EX, L1, L2, elbow=elbow)
    assert sol.singular == ()
    assert math.isclose(sol.theta0, h["theta0"], abs_tol=1e-12)
    assert math.isclose(sol.delta0, h["theta0"], abs_tol=1e-12)  # start θ̄0 = 0
    assert math.isclose(sol.theta, h["theta"], abs_tol=1e-12)
    assert math.isclose(sol.phi, h["phi"], abs_tol=1e-12)
    assert math.isclose(sol.theta1, h["phi"] + sign * h["theta"], abs_tol=1e-12)
    assert math.isclose(sol.theta2, -sign * (math.pi - h["beta"]), abs_tol=1e-12)
    assert math.isclose(sol.delta, sol.theta1 + sol.theta2, abs_tol=1e-12)  # start θ̄1 = θ̄2 = 0
    # eq. (1) reaches w on both branches
    assert np.allclose(eq1(sol.theta0, sol.theta1, sol.theta2, L1, L2), W_EX, atol=1e-12)
    # the elbow is at distance l1 from the shoulder and l2 from the wrist
    e = elbow_eq1(sol.theta0, sol.theta1, L1)
    assert math.isclose(np.linalg.norm(W_EX - e), L2, abs_tol=1e-12)


def test_exercise_1_the_two_branches_by_number():
    up = ts.solve(W_EX, TARGET_EX, L1, L2, elbow="up")
    down = ts.solve(W_EX, TARGET_EX, L1, L2, elbow="down")
    assert math.isclose(math.degrees(up.theta1), 95.9034, abs_tol=1e-4)
    assert math.isclose(math.degrees(up.theta2), -65.3757, abs_tol=1e-4)
    assert math.isclose(math.degrees(down.theta1), 45.1542, abs_tol=1e-4)
    assert math.isclose(math.degrees(down.theta2), 65.3757, abs_tol=1e-4)


@pytest.mark.parametrize("elbow", ["up", "down"])
def test_elbow_up_is_above_the_shoulder_wrist_line(elbow):
    sol = ts.solve(W_EX, TARGET_EX, L1, L2, elbow=elbow)
    e = elbow_eq1(sol.theta0, sol.theta1, L1)
    r_hat = np.array([math.cos(sol.theta0), math.sin(sol.theta0), 0.0])
    # in the arm plane (r, z): cross(w, e) > 0 means e lies above the line from s to w
    side = (W_EX @ r_hat) * e[2] - W_EX[2] * (e @ r_hat)
    assert (side > 0) if elbow == "up" else (side < 0)


def test_exercise_1_rotations_by_hand():
    sol = ts.solve(W_EX, TARGET_EX, L1, L2, elbow="up")
    c = math.sqrt(0.5)
    assert np.allclose(sol.K_base, [[c, -c, 0], [c, c, 0], [0, 0, 1]], atol=1e-12)  # Rz(45°)
    assert np.allclose(sol.a, [c, -c, 0], atol=1e-12)  # (sin 45°, -cos 45°, 0)
    # frames after each step: K_base F̄ with F̄ = I, then K(a, δ), then the target
    assert np.allclose(sol.frame_step1, sol.K_base, atol=1e-12)
    assert np.allclose(sol.frame_step2, forearm_orientation(sol.theta0, sol.theta1, sol.theta2), atol=1e-12)
    assert np.allclose(sol.frame_step3, TARGET_EX, atol=1e-12)
    product = sol.K_wrist @ sol.K_arm @ sol.K_base @ np.eye(3)
    assert np.abs(product - TARGET_EX).max() < 1e-12
    # the composite rotation: a rotation, fixing its axis, by its angle
    assert_rotation(sol.K_wrist)
    assert np.allclose(sol.K_wrist @ sol.axis, sol.axis, atol=1e-12)
    assert math.isclose((np.trace(sol.K_wrist) - 1) / 2, math.cos(sol.angle), abs_tol=1e-12)
    # the step-2 frame's x axis is the forearm direction (the arm is straight at the start)
    fore = W_EX - elbow_eq1(sol.theta0, sol.theta1, L1)
    assert np.allclose(sol.frame_step2[:, 0], fore / L2, atol=1e-12)


def test_composite_is_unique_and_equals_target_times_step2_transpose():
    # K F2 = F has the unique solution K = F F2^{-1} = F F2^T: check column by column
    sol = ts.solve(W_EX, TARGET_EX, L1, L2)
    for i in range(3):
        assert np.allclose(sol.K_wrist @ sol.frame_step2[:, i], TARGET_EX[:, i], atol=1e-12)
    assert np.allclose(sol.K_wrist, sum(np.outer(TARGET_EX[:, i], sol.frame_step2[:, i]) for i in range(3)))


@pytest.mark.parametrize("elbow", ["up", "down"])
def test_zyz_wrist_angles_reproduce_the_target(elbow):
    sol = ts.solve(W_EX, TARGET_EX, L1, L2, elbow=elbow)
    phi, theta, psi = sol.wrist_zyz
    assert 0 <= theta <= math.pi
    W = rotz(phi) @ roty(theta) @ rotz(psi)
    assert np.allclose(sol.frame_step2 @ W, TARGET_EX, atol=1e-12)
    # the same rotation seen from the base: K_wrist = F2 W F2^T
    assert np.allclose(sol.frame_step2 @ W @ sol.frame_step2.T, sol.K_wrist, atol=1e-12)


# ---------------------------------------------------------------------------------------------
# Eq. (1) as the module computes it (joint_points, wrist_position) against eq1 typed in here
# ---------------------------------------------------------------------------------------------


def test_joint_points_and_wrist_position_follow_eq1():
    rng = np.random.default_rng(SEED + 4)
    t = rng.uniform(-math.pi, math.pi, (40, 3))
    P = ts.joint_points(t[:, 0], t[:, 1], t[:, 2], L1, L2)
    W = ts.wrist_position(t[:, 0], t[:, 1], t[:, 2], L1, L2)
    assert P.shape == (40, 3, 3) and W.shape == (40, 3)
    for k, (t0, t1, t2) in enumerate(t):
        assert np.allclose(P[k, 0], 0.0, atol=0)  # the shoulder is the origin
        assert np.allclose(P[k, 1], elbow_eq1(t0, t1, L1), atol=1e-12)
        assert np.allclose(P[k, 2], eq1(t0, t1, t2, L1, L2), atol=1e-12)
        assert np.allclose(W[k], eq1(t0, t1, t2, L1, L2), atol=1e-12)
    # hand-worked: θ0 = 90°, θ1 = 0, θ2 = 90° puts the elbow at (0, l1, 0) and the wrist l2 above it
    assert np.allclose(ts.joint_points(math.pi / 2, 0.0, math.pi / 2, L1, L2), [[0, 0, 0], [0, L1, 0], [0, L1, L2]])
    # scalars broadcast against a batch
    assert np.allclose(ts.wrist_position(0.3, t[:, 1], 0.0, L1, L2)[:, 2], (L1 + L2) * np.sin(t[:, 1]))


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: ts.joint_points(0.0, 0.0, 0.0, 0.0, 1.0), "^l1: expected a positive length"),
        (lambda: ts.wrist_position(0.0, 0.0, 0.0, 1.0, -1.0), "^l2: expected a positive length"),
        (lambda: ts.joint_points(np.nan, 0.0, 0.0, 1.0, 1.0), "^theta0: expected finite"),
        (lambda: ts.joint_points(0.0, "up", 0.0, 1.0, 1.0), "^theta1: "),
        (lambda: ts.arm_axis("x"), "^theta0: "),
        (lambda: ts.arm_axis(np.inf), "^theta0: expected finite"),
        (lambda: ts.as_state(3), "^start: expected None, an ArmState"),
        (lambda: ts.as_state((0.0, 0.0, 0.0, [1, 0, 0], [0, 1, 0], [0, 0])), "^start f3: "),
    ],
)
def test_eq1_helpers_bad_input(call, match):
    with pytest.raises(ValueError, match=match):
        call()


# ---------------------------------------------------------------------------------------------
# The sign of a in eq. (4) and the step composition
# ---------------------------------------------------------------------------------------------


def test_turning_about_a_increases_theta1():
    rng = np.random.default_rng(SEED)
    for t0, t1, d in rng.uniform(-3, 3, size=(50, 3)):
        K = ts.rodrigues(ts.arm_axis(t0), d)
        assert np.allclose(K @ elbow_eq1(t0, t1, L1), elbow_eq1(t0, t1 + d, L1), atol=1e-12)
        # and the whole arm: both points turn together when θ1 grows by d
        t2 = rng.uniform(-3, 3)
        assert np.allclose(K @ eq1(t0, t1, t2, L1, L2), eq1(t0, t1 + d, t2, L1, L2), atol=1e-12)
    # the opposite sign of a would turn the arm the other way
    K_wrong = ts.rodrigues(-ts.arm_axis(0.3), 0.5)
    assert not np.allclose(K_wrong @ elbow_eq1(0.3, 0.1, L1), elbow_eq1(0.3, 0.6, L1))


def test_step_rotations_equal_the_change_of_forearm_orientation():
    # K(a, δ) K(e_z, δ0) = R(θ) R(θ̄)^T with R the forearm orientation: the source's steps are exact
    rng = np.random.default_rng(SEED + 1)
    for _ in range(50):
        start = rng.uniform(-math.pi, math.pi, 3)
        goal = rng.uniform(-math.pi, math.pi, 3)
        w = eq1(*goal, L1, L2)
        sol = ts.solve(w, np.eye(3), L1, L2, start=(start[0], start[1], start[2], np.eye(3)))
        expected = forearm_orientation(sol.theta0, sol.theta1, sol.theta2) @ forearm_orientation(*start).T
        assert np.allclose(sol.K_arm @ sol.K_base, expected, atol=1e-12)


# ---------------------------------------------------------------------------------------------
# Random reachable targets (seeded)
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("elbow", ["up", "down"])
def test_random_targets_round_trip(elbow):
    rng = np.random.default_rng(SEED + 2)
    for _ in range(300):
        l1, l2 = rng.uniform(0.2, 3.0, 2)
        goal = rng.uniform(-math.pi, math.pi, 3)
        w = eq1(*goal, l1, l2)
        if np.hypot(w[0], w[1]) < 1e-6:
            continue
        F = random_rotation(rng)
        start = ts.ArmState(*rng.uniform(-math.pi, math.pi, 3), random_rotation(rng))
        sol = ts.solve(w, F, l1, l2, elbow=elbow, start=start)
        assert np.allclose(eq1(sol.theta0, sol.theta1, sol.theta2, l1, l2), w, atol=1e-9)
        assert np.abs(sol.K_wrist @ sol.K_arm @ sol.K_base @ start.frame - F).max() < 1e-12
        for K in (sol.K_base, sol.K_arm, sol.K_wrist, sol.frame_step1, sol.frame_step2, sol.frame_step3):
            assert_rotation(K, atol=1e-11)
        W = rotz(sol.wrist_zyz[0]) @ roty(sol.wrist_zyz[1]) @ rotz(sol.wrist_zyz[2])
        assert np.allclose(sol.frame_step2 @ W, F, atol=1e-9)
        assert np.allclose(ts.rodrigues(sol.axis, sol.angle), sol.K_wrist, atol=1e-9)
        assert -math.pi < sol.theta1 <= math.pi


finite_angle = st.floats(-math.pi, math.pi, allow_nan=False)


@settings(derandomize=True, max_examples=150, deadline=None)
@given(
    t0=finite_angle,
    t1=finite_angle,
    t2=finite_angle,
    l1=st.floats(0.1, 5.0),
    l2=st.floats(0.1, 5.0),
    elbow=st.sampled_from(["up", "down"]),
)
def test_hypothesis_the_wrist_centre_is_reached(t0, t1, t2, l1, l2, elbow):
    w = eq1(t0, t1, t2, l1, l2)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ts.ThreeStepWarning)
        sol = ts.solve(w, rotx(t0) @ rotz(t2), l1, l2, elbow=elbow)
    assert np.all(np.isfinite(sol.joints))
    assert np.allclose(eq1(sol.theta0, sol.theta1, sol.theta2, l1, l2), w, atol=1e-8 * (l1 + l2))
    # the two branches: up has θ2 <= 0, down θ2 >= 0
    assert (sol.theta2 <= 1e-12) if elbow == "up" else (sol.theta2 >= -1e-12)


def test_start_formats_agree():
    rng = np.random.default_rng(SEED + 3)
    F0 = random_rotation(rng)
    t = (0.2, -0.4, 0.9)
    forms = [
        ts.ArmState(*t, F0),
        {"theta0": t[0], "theta1": t[1], "theta2": t[2], "frame": F0},
        {"theta0": t[0], "theta1": t[1], "theta2": t[2], "F": F0},
        (*t, F0),
        (*t, F0[:, 0], F0[:, 1], F0[:, 2]),
    ]
    sols = [ts.solve(W_EX, TARGET_EX, L1, L2, start=s) for s in forms]
    for s in sols[1:]:
        assert np.array_equal(s.K_wrist, sols[0].K_wrist)
        assert s.delta0 == sols[0].delta0 and s.delta == sols[0].delta
    default = ts.solve(W_EX, TARGET_EX, L1, L2)
    assert np.array_equal(default.start.frame, np.eye(3)) and default.start.joints.tolist() == [0, 0, 0]


# ---------------------------------------------------------------------------------------------
# Singular and boundary cases
# ---------------------------------------------------------------------------------------------


def test_wrist_on_the_base_axis_keeps_the_start_base_angle_and_warns():
    start = ts.ArmState(0.7, 0.0, 0.0, np.eye(3))
    with pytest.warns(ts.ThreeStepWarning, match="base axis"):
        sol = ts.solve([0.0, 0.0, 2.0], TARGET_EX, L1, L2, start=start)
    assert sol.theta0 == 0.7 and sol.delta0 == 0.0
    assert any("base axis" in s for s in sol.singular)
    assert np.allclose(sol.K_base, np.eye(3))
    assert np.allclose(eq1(sol.theta0, sol.theta1, sol.theta2, L1, L2), [0, 0, 2], atol=1e-12)
    assert np.abs(sol.K_wrist @ sol.K_arm @ sol.K_base - TARGET_EX).max() < 1e-12
    # straight down too
    with pytest.warns(ts.ThreeStepWarning):
        down = ts.solve([0.0, 0.0, -1.0], TARGET_EX, L1, L2, elbow="down")
    assert np.allclose(eq1(down.theta0, down.theta1, down.theta2, L1, L2), [0, 0, -1], atol=1e-12)


def test_wrist_at_the_shoulder_with_equal_links():
    with pytest.warns(ts.ThreeStepWarning, match="shoulder"):
        sol = ts.solve([0.0, 0.0, 0.0], np.eye(3), 1.0, 1.0, start=(0.0, 0.3, 0.0, np.eye(3)))
    assert sol.theta1 == 0.3 and math.isclose(abs(sol.theta2), math.pi)
    assert np.all(np.isfinite(sol.joints))
    assert np.allclose(eq1(sol.theta0, sol.theta1, sol.theta2, 1.0, 1.0), 0.0, atol=1e-12)


@pytest.mark.parametrize("elbow", ["up", "down"])
def test_stretched_and_folded_boundaries(elbow):
    d = np.array([1.0, 2.0, 2.0]) / 3.0  # a unit direction
    stretched = ts.solve((L1 + L2) * d, np.eye(3), L1, L2, elbow=elbow)
    # exact: a wrist within tolerance of the stretched boundary is snapped onto it by design
    assert stretched.theta2 == 0.0 and stretched.theta == 0.0
    assert np.allclose(eq1(*stretched.joints, L1, L2), (L1 + L2) * d, atol=1e-12)
    folded = ts.solve((L1 - L2) * d, np.eye(3), L1, L2, elbow=elbow)
    assert math.isclose(abs(folded.theta2), math.pi, abs_tol=1e-12)
    assert np.allclose(eq1(*folded.joints, L1, L2), (L1 - L2) * d, atol=1e-12)


def test_composite_of_zero_and_half_turn():
    plain = ts.solve(W_EX, np.eye(3), L1, L2)
    same = ts.solve(W_EX, plain.frame_step2, L1, L2)  # no wrist motion needed
    assert same.angle == pytest.approx(0.0, abs=1e-7)
    assert np.allclose(same.K_wrist, np.eye(3), atol=1e-12)
    half = plain.frame_step2 @ rotx(math.pi)  # a half turn about f1 of the step-2 frame
    sol = ts.solve(W_EX, half, L1, L2)
    assert sol.angle == pytest.approx(math.pi)
    assert np.allclose(abs(sol.axis @ plain.frame_step2[:, 0]), 1.0)
    m = ts.motion(sol, steps_per_phase=5)
    assert np.allclose(m.frames[-1], half, atol=1e-12)
    assert np.allclose(ts.rodrigues(sol.axis, sol.angle) @ sol.frame_step2, half, atol=1e-9)


# ---------------------------------------------------------------------------------------------
# motion()
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("elbow", ["up", "down"])
def test_motion_starts_at_start_and_ends_at_target(elbow):
    start = ts.ArmState(-0.5, 0.3, 0.4, rotx(0.3) @ rotz(1.0))
    sol = ts.solve(W_EX, TARGET_EX, L1, L2, elbow=elbow, start=start)
    n = 10
    m = ts.motion(sol, steps_per_phase=n)
    T = 3 * n + 1
    assert m.points.shape == (T, 3, 3) and m.frames.shape == (T, 3, 3) and m.path.shape == (T, 3)
    assert m.joints.shape == (T, 3) and m.phase.tolist() == [0] + [1] * n + [2] * n + [3] * n
    # start
    assert np.allclose(m.frames[0], start.frame) and np.allclose(m.joints[0], start.joints)
    assert np.allclose(m.path[0], eq1(*start.joints, L1, L2))
    assert np.allclose(m.points[0, 0], 0.0)
    # the ends of the phases are the step frames
    assert np.allclose(m.frames[n], sol.frame_step1, atol=1e-12)
    assert np.allclose(m.frames[2 * n], sol.frame_step2, atol=1e-12)
    assert np.allclose(m.frames[-1], TARGET_EX, atol=1e-12)
    assert np.allclose(m.path[-1], W_EX, atol=1e-12)
    # every sample: the points obey eq. (1), links keep their lengths, frames are rotations
    for k in range(T):
        assert np.allclose(m.points[k, 2], eq1(*m.joints[k], L1, L2), atol=1e-12)
        assert math.isclose(np.linalg.norm(m.points[k, 1]), L1)
        assert math.isclose(np.linalg.norm(m.points[k, 2] - m.points[k, 1]), L2)
        assert_rotation(m.frames[k])
    # phase 1 keeps the height, phase 3 keeps the arm still
    assert np.allclose(m.path[: n + 1, 2], m.path[0, 2])
    assert np.allclose(m.points[2 * n :], m.points[-1])
    # the path is continuous: no jump between samples larger than a small arc
    steps = np.linalg.norm(np.diff(m.path, axis=0), axis=1)
    assert steps.max() < (L1 + L2) * max(abs(sol.delta0), abs(sol.delta), 1e-9) / n * 2.5


def test_motion_frames_follow_the_step_rotations():
    sol = ts.solve(W_EX, TARGET_EX, L1, L2)
    m = ts.motion(sol, steps_per_phase=4)
    # halfway through phase 2 the frame is K(a, δ/2) F1, i.e. the forearm orientation at half the joints
    mid = m.frames[4 + 2]
    assert np.allclose(mid, ts.rodrigues(sol.a, sol.delta / 2) @ sol.frame_step1, atol=1e-12)
    assert np.allclose(mid, forearm_orientation(*m.joints[6]), atol=1e-12)


# ---------------------------------------------------------------------------------------------
# Bad input
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"w": [3.0, 0.0, 0.0]}, "exceeds l1 \\+ l2"),
        ({"w": [0.2, 0.0, 0.1]}, "less than \\|l1 - l2\\|"),
        ({"w": [0.5, 0.5]}, "^w: "),
        ({"w": [np.nan, 0.5, 2.0]}, "^w: "),
        ({"target": np.diag([1.0, 1.0, -1.0])}, "^target: .*reflection"),
        ({"target": 2 * np.eye(3)}, "^target: .*rotation"),
        ({"target": np.eye(4)}, "^target: "),
        ({"l1": 0.0}, "^l1: "),
        ({"l2": -1.0}, "^l2: "),
        ({"elbow": "left"}, "^elbow: .*'up' or 'down'"),
        ({"elbow": 1}, "^elbow: "),
        ({"start": (0.0, 0.0)}, "^start: "),
        ({"start": {"theta3": 0.0}}, "^start: .*theta3"),
        ({"start": (0.0, 0.0, 0.0, np.diag([-1.0, 1.0, 1.0]))}, "^start.frame: "),
        ({"start": "straight"}, "^start: "),
    ],
)
def test_bad_input_raises_with_a_reason(kwargs, match):
    args = {"w": W_EX, "target": TARGET_EX, "l1": L1, "l2": L2, **kwargs}
    with pytest.raises(ValueError, match=match):
        ts.solve(**args)


def test_motion_bad_input():
    sol = ts.solve(W_EX, TARGET_EX, L1, L2)
    for bad in (0, -3, 2.5, True):
        with pytest.raises(ValueError, match="steps_per_phase"):
            ts.motion(sol, steps_per_phase=bad)
    with pytest.raises(ValueError, match="result"):
        ts.motion({"theta0": 0.0})


def test_results_are_immutable():
    sol = ts.solve(W_EX, TARGET_EX, L1, L2)
    with pytest.raises(AttributeError):
        sol.theta0 = 1.0  # type: ignore[misc]
    with pytest.raises(ValueError):
        sol.K_wrist[0, 0] = 2.0


def test_wrist_next_to_the_base_axis_is_snapped_onto_it():
    # Within the solver's tolerance 1e-9 (l1 + l2) of the base axis, w counts as on it: θ0 is
    # free and the start value is kept, exactly (by design), instead of atan2 of two rounding
    # residues whose signs decide a 90° swing of the base.
    w = np.array([1e-12, -1e-12, 2.0])
    start = ts.ArmState(0.3, 0.0, 0.0)
    with pytest.warns(ts.ThreeStepWarning, match="base axis"):
        sol = ts.solve(w, TARGET_EX, L1, L2, start=start)
    assert sol.theta0 == 0.3  # the start value, snapped by design
    assert np.allclose(eq1(*sol.joints, L1, L2), w, atol=1e-9 * (L1 + L2))


@pytest.mark.parametrize("ulps", [-2, -1, 1, 2])
def test_boundary_answers_do_not_depend_on_the_last_bit(ulps):
    # |w| one or two ulps either side of l1 + l2 (as different BLAS kernels produce) gives
    # the same, snapped answer: θ = 0 and θ2 = 0 exactly.
    d = np.array([1.0, 2.0, 2.0]) / 3.0
    r = np.nextafter(L1 + L2, np.inf if ulps > 0 else -np.inf)
    for _ in range(abs(ulps) - 1):
        r = np.nextafter(r, np.inf if ulps > 0 else -np.inf)
    sol = ts.solve(r * d, np.eye(3), L1, L2)
    ref = ts.solve((L1 + L2) * d, np.eye(3), L1, L2)
    assert sol.theta2 == 0.0 and sol.theta == 0.0  # snapped by design
    assert sol.theta1 == ref.theta1 and sol.theta0 == ref.theta0


def test_regular_targets_do_not_warn():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        sol = ts.solve(W_EX, TARGET_EX, L1, L2, elbow="down")
    assert sol.singular == ()
