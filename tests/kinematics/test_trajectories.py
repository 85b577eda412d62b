"""Cartesian paths and joint paths: geometry of the paths by hand, joint paths checked through the
forward kinematics, the nearest-continuation rule against the naive first solution at a wrist flip."""

from __future__ import annotations

import numpy as np
import pytest

from puma_course.kinematics import Porter, Puma560
from puma_course.kinematics import trajectories as tr
from puma_course.kinematics.ik import joint_distance
from puma_course.transforms import rotx, rotz

ARM = Puma560()


# ---------------------------------------------------------------- paths
def test_line_path_endpoints_spacing_and_fixed_orientation():
    T0 = np.eye(4)
    T0[:3, :3] = rotz(0.3) @ rotx(0.2)
    T0[:3, 3] = [0.1, 0.2, 0.3]
    T1 = np.eye(4)
    T1[:3, 3] = [0.4, -0.1, 0.6]  # T1's rotation (identity) is ignored
    P = tr.line_path(T0, T1, 7)
    assert P.shape == (7, 4, 4)
    assert np.allclose(P[0, :3, 3], [0.1, 0.2, 0.3]) and np.allclose(P[-1, :3, 3], [0.4, -0.1, 0.6])
    steps = np.diff(P[:, :3, 3], axis=0)
    assert np.allclose(steps, [0.05, -0.05, 0.05])  # (0.3, -0.3, 0.3) / 6 by hand
    assert np.allclose(P[:, :3, :3], T0[:3, :3])
    assert np.allclose(P[:, 3], [0, 0, 0, 1])
    assert np.allclose(tr.line_path(T0, [0.4, -0.1, 0.6], 7), P)


def test_circle_path_geometry():
    c, r, nrm = np.array([0.2, 0.1, 0.4]), 0.15, np.array([1.0, 1.0, 0.0])
    R = rotz(0.5)
    P = tr.circle_path(c, r, nrm, R, 41)
    pts = P[:, :3, 3]
    assert np.allclose(np.linalg.norm(pts - c, axis=1), r)
    assert np.allclose((pts - c) @ nrm, 0.0)
    assert np.allclose(pts[0], pts[-1])  # closed
    assert np.allclose(P[:, :3, :3], R)
    # counter-clockwise seen from the tip of the normal: (p0 - c) x (p1 - c) points along the normal
    assert np.cross(pts[0] - c, pts[1] - c) @ nrm > 0
    # equal steps: chord 2 r sin(π / 40)
    assert np.allclose(np.linalg.norm(np.diff(pts, axis=0), axis=1), 2 * r * np.sin(np.pi / 40))
    P2 = tr.circle_path(c, r, [0, 0, 1], R, 5, start=[0, 1, 0])
    assert np.allclose(P2[0, :3, 3], c + [0, r, 0])


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: tr.line_path(np.eye(4), [1, 2], 5), "T1"),
        (lambda: tr.line_path(np.eye(3), [1, 2, 3], 5), "T0"),
        (lambda: tr.line_path(np.eye(4), [1, 2, 3], 1), "n"),
        (lambda: tr.circle_path([0, 0, 0], 1.0, [0, 0, 0], np.eye(3), 5), "normal"),
        (lambda: tr.circle_path([0, 0, 0], -1.0, [0, 0, 1], np.eye(3), 5), "radius"),
        (lambda: tr.circle_path([0, 0, 0], 1.0, [0, 0, 1], 2 * np.eye(3), 5), "R"),
        (lambda: tr.circle_path([0, 0, 0], 1.0, [0, 0, 1], np.eye(3), 5, start=[0, 0, 2]), "start"),
    ],
)
def test_bad_path_input(call, match):
    with pytest.raises(ValueError, match=match):
        call()


# ---------------------------------------------------------------- joint paths on the PUMA-560
def _wrist_flip_path(n: int = 60):
    """A vertical line whose middle pose has θ5 = 0 on the branch left/up: the wrist flips there."""
    qm = np.array([0.0, -0.6, 0.3, 0.0, 0.0, 0.0])
    Tm = ARM.fk(qm)
    d = np.array([0.0, 0.0, 0.15])
    T0 = Tm.copy()
    T0[:3, 3] -= d
    return tr.line_path(T0, Tm[:3, 3] + d, n), qm


