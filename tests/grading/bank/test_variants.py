"""The variant mechanisms of ex05 q1, ex06 q2 and q4 and ex08 against independent, hand-worked truths (issue 22).

Each variant keeps a lecture's teaching but changes the mechanism so that copying the lecture does not answer
the question: Porter's chain with a pitching hand, with a telescopic rod, with a stroke limit, and the
three-step arm read as a palletising arm. The references are checked here against geometry worked out by
hand (rotation columns, distances, the wrist centre's formula), not against themselves.
"""

from __future__ import annotations

import numpy as np

from puma_course import Porter, transforms
from puma_course.grading import EXERCISES
from puma_course_bank._reference import motion, porter_chain

RNG_SEED = 7


def test_the_pitching_hand_turns_about_y4_through_p5():
    rng = np.random.default_rng(RNG_SEED)
    for _ in range(5):
        q = rng.uniform(-np.pi, np.pi, 6)
        q[2] = rng.uniform(0.2, 2.0)
        L = tuple(rng.uniform(0.3, 1.5, 3))
        F4 = Porter(*L).fk(np.r_[q[:5], 0.0])  # at α5 = 0 both hands are the frame F4' at p5
        T = porter_chain.porter_pitch_fk(q, *L)
        c, s = np.cos(q[5]), np.sin(q[5])
        assert np.allclose(T[:3, 3], F4[:3, 3])  # the pitch turns about a line through p5: p5 stays
        assert np.allclose(T[:3, 1], F4[:3, 1])  # ... about y4: y stays
        assert np.allclose(T[:3, 0], c * F4[:3, 0] - s * F4[:3, 2])  # x turns towards -z (right-hand rule about y)
        assert np.allclose(T[:3, 2], s * F4[:3, 0] + c * F4[:3, 2])
        # about the parallel line through p4 the hand point moves on a circle of radius l4 about p4
        W = porter_chain.porter_pitch_through_p4(q, *L)
        p4 = F4[:3, 3] - L[2] * F4[:3, 0]
        assert np.isclose(np.linalg.norm(W[:3, 3] - p4), L[2]) and np.allclose(W[:3, :3], T[:3, :3])


def test_the_telescopic_rod_keeps_the_rows_at_least_l2_long():
    rng = np.random.default_rng(RNG_SEED)
    for T, l1, l2, l3, l4 in porter_chain.porter_rod_poses(rng, 5):
        exp = porter_chain.porter_rod_ik_expected(T, l1, l2, l3, l4)
        S = exp["solutions"]
        assert len(S) == 2 and np.all(S[:, 2] >= 0)  # l2 lies between the two rod lengths
        for q in S:
            P = Porter(l1, l3, l4).points(q + [0, 0, l2, 0, 0, 0])
            assert np.isclose(np.linalg.norm(P[3] - P[2]), l2 + q[2])  # the rod: fixed part plus stroke
            assert np.allclose(porter_chain.porter_rod_fk(q, l1, l2, l3, l4), T)
        # Porter's other two configurations need a rod shorter than l2
        every = np.asarray(Porter(l1, l3, l4).ik(T).q)
        assert sorted(every[:, 2] < l2) == [False, False, True, True]


def test_the_stroke_limit_leaves_two_configurations_or_none():
    rng = np.random.default_rng(RNG_SEED)
    counts = []
    for T, l1, l3, l4, q2_max in porter_chain.porter_limited_poses(rng, 6):
        S = porter_chain.porter_limited_expected(T, l1, l3, l4, q2_max)["solutions"]
        strokes = np.asarray(Porter(l1, l3, l4).ik(T).q)[:, 2]
        assert len(S) == int(np.sum(strokes <= q2_max)) and np.all(S[:, 2] <= q2_max)
        if len(S):
            assert np.allclose(Porter(l1, l3, l4).fk(S), T)
        counts.append(len(S))
    assert set(counts) == {0, 2}  # both kinds of case are graded


def test_the_palletising_arm_reads_its_base_from_ey_and_its_forearm_from_the_horizontal():
    ex = EXERCISES["ex08_three_step"]
    rng = np.random.default_rng(RNG_SEED)
    for w, F, l1, l2, elbow, tb, Fb in motion.three_step_cases(rng, 6, _reach):
        t1, t2 = ex.question("q2").reference(w, l1, l2, elbow)
        g0 = np.arctan2(w[1], w[0])
        r = l1 * np.cos(t1) + l2 * np.cos(t2)  # this arm's eq. (1): θ2 the forearm's elevation
        assert np.allclose([r * np.cos(g0), r * np.sin(g0), l1 * np.sin(t1) + l2 * np.sin(t2)], w)
        # the frame is carried rigidly by the forearm, whose orientation is Rz(γ0) Ry(-θ2), γ0 = θ0 + π/2
        forearm = transforms.rotz(g0) @ transforms.roty(-t2)
        start = transforms.rotz(tb[0] + np.pi / 2) @ transforms.roty(-tb[2])
        F2 = ex.question("q3").reference(w, l1, l2, elbow, tb, Fb)
        assert np.allclose(F2, forearm @ start.T @ Fb)
        assert np.allclose(ex.question("q4").reference(w, F, l1, l2, elbow, tb, Fb) @ F2, F)  # 𝒦 F2 = F
        F1 = ex.question("q1").reference(w, tb, Fb)
        assert np.allclose(F1, transforms.rotz(g0 - np.pi / 2 - tb[0]) @ Fb)


def _reach(rng: np.random.Generator, n: int) -> list[tuple[np.ndarray, float, float]]:
    out: list[tuple[np.ndarray, float, float]] = []
    while len(out) < n:
        l1, l2 = rng.uniform(0.5, 1.5, 2)
        d = rng.uniform(abs(l1 - l2) + 0.1, l1 + l2 - 0.1)
        u = rng.normal(size=3)
        out.append((d * u / np.linalg.norm(u), float(l1), float(l2)))
    return out


def test_a_joint_offset_shifts_the_joint_values_and_refuses_bad_input():
    from puma_course.kinematics import MountedFk

    rod = MountedFk(Porter(1.0, 0.5, 0.3).fk, offset=[0.0, 0.0, 0.4, 0.0, 0.0, 0.0])
    P = Porter(1.0, 0.5, 0.3).points([0.3, -0.2, 0.1 + 0.4, 0.5, 0.6, 0.7])
    assert np.isclose(np.linalg.norm(P[3] - P[2]), 0.5)  # the rod: 0.4 fixed plus a stroke of 0.1
    assert np.allclose(rod([0.3, -0.2, 0.1, 0.5, 0.6, 0.7])[:3, 3], P[5])
    for bad in ([0.0, np.nan], [[0.0]], "x"):
        try:
            MountedFk(Porter().fk, offset=bad)
        except ValueError as exc:
            assert "offset" in str(exc)
        else:
            raise AssertionError(f"offset={bad!r} was accepted")
