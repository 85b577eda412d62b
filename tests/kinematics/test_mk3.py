"""Motoman MK3 (5R): forward kinematics against the lecture's printed closed forms, and the closed-form
5R inverse kinematics by round trips, the arm-plane condition, labels read off the drawn arm, every
singular case, unreachable poses and bad input."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
import sympy as sp

from puma_course.kinematics import MK3, SingularityWarning
from puma_course.kinematics.ik import joint_distance
from puma_course.kinematics.mk3 import BRANCH_LABELS
from puma_course.transforms import rotx

ARM = MK3()


def mk3_printed(q, d1=360.0, a1=135.0, a2=250.0, a3=215.0, d5=100.0):
    """The lecture's closed forms of 0T5 for the MK3, typed in by hand."""
    t1, t2, t3, t4, t5 = q
    c1, s1, c5, s5 = math.cos(t1), math.sin(t1), math.cos(t5), math.sin(t5)
    c2, s2 = math.cos(t2), math.sin(t2)
    c23, s23 = math.cos(t2 + t3), math.sin(t2 + t3)
    c234, s234 = math.cos(t2 + t3 + t4), math.sin(t2 + t3 + t4)
    reach = a1 + a2 * c2 + a3 * c23 + d5 * s234
    return np.array(
        [
            [c1 * c234 * c5 + s1 * s5, -c1 * c234 * s5 + s1 * c5, c1 * s234, c1 * reach],
            [s1 * c234 * c5 - c1 * s5, -s1 * c234 * s5 - c1 * c5, s1 * s234, s1 * reach],
            [c5 * s234, -s5 * s234, -c234, d1 + a2 * s2 + a3 * s23 - d5 * c234],
            [0, 0, 0, 1],
        ]
    )


def test_mk3_zero_pose_hand_worked():
    # Arm links horizontal along x: a1 + a2 + a3 = 600 mm out; the tool d5 = 100 mm points down.
    T = MK3().fk(np.zeros(5))
    assert np.allclose(T[:3, 3], [600, 0, 260])
    assert np.allclose(T[:3, 2], [0, 0, -1])


def test_mk3_ready_pose_hand_worked():
    # θ2 = 90°, θ3 = -90°: upper arm vertical (z = 360 + 250), forearm horizontal (x = 135 + 215),
    # tool down by 100.
    r = MK3()
    assert np.allclose(r.fk(r.q("qr"))[:3, 3], [350, 0, 510])


def test_mk3_matches_printed_closed_forms():
    rng = np.random.default_rng(3)
    r = MK3()
    for q in rng.uniform(-math.pi, math.pi, (100, 5)):
        assert np.allclose(r.fk(q), mk3_printed(q), atol=1e-9)


def test_batches_are_vectorised_shapes():
    assert MK3().fk(np.zeros((2, 5))).shape == (2, 4, 4)
    assert MK3().frames(np.zeros((2, 5))).shape == (2, 6, 4, 4)


@pytest.mark.parametrize(
    "call, fragment",
    [
        (lambda: MK3().fk(np.zeros(6)), "shape (5,)"),
        (lambda: MK3(d5=[1, 2]), "d5"),
        (lambda: MK3(a2=0.0), "a2: expected a positive length"),
        (lambda: MK3(a3=-1.0), "a3: expected a positive length"),
        (lambda: MK3().ik(np.eye(4), tol=-1.0), "tol: expected a small positive tolerance"),
        (lambda: MK3().ik(np.eye(4), near=np.zeros(6)), "near: expected a joint vector of shape (5,)"),
        (lambda: MK3().ik_batch(np.stack([np.eye(4)] * 2), near=np.zeros((3, 5))), "near"),
    ],
)
def test_bad_input(call, fragment):
    with pytest.raises(ValueError) as err:
        call()
    assert fragment in str(err.value)