def test_follow_reaches_every_pose_and_moves_smoothly():
    q0 = ARM.q("qn")
    T0 = ARM.fk(q0)
    path = tr.circle_path(T0[:3, 3] - [0, 0.1, 0], 0.1, [1, 0, 0], T0[:3, :3], 200, start=[0, 1, 0])
    jp = tr.follow(ARM, path, q0)
    assert jp.q.shape == (200, 6)
    assert np.abs(ARM.fk(jp.q) - path).max() < 1e-9
    assert jp.start_jump < 1e-9
    # a chord of 2π·0.1/199 ≈ 3 mm needs only small joint steps; and the loop closes on itself
    assert jp.max_step < 0.05
    assert joint_distance(jp.q[0], jp.q[-1]) < 1e-9


def test_follow_stays_on_the_branch_of_q0():
    q_right = ARM.ik(ARM.fk(ARM.q("qn")))
    k = q_right.labels.index("right/down/flip")
    q0 = q_right[k]
    path = tr.line_path(ARM.fk(q0), ARM.fk(q0)[:3, 3] + [0.0, 0.05, 0.05], 30)
    jp = tr.follow(ARM, path, q0)
    assert (jp.choice == 7).all()  # branch index of right/down/flip in BRANCH_LABELS
    assert jp.start_jump < 1e-9 and jp.max_step < 0.05
    nv = tr.naive(ARM, path, q0)
    assert (nv.choice == 0).all()
    assert nv.start_jump > 1.0  # the naive first solution is another arm altogether
    assert nv.start_jump == pytest.approx(float(joint_distance(nv.q[0], q0)))


def test_naive_jumps_at_the_wrist_flip_follow_does_not():
    path, qm = _wrist_flip_path()
    q0 = ARM.ik(path[0]).nearest(qm)
    jp = tr.follow(ARM, path, q0)
    nv = tr.naive(ARM, path)
    assert np.abs(ARM.fk(jp.q) - path).max() < 1e-9
    assert np.abs(ARM.fk(nv.q) - path).max() < 1e-9
    # θ5 changes sign along the path; the continuous solution crosses from noflip to flip
    assert jp.q[0, 4] * jp.q[-1, 4] < 0
    assert set(jp.choice.tolist()) == {0, 1}
    assert jp.max_step < 0.05
    # the naive choice stays on "noflip" and so turns θ4 and θ6 by π at once: a step of sqrt(2) π
    assert nv.max_step == pytest.approx(np.sqrt(2) * np.pi, abs=0.02)


def test_unreachable_path_raises_with_the_pose_index():
    T0 = ARM.fk(ARM.q("qn"))
    path = tr.line_path(T0, [1.5, 0.0, 0.0], 10)
    with pytest.raises(ValueError, match="pose [0-9] of the path"):
        tr.follow(ARM, path, ARM.q("qn"))
    with pytest.raises(ValueError, match="^robot: expected a robot of the course"):
        tr.follow(object(), path, ARM.q("qn"))
    with pytest.raises(ValueError, match="q0"):
        tr.follow(ARM, path[:1], np.zeros(5))


def test_step_distance_and_unwrap():
    assert joint_distance([np.pi - 0.1, 0.0], [-np.pi + 0.1, 0.0]) == pytest.approx(0.2)
    # a prismatic joint is not wrapped
    assert joint_distance([0.0, 7.0], [0.0, 0.0], revolute=[True, False]) == pytest.approx(7.0)
    q = np.array([[3.0, 1.0], [-3.0, 2.0], [-2.9, 9.0]])
    u = tr.unwrap(q, revolute=[True, False])
    assert np.allclose(u[:, 0], [3.0, 2 * np.pi - 3.0, 2 * np.pi - 2.9])
    assert np.allclose(u[:, 1], q[:, 1])


def test_thousand_pose_path_is_vectorised_enough():
    """Not a timing assert: only that 1,000 poses go through the batched solver in one call."""
    q0 = ARM.q("qn")
    T0 = ARM.fk(q0)
    path = tr.circle_path(T0[:3, 3] - [0, 0.1, 0], 0.1, [1, 0, 0], T0[:3, :3], 1000, start=[0, 1, 0])
    calls = []

    class Counting(Puma560):
        def ik_batch(self, T, near=None, **kw):
            calls.append(len(T))
            return super().ik_batch(T, near, **kw)

    jp = tr.follow(Counting(), path, q0)
    assert calls == [1000]
    assert jp.q.shape == (1000, 6)


# ---------------------------------------------------------------- Porter's chain
def test_porter_follow_line_and_circle():
    l1, l3, l4 = 1.0, 0.5, 0.3
    q0 = np.array([0.3, 0.4, 1.0, 0.5, 0.6, 0.7])
    pa = Porter(l1, l3, l4)
    T0 = pa.fk(q0)
    for path in (
        tr.line_path(T0, T0[:3, 3] + [0.3, 0.2, 0.4], 100),
        tr.circle_path(T0[:3, 3] - [0, 0.3, 0], 0.3, [0, 0, 1], T0[:3, :3], 100, start=[0, 1, 0]),
    ):
        jp = tr.follow(pa, path, q0)
        assert np.abs(pa.fk(jp.q) - path).max() < 1e-9
        assert jp.start_jump < 1e-9
        assert jp.max_step < 0.2
        assert (jp.q[:, 2] >= 0).all()


def test_porter_naive_jumps_where_the_planes_become_parallel():
    """x5 = y0 fixed and p4 crossing the plane y = 0 at x > 0: there s4 = cos α1 = 1, c4 = 0 (Porter's
    planes-parallel case), and the continuous solution moves from the branch c4 > 0 to c4 < 0."""
    l1, l3, l4 = 1.0, 0.5, 0.3
    T0 = np.eye(4)
    T0[:3, :3] = rotz(np.pi / 2)
    T0[:3, 3] = [1.0, -0.4 + l4, 1.3]
    path = tr.line_path(T0, [1.0, 0.4 + l4, 1.3], 60)
    pa = Porter(l1, l3, l4)
    q0 = pa.ik_batch(path[:1]).q[0, 0]
    jp = tr.follow(pa, path, q0)
    nv = tr.naive(pa, path, q0)
    assert np.abs(pa.fk(jp.q) - path).max() < 1e-9
    assert np.abs(pa.fk(nv.q) - path).max() < 1e-9
    assert jp.max_step < 0.05 and nv.start_jump == 0.0
    assert nv.max_step > 3.0
    assert set(jp.choice.tolist()) == {0, 1}


def _short_path() -> np.ndarray:
    return tr.line_path(ARM.fk(ARM.q("qn")), [0.4, 0.2, 0.3], 3)


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: joint_distance([0.0, 0.0], [0.0, 0.0, 0.0]), "^q, q_ref: expected joint vectors of the same length"),
        (lambda: joint_distance([np.nan, 0.0], [0.0, 0.0]), "^q: expected finite"),
        # a mask of the wrong length used to broadcast silently (or raise IndexError in unwrap and follow)
        (
            lambda: joint_distance([0.0, 7.0], [0.0, 0.0], revolute=[True]),
            r"^revolute: expected a boolean mask of shape \(2,\)",
        ),
        (lambda: tr.unwrap([1.0, 2.0, 3.0]), "^q: expected a joint path"),
        (lambda: tr.unwrap([[1.0, 2.0]], revolute=[True]), r"^revolute: expected a boolean mask of shape \(2,\)"),
        # a non-boolean mask ([1, 0]) used to be accepted
        (lambda: tr.unwrap([[1.0, 2.0]], revolute=[1, 0]), r"^revolute: expected a boolean mask of shape \(2,\)"),
        (lambda: tr.follow(ARM, _short_path()[:0], ARM.q("qn")), "^path_Ts: expected at least one pose"),
        (lambda: tr.naive(ARM, _short_path()[:0]), "^path_Ts: expected at least one pose"),  # was IndexError
        (lambda: tr.line_path(np.eye(4), [1, 2, 3], 5.5), "^n: expected a whole number"),  # was truncated to 5
        (lambda: tr.circle_path([0, 0, 0], 1.0, [0, 0, 1], np.eye(3), 2.5), "^n: expected a whole number"),
        (lambda: tr.naive(ARM, _short_path(), np.zeros(5)), r"^q0: expected .* shape \(6,\)"),
        (lambda: tr.follow(ARM, np.eye(3), ARM.q("qn")), "^path_Ts: "),
        (lambda: Porter(-1.0, 0.5, 0.3), "^l1: expected a positive length"),
    ],
)
def test_bad_joint_path_input(call, match):
    with pytest.raises(ValueError, match=match):
        call()


# ---------------------------------------------------------------- time
def test_quintic_time_scaling_starts_and_stops_at_rest():
    ts = tr.time_scaling(2.0, 201)
    assert ts.s[0] == 0.0 and ts.s[-1] == 1.0
    assert ts.sdot[0] == ts.sdot[-1] == 0.0 and ts.sddot[0] == ts.sddot[-1] == 0.0
    # hand values at the middle: s = 1/2 by symmetry, the peak speed 15 / (8 T), no acceleration
    assert ts.s[100] == pytest.approx(0.5) and ts.sdot[100] == pytest.approx(15 / 16) and abs(ts.sddot[100]) < 1e-12
    # the derivatives are the derivatives: compare with finite differences of s
    assert np.allclose(np.gradient(ts.s, ts.t)[1:-1], ts.sdot[1:-1], atol=1e-3)
    assert np.allclose(np.gradient(ts.sdot, ts.t)[1:-1], ts.sddot[1:-1], atol=1e-2)
    assert (np.diff(ts.s) >= 0).all()  # monotonic: the path is never walked back
    lin = tr.time_scaling(4.0, 5, kind="linear")
    assert lin.s.tolist() == [0.0, 0.25, 0.5, 0.75, 1.0] and np.allclose(lin.sdot, 0.25)