# ================================================================ inverse kinematics
def test_the_arm_plane_structure_by_sympy():
    """Second derivation of what the solver relies on: M = Rz(-θ1) R has the printed structure,
    so its middle row is (-s5, -c5, 0) and the tool point, z5 and the wrist point stay in the arm plane."""
    t = sp.symbols("t1:6", real=True)
    d1, a1, a2, a3, d5 = sp.symbols("d1 a1 a2 a3 d5", real=True)

    def mdh(al, a, th, d):
        ca, sa, ct, s_ = sp.cos(al), sp.sin(al), sp.cos(th), sp.sin(th)
        return sp.Matrix(
            [[ct, -s_, 0, a], [s_ * ca, ct * ca, -sa, -sa * d], [s_ * sa, ct * sa, ca, ca * d], [0, 0, 0, 1]]
        )

    h = sp.pi / 2
    T = mdh(0, 0, t[0], d1) * mdh(h, a1, t[1], 0) * mdh(0, a2, t[2], 0) * mdh(0, a3, t[3], 0) * mdh(h, 0, t[4], d5)
    Rz = sp.Matrix([[sp.cos(t[0]), sp.sin(t[0]), 0], [-sp.sin(t[0]), sp.cos(t[0]), 0], [0, 0, 1]])
    M = sp.simplify(Rz * T[:3, :3])
    assert sp.simplify(M[1, :] - sp.Matrix([[-sp.sin(t[4]), -sp.cos(t[4]), 0]])) == sp.zeros(1, 3)
    t234 = t[1] + t[2] + t[3]
    assert sp.simplify(M[0, 2] - sp.sin(t234)) == 0 and sp.simplify(M[2, 2] + sp.cos(t234)) == 0
    p_plane = sp.simplify(Rz * T[:3, 3])
    assert sp.simplify(p_plane[1]) == 0  # the tool point lies in the arm plane


def test_round_trip_many_poses_and_the_original_is_found():
    rng = np.random.default_rng(21)
    q = rng.uniform(-math.pi, math.pi, (3000, 5))
    T = ARM.fk(q)
    b = ARM.ik_batch(T)
    assert b.reachable.all() and b.valid.sum(axis=1).min() >= 2  # at least one arm plane, both elbows...
    assert np.isfinite(b.q).all()
    Tq = ARM.fk(b.q.reshape(-1, 5)).reshape(-1, 4, 4, 4)
    err = np.abs(Tq - T[:, None]).max(axis=(2, 3)) / 600.0
    assert err[b.valid].max() < 1e-12
    d = np.where(b.valid, joint_distance(b.q, q[:, None]), np.inf).min(axis=1)
    assert d.max() < 1e-7  # ...and the configuration we started from is among the solutions
    assert (b.q > -math.pi).all() and (b.q <= math.pi).all()


def test_scalar_ik_equals_the_batch_and_sorts_by_near():
    rng = np.random.default_rng(22)
    for q in rng.uniform(-math.pi, math.pi, (100, 5)):
        T = ARM.fk(q)
        b = ARM.ik_batch(T[None])
        s = ARM.ik(T)
        keep = np.flatnonzero(b.valid[0])
        assert list(s.labels) == [BRANCH_LABELS[j] for j in keep]
        assert np.array_equal(np.asarray(s), b.q[0, keep])
        n = ARM.ik(T, near=q)
        assert joint_distance(n[0], q) < 1e-7
        assert np.all(np.diff(joint_distance(np.asarray(n), q)) >= 0)


def test_labels_match_the_drawn_arm():
    """front: θ1 points the arm plane towards the wrist point; up: the drawn elbow (origin of frame {3})
    is above the line from joint 2 (origin of {2}) to the wrist point (origin of {5} minus d5 z5)."""
    rng = np.random.default_rng(23)
    q = rng.uniform(-math.pi, math.pi, (400, 5))
    F = ARM.frames(q)
    b = ARM.ik_batch(F[:, -1])
    k = np.argmin(np.where(b.valid, joint_distance(b.q, q[:, None]), np.inf), axis=1)
    j2, elbow = F[:, 2, :3, 3], F[:, 3, :3, 3]
    wrist = F[:, 5, :3, 3] - 100.0 * F[:, 5, :3, 2]
    c1, s1 = np.cos(q[:, 0]), np.sin(q[:, 0])
    front = c1 * wrist[:, 0] + s1 * wrist[:, 1] >= 0
    u = np.stack([c1, s1, 0 * c1], axis=1)

    def plane(p):  # (horizontal coordinate along the arm plane, height), both seen from joint 2
        return np.einsum("ni,ni->n", p - j2, u), p[:, 2] - j2[:, 2]

    (he, ze), (hw, zw) = plane(elbow), plane(wrist)
    sgn = np.where(hw >= 0, 1.0, -1.0)
    up = sgn * (hw * ze - zw * he) > 0
    expect = [f"{'front' if f else 'back'}/{'up' if e else 'down'}" for f, e in zip(front, up, strict=True)]
    assert [BRANCH_LABELS[i] for i in k] == expect