def test_paths_follow_a_time_scaling():
    T0 = ARM.fk(ARM.q("qn"))
    ts = tr.time_scaling(1.0, 11)
    P = tr.line_path(T0, T0[:3, 3] + [0.0, 0.1, 0.0], s=ts.s)
    assert np.allclose(P[:, 1, 3] - T0[1, 3], 0.1 * ts.s)  # y advances by 0.1 s(t)
    C = tr.circle_path([0, 0, 0], 1.0, [0, 0, 1], np.eye(3), s=ts.s)
    assert np.allclose(C[:, :2, 3], np.column_stack([np.cos(2 * np.pi * ts.s), np.sin(2 * np.pi * ts.s)]))
    with pytest.raises(ValueError, match="^s: expected at least 2 path parameters in \\[0, 1\\]"):
        tr.line_path(T0, [0, 0, 0], s=[0.0, 1.5])


def test_joint_velocities_by_hand_and_across_the_wrap():
    t = np.linspace(0.0, 2.0, 21)
    q = np.column_stack([np.pi - 0.3 + 0.4 * t, -1.0 + 3.0 * t])  # the first crosses +π
    q[:, 0] = np.angle(np.exp(1j * q[:, 0]))  # stored wrapped, as the solvers give it
    v = tr.joint_velocities(q, t, revolute=np.array([True, False]))
    assert np.allclose(v, [[0.4, 3.0]] * 21)
    with pytest.raises(ValueError, match="^t: expected strictly increasing times"):
        tr.joint_velocities(q, np.zeros(21))
    with pytest.raises(ValueError, match="^t: expected times of shape \\(21,\\)"):
        tr.joint_velocities(q, t[:5])


# ---- issue 25 (1h): joint-space interpolation beside the Cartesian line --------------------------------------------


def test_joint_interpolation_ends_steps_and_short_way_round():
    from puma_course.kinematics.trajectories import joint_interpolation

    q0, q1 = np.array([*np.radians([170.0, 10.0]), 0.0]), np.array([*np.radians([-170.0, 40.0]), 0.5])
    Q = joint_interpolation(q0, q1, 7, revolute=[True, True, False])
    assert Q.shape == (7, 3) and np.allclose(Q[0], q0)
    assert np.allclose(np.degrees(Q[-1, :2]), [190.0, 40.0]) and np.isclose(Q[-1, 2], 0.5)  # 190° is -170°
    steps = np.diff(Q, axis=0)
    assert np.allclose(steps, steps[0])  # equal steps: a straight line in joint space
    assert np.allclose(np.degrees(steps[0, :2]), [20.0 / 6, 30.0 / 6])


def test_the_hand_leaves_the_line_in_joint_space_but_not_in_cartesian():
    from puma_course.kinematics import Puma560
    from puma_course.kinematics.trajectories import follow, joint_interpolation, line_path

    arm = Puma560()
    q0 = arm.q("qn")
    T0 = arm.fk(q0)
    T1 = T0.copy()
    T1[:3, 3] += [-0.3, 0.1, 0.1]
    cart = follow(arm, line_path(T0, T1, 41), q0)
    joint = joint_interpolation(cart.q[0], cart.q[-1], 41, revolute=arm.revolute)

    def off_line(P):  # distance of each point from the segment's line, by hand
        u = (T1[:3, 3] - T0[:3, 3]) / np.linalg.norm(T1[:3, 3] - T0[:3, 3])
        d = P - T0[:3, 3]
        return np.linalg.norm(d - np.outer(d @ u, u), axis=1)

    assert np.allclose(arm.fk(joint[-1]), T1, atol=1e-9)  # same endpoints
    assert off_line(arm.fk(cart.q)[:, :3, 3]).max() < 1e-9
    assert off_line(arm.fk(joint)[:, :3, 3]).max() > 0.005  # the joint-space line bends the hand's path


@pytest.mark.parametrize(
    ("args", "kwargs", "name"),
    [
        (([0.0, 1.0], [0.0]), {"n": 3}, "q1"),
        (([0.0], [np.nan]), {"n": 3}, "q1"),
        (([0.0], [1.0]), {"n": 1}, "n"),
        (([0.0, 0.0], [1.0, 1.0]), {"n": 3, "revolute": [True]}, "revolute"),
    ],
)
def test_joint_interpolation_rejects_bad_input_naming_it(args, kwargs, name):
    from puma_course.kinematics.trajectories import joint_interpolation

    with pytest.raises(ValueError, match=name):
        joint_interpolation(*args, **kwargs)


# ---- lecture 10 section 10: a joint-space line through a singularity; steps compared like for like ------


def _det_factored(q: np.ndarray, a2: float, a3: float, d4: float) -> np.ndarray:
    """det J of the PUMA-560 as lecture 09 factors it: -a2 (a3 s3 + d4 c3)(a2 c2 + a3 c23 - d4 s23) s5."""
    t2, t3, t5 = q[..., 1], q[..., 2], q[..., 4]
    return (-a2 * (a3 * np.sin(t3) + d4 * np.cos(t3))
            * (a2 * np.cos(t2) + a3 * np.cos(t2 + t3) - d4 * np.sin(t2 + t3)) * np.sin(t5))  # fmt: skip


def test_a_joint_space_line_crosses_a_singularity_with_neither_end_at_one():
    arm = Puma560()
    q_from = np.radians([10.0, -40.0, 10.0, 20.0, 25.0, -30.0])
    q_to = np.radians([40.0, -60.0, 30.0, -10.0, -25.0, 20.0])
    s = np.linspace(0.0, 1.0, 11)
    line = tr.joint_interpolation(q_from, q_to, s=s, revolute=arm.revolute)
    J = arm.jacobian(line)
    det = np.linalg.det(J)
    p = arm.parameters()
    np.testing.assert_allclose(det, _det_factored(line, p["a2"], p["a3"], p["d4"]), atol=1e-12)
    assert det[0] == pytest.approx(-0.0441, abs=5e-5) and det[-1] == pytest.approx(0.0315, abs=5e-5)
    assert det[0] < 0 < det[-1]  # the ends are not singular, and the sign changes on the way
    # at s = 0.5, θ5 = 25° - 25° = 0 (to rounding): joints 4 and 6 turn about one axis through the wrist centre,
    # so their columns of J are equal (rank 5) and det J is 0
    assert abs(line[5, 4]) < 1e-15
    np.testing.assert_allclose(J[5][:, 3], J[5][:, 5], atol=1e-12)
    assert abs(det[5]) < 1e-12
    # what does hold: the joint rates are bounded, the same Δq per unit of s on every stretch
    rates = np.diff(line, axis=0) / np.diff(s)[:, None]
    np.testing.assert_allclose(rates, np.broadcast_to(q_to - q_from, rates.shape), atol=1e-12)


def test_largest_step_of_one_joint_and_step_length_like_for_like():
    """JointPath.max_step is a length ‖Δq‖ (wrapped): the lecture compares one joint with one, length with length."""
    arm = Puma560()
    q_start = arm.q("qn")
    T_a = arm.fk(q_start)
    T_b = T_a.copy()
    T_b[:3, 3] += [-0.3, 0.1, 0.1]
    cart = tr.follow(arm, tr.line_path(T_a, T_b, 61), q_start)
    joint = tr.joint_interpolation(cart.q[0], cart.q[-1], 61, revolute=arm.revolute)
    dq_cart = np.diff(np.unwrap(cart.q, axis=0), axis=0)
    dq_joint = np.diff(joint, axis=0)
    assert cart.max_step == pytest.approx(np.linalg.norm(dq_cart, axis=1).max(), abs=1e-12)  # a length
    # on the joint-space line every step is Δq / 60, Δq from the two ends by hand
    delta = (cart.q[-1] - cart.q[0] + np.pi) % (2 * np.pi) - np.pi
    assert np.abs(dq_joint).max() == pytest.approx(np.abs(delta).max() / 60, abs=1e-12)
    assert np.linalg.norm(dq_joint, axis=1).max() == pytest.approx(np.linalg.norm(delta) / 60, abs=1e-12)
    # the lecture's table [deg]: one joint 1.30 (Cartesian) and 0.70 (joint space), lengths 1.65 and 1.04
    lengths = np.linalg.norm(dq_joint, axis=1)
    got = np.degrees([np.abs(dq_cart).max(), np.abs(dq_joint).max(), cart.max_step, lengths.max()])
    np.testing.assert_allclose(got, [1.296, 0.695, 1.646, 1.039], atol=1e-3)
    assert got[0] < got[2] and got[1] < got[3]  # a step's length exceeds its largest joint's change