def test_a_pose_out_of_the_arm_plane_is_refused_with_the_reason():
    T = ARM.fk([0.3, 1.0, -0.6, 0.2, 0.4])
    for angle in (1e-3, 0.2, 1.0):
        Tx = T.copy()
        Tx[:3, :3] = T[:3, :3] @ rotx(angle)  # a turn about x5 tilts z5 out of the plane
        sol = ARM.ik(Tx)
        assert not sol.success and len(sol) == 0
        assert "5-DOF" in sol.reason and "approach vector z5" in sol.reason
        # how far z5 leaves the vertical plane through the base axis and the wrist point w = p - d5 z5
        z5 = Tx[:3, 2]
        w = Tx[:3, 3] - 100.0 * z5
        u = w[:2] / np.hypot(*w[:2])
        off = math.degrees(math.asin(abs(-u[1] * z5[0] + u[0] * z5[1])))
        assert f"z5 at {off:.3g}°" in sol.reason
    # a tool point off the plane of z5 is refused the same way
    Tp = T.copy()
    Tp[:3, 3] += 5.0 * np.array([-math.sin(0.3), math.cos(0.3), 0.0])
    assert "5-DOF" in ARM.ik(Tp).reason


def test_out_of_reach():
    T = np.eye(4)
    T[:3, :3] = np.diag([1.0, -1.0, -1.0])  # tool down: in every vertical plane
    T[:3, 3] = [2000.0, 0.0, 300.0]
    sol = ARM.ik(T)
    assert not sol.success and "out of reach" in sol.reason
    b = ARM.ik_batch(np.stack([T, ARM.fk(np.zeros(5))]))
    assert b.reachable.tolist() == [False, True] and np.isfinite(b.q).all() and (b.q[0] == 0).all()


def test_elbow_singular_stretched():
    q = np.array([0.4, 0.3, 0.0, -0.5, 0.2])  # θ3 = 0: upper arm and forearm in line
    T = ARM.fk(q)
    with pytest.warns(SingularityWarning, match="elbow"):
        sol = ARM.ik(T, near=q)
    assert len(sol) == 1  # up = down; the back plane is out of reach at full stretch
    assert sol.flags == (("elbow",),) and sol[0][2] == 0.0  # θ3 snapped to exactly 0
    assert joint_distance(sol[0], q) < 1e-7 and np.abs(ARM.fk(sol[0]) - T).max() < 1e-9


def test_base_axis_singular_wrist_on_the_axis_tool_vertical():
    # the wrist point on the base axis needs a1 + a2 c2 + a3 c23 = 0 and a vertical tool: S234 = 0
    t2 = 2.0
    t3 = math.acos((-135.0 - 250.0 * math.cos(t2)) / 215.0) - t2
    q = np.array([0.7, t2, t3, -t2 - t3, 0.3])
    T = ARM.fk(q)
    assert np.hypot(*T[:2, 3]) < 1e-9
    with pytest.warns(SingularityWarning, match="base_axis"):
        sol = ARM.ik(T, near=q)
    assert all("base_axis" in f for f in sol.flags)
    assert all(lab.startswith("front") for lab in sol.labels)  # front = back: one representative plane
    assert sol[0][0] == pytest.approx(0.7)  # θ1 from near
    for row in sol:
        assert np.abs(ARM.fk(row) - T).max() < 1e-9
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SingularityWarning)
        assert ARM.ik(T)[0][0] == 0.0  # without near: θ1 = 0 exactly


def test_joint2_axis_singular_with_equal_links():
    arm = MK3(a2=200.0, a3=200.0)
    q = np.array([0.2, 0.9, math.pi, 0.4, -0.3])  # folded flat: the wrist point on joint 2's axis
    T = arm.fk(q)
    with pytest.warns(SingularityWarning, match="joint2_axis"):
        sol = arm.ik(T, near=q)
    # the front plane sees w on joint 2's axis (θ2 free); the back plane sees it 2 a1 away
    assert [("joint2_axis" in f) for f in sol.flags] == [lab.startswith("front") for lab in sol.labels]
    assert joint_distance(sol[0], q) < 1e-7
    for row in sol:
        assert np.abs(arm.fk(row) - T).max() < 1e-9
