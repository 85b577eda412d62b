"""PUMA-560: forward kinematics against hand-worked poses and the lecture's closed forms; closed-form
inverse kinematics by round trips through the forward kinematics (the independent truth), branch
labels checked against the geometry of the drawn arm, every singular case, unreachable poses and bad
input."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from puma_course.kinematics import DHChain, Puma560, SingularityWarning
from puma_course.kinematics.ik import joint_distance
from puma_course.kinematics.puma560 import BRANCH_LABELS
from puma_course.transforms import wrap_angle as wrap

A2, A3, D3, D4 = 0.4318, 0.0203, 0.15005, 0.4318


def craig_puma_position(q, a2=A2, a3=A3, d3=D3, d4=D4):
    """Wrist position of the PUMA-560 written out by hand (Craig, eq. 3.14's p column)."""
    t1, t2, t3 = q[..., 0], q[..., 1], q[..., 2]
    c1, s1 = np.cos(t1), np.sin(t1)
    c2, s2 = np.cos(t2), np.sin(t2)
    c23, s23 = np.cos(t2 + t3), np.sin(t2 + t3)
    r = a2 * c2 + a3 * c23 - d4 * s23
    return np.stack([c1 * r - d3 * s1, s1 * r + d3 * c1, -a3 * s23 - a2 * s2 - d4 * c23], axis=-1)


def test_puma_zero_pose_hand_worked():
    # All joints at zero: the upper arm along x1 (a2), the offset a3 further,
    # d3 sideways along y, and the forearm d4 hanging along -z.
    T = Puma560().fk(np.zeros(6))
    assert np.allclose(T[:3, 3], [A2 + A3, D3, -D4])
    # With every θ = 0 only the twists act, all about x: -90 - 90 + 90 - 90 = -180 degrees.
    assert np.allclose(T[:3, :3], np.diag([1.0, -1.0, -1.0]))


def test_puma_second_hand_worked_pose():
    # θ1 = 90°, θ3 = -90°: the arm stretched horizontally, turned to point along +y.
    # Position: x = -d3, y = a2 + d4, z = a3.
    q = np.array([math.pi / 2, 0, -math.pi / 2, 0, 0, 0])
    assert np.allclose(Puma560().fk(q)[:3, 3], [-D3, A2 + D4, A3])


def test_puma_named_configurations():
    r = Puma560()
    assert np.allclose(r.fk(r.q("qr"))[:3, 3], [-A3, D3, A2 + D4])  # straight up
    assert np.allclose(r.fk(r.q("qs"))[:3, 3], [A2 + D4, D3, A3])  # stretched along x
    assert np.array_equal(r.q("qz"), np.zeros(6))
    # nominal: upper arm 45° above horizontal (θ2 = -45°), forearm level (θ2 + θ3 = -90°), so the wrist
    # is a2/√2 out and up from the shoulder, then d4 further out, lifted by a3
    h = A2 / np.sqrt(2.0)
    assert np.allclose(r.fk(r.q("qn"))[:3, 3], [h + D4, D3, h + A3])


def test_puma_positions_match_hand_written_closed_form_on_random_batch():
    rng = np.random.default_rng(1)
    q = rng.uniform(-math.pi, math.pi, (500, 6))
    assert np.allclose(Puma560().fk(q)[:, :3, 3], craig_puma_position(q), atol=1e-12)
    r = Puma560(a2=1.0, a3=0.2, d3=-0.3, d4=0.7)
    assert np.allclose(r.fk(q)[:, :3, 3], craig_puma_position(q, 1.0, 0.2, -0.3, 0.7), atol=1e-12)


def test_puma_printed_rotation_column_entries():
    # r11, r21, r31 as printed in the lecture (eq. 3.14).
    rng = np.random.default_rng(2)
    for q in rng.uniform(-math.pi, math.pi, (50, 6)):
        c = np.cos(q)
        s = np.sin(q)
        c23, s23 = math.cos(q[1] + q[2]), math.sin(q[1] + q[2])
        inner = c23 * (c[3] * c[4] * c[5] - s[3] * s[5]) - s23 * s[4] * c[5]
        side = s[3] * c[4] * c[5] + c[3] * s[5]
        r11 = c[0] * inner + s[0] * side
        r21 = s[0] * inner - c[0] * side
        r31 = -s23 * (c[3] * c[4] * c[5] - s[3] * s[5]) - c23 * s[4] * c[5]
        assert np.allclose(Puma560().fk(q)[:3, 0], [r11, r21, r31], atol=1e-12)


def test_closed_form_fk_equals_the_dh_product():
    """Second derivation: eq. 3.14 (Puma560.fk) against the generic column walk of the six link matrices."""
    rng = np.random.default_rng(11)
    q = rng.uniform(-math.pi, math.pi, (300, 6))
    for arm in (Puma560(), Puma560(a2=1.0, a3=-0.2, d3=-0.3, d4=0.7)):
        assert np.allclose(arm.fk(q), DHChain.fk(arm, q), atol=1e-14)
        assert np.allclose(arm.fk(q[0]), DHChain.fk(arm, q[0]), atol=1e-14)
        assert np.allclose(arm.frames(q)[:, -1], arm.fk(q), atol=1e-14)


def test_batches_are_vectorised_shapes():
    q = np.zeros((3, 6))
    assert Puma560().fk(q).shape == (3, 4, 4)
    assert Puma560().frames(q).shape == (3, 7, 4, 4)
    assert Puma560().points(q).shape == (3, 6, 3)


def test_points_show_the_shoulder_offset_hand_worked():
    # at qz: foot below the base, base, d3 along y, end of a2, then a3, then d4 down to the wrist centre
    P = Puma560().points(np.zeros(6))
    expected = [[0, 0, -0.35], [0, 0, 0], [0, D3, 0], [A2, D3, 0], [A2 + A3, D3, 0], [A2 + A3, D3, -D4]]
    assert np.allclose(P, expected, atol=1e-15)
    q = np.random.default_rng(3).uniform(-3, 3, (20, 6))
    P = Puma560().points(q)
    # the drawn links have the table's lengths whatever the pose
    assert np.allclose(np.linalg.norm(P[:, 2] - P[:, 1], axis=1), D3)
    assert np.allclose(np.linalg.norm(P[:, 3] - P[:, 2], axis=1), A2)
    assert np.allclose(np.linalg.norm(P[:, 4] - P[:, 3], axis=1), A3)
    assert np.allclose(np.linalg.norm(P[:, 5] - P[:, 4], axis=1), D4)
    assert np.allclose(P[:, 5], Puma560().fk(q)[:, :3, 3])  # the last point is the wrist centre


@pytest.mark.parametrize(
    "call, fragment",
    [
        (lambda: Puma560(a2="long"), "a2"),
        (lambda: Puma560(d4=float("nan")), "d4: expected finite"),
        (lambda: Puma560().fk(np.zeros(5)), "shape (6,)"),
        (lambda: Puma560(a2=0.0), "a2: expected a positive length"),  # was accepted and refused only at ik
        (lambda: Puma560(a2=-0.4), "a2: expected a positive length"),
        (lambda: Puma560(a3=0.0, d4=0.0), "a3, d4: expected a forearm of non-zero length"),
        (lambda: Puma560(a2=1e300), "a2: expected values of size at most"),
    ],
)
def test_fk_bad_input(call, fragment):
    with pytest.raises(ValueError) as err:
        call()
    assert fragment in str(err.value)


# ================================================================ inverse kinematics
ARM = Puma560()
A2, A3, D3, D4 = 0.4318, 0.0203, 0.15005, 0.4318


def _random_q(n: int, seed: int) -> np.ndarray:  # noqa: D103
    return np.random.default_rng(seed).uniform(-np.pi, np.pi, (n, 6))


def _pose_error(arm, q, T) -> float:
    return float(np.abs(arm.fk(q) - T).max())


# ---------------------------------------------------------------- general position
def test_batch_round_trip_thousands_of_poses():
    q = _random_q(5000, 1)
    T = ARM.fk(q)
    sol = ARM.ik_batch(T)
    assert sol.q.shape == (5000, 8, 6)
    assert sol.reachable.all()
    assert np.isfinite(sol.q).all()
    # random configurations are (almost surely) far from every singularity: 8 valid branches each
    assert sol.valid.all()
    Tq = ARM.fk(sol.q.reshape(-1, 6)).reshape(5000, 8, 4, 4)
    assert np.abs(Tq - T[:, None]).max() < 1e-9
    # the configuration we started from is one of the eight (1e-6: near the folded arm, where the
    # wrist centre comes within sqrt(a3² + d4²) - a2 = 0.5 mm of the joint-2 axis, θ2 is ill-conditioned)
    assert joint_distance(sol.q, q[:, None]).min(axis=1).max() < 1e-6
    # angles wrapped to (-π, π]
    assert (sol.q > -np.pi).all() and (sol.q <= np.pi).all()


def test_scalar_round_trip_and_original_first_with_near():
    q = _random_q(300, 2)
    for qi in q:
        Ti = ARM.fk(qi)
        sol = ARM.ik(Ti, near=qi)
        assert len(sol) == 8
        assert np.asarray(sol).shape == (8, 6)
        for row in sol:
            assert _pose_error(ARM, row, Ti) < 1e-9
        assert joint_distance(sol[0], qi) < 1e-7  # nearest first: the original itself
        d = joint_distance(np.asarray(sol), qi)
        assert np.all(np.diff(d) >= 0)
        assert not sol.is_singular


def test_eight_distinct_solutions_in_general_position():
    q = np.array([0.3, -0.7, 0.4, 1.1, 0.8, -0.5])
    sol = ARM.ik(ARM.fk(q))
    Q = np.asarray(sol)
    D = joint_distance(Q[:, None], Q[None, :])
    assert (D[~np.eye(8, dtype=bool)] > 1e-3).all()
    assert sorted(sol.labels) == sorted(BRANCH_LABELS)
    assert sol.flags == ((),) * 8 and sol.success and sol.reason == ""


def test_labels_match_the_geometry_of_the_arm():
    """Shoulder from the sign of the reach X = c1 px + s1 py, elbow from where the drawn elbow sits
    relative to the shoulder-wrist line, wrist from the sign of θ5 -- all read off fk frames."""
    q = _random_q(400, 3)
    F = ARM.frames(q)  # (N, 7, 4, 4)
    p = F[:, 6, :3, 3]
    c1, s1 = np.cos(q[:, 0]), np.sin(q[:, 0])
    X = c1 * p[:, 0] + s1 * p[:, 1]
    left = X > 0
    # arm-plane coordinates seen facing the wrist: h horizontal (towards the wrist), z up
    sgn = np.where(left, 1.0, -1.0)
    E = F[:, 3, :3, 3]
    hE, zE = sgn * (c1 * E[:, 0] + s1 * E[:, 1]), E[:, 2]
    hW, zW = sgn * X, p[:, 2]
    up = hW * zE - zW * hE > 0  # elbow to the left of the shoulder->wrist ray = above it
    noflip = np.sin(q[:, 4]) > 0
    sol = ARM.ik_batch(ARM.fk(q))
    k = np.argmin(joint_distance(sol.q, q[:, None]), axis=1)
    labels = [BRANCH_LABELS[i] for i in k]
    expect = [
        f"{'left' if a else 'right'}/{'up' if b else 'down'}/{'noflip' if c else 'flip'}"
        for a, b, c in zip(left, up, noflip, strict=True)
    ]
    assert labels == expect


@settings(derandomize=True, max_examples=150, deadline=None)
@given(st.lists(st.floats(-np.pi, np.pi), min_size=6, max_size=6))
def test_hypothesis_round_trip(qlist):
    q = np.array(qlist)
    T = ARM.fk(q)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SingularityWarning)
        sol = ARM.ik(T, near=q)
    assert 1 <= len(sol) <= 8
    for row in sol:
        assert _pose_error(ARM, row, T) < 1e-7
    # the original is reached by the nearest solution (possibly another representative at a singularity)
    assert _pose_error(ARM, sol[0], T) < 1e-7


def test_sympy_position_norm_gives_the_equation_of_theta3():
    """Second derivation: |p|² of the symbolic 0T4 equals a2²+a3²+d3²+d4²+2 a2 (a3 c3 - d4 s3)."""
    import sympy as sp  # a dependency of the course (pyproject): a missing sympy must fail, not skip

    t = sp.symbols("t1:4", real=True)
    a2, a3, d3, d4 = sp.symbols("a2 a3 d3 d4", real=True)

    def mdh(al, a, th, d):
        ca, sa, ct, s_ = sp.cos(al), sp.sin(al), sp.cos(th), sp.sin(th)
        return sp.Matrix(
            [[ct, -s_, 0, a], [s_ * ca, ct * ca, -sa, -sa * d], [s_ * sa, ct * sa, ca, ca * d], [0, 0, 0, 1]]
        )

    h = sp.pi / 2
    T = mdh(0, 0, t[0], 0) * mdh(-h, 0, t[1], 0) * mdh(0, a2, t[2], d3) * mdh(-h, a3, 0, d4)
    p = T[:3, 3]
    lhs = sp.expand(p.dot(p))
    rhs = a2**2 + a3**2 + d3**2 + d4**2 + 2 * a2 * (a3 * sp.cos(t[2]) - d4 * sp.sin(t[2]))
    assert sp.simplify(sp.expand_trig(lhs - rhs)) == 0
    # and the shoulder equation -s1 px + c1 py = d3
    assert sp.simplify(-sp.sin(t[0]) * p[0] + sp.cos(t[0]) * p[1] - d3) == 0


# ---------------------------------------------------------------- singular cases
def _shoulder_singular_q(t3: float = 0.4) -> np.ndarray:
    """θ2 chosen so that the reach X = c2 vx - s2 vy is zero: wrist centre on the cylinder ρ = d3."""
    vx = A2 + A3 * np.cos(t3) - D4 * np.sin(t3)
    vy = A3 * np.sin(t3) + D4 * np.cos(t3)
    return np.array([0.2, np.arctan2(vx, vy), t3, 0.5, 0.7, -0.3])


def test_wrist_singular_theta5_zero():
    q = np.array([0.3, -0.6, 0.2, 0.9, 0.0, 0.4])
    T = ARM.fk(q)
    with pytest.warns(SingularityWarning, match="θ4 \\+ θ6"):
        sol = ARM.ik(T)
    # only the original arm branch has θ5 = 0 (the other three see the same R through another ^0R_3):
    # there flip duplicates noflip, one representative stays -> 3 x 2 + 1 = 7 solutions
    assert len(sol) == 7
    wrist = [i for i, f in enumerate(sol.flags) if "wrist" in f]
    assert len(wrist) == 1
    assert sol.labels[wrist[0]].endswith("noflip")
    assert sol.is_singular and "θ4 + θ6" in sol.messages["wrist"]
    for row in sol:
        assert _pose_error(ARM, row, T) < 1e-9
        assert np.isfinite(row).all()
    # without near, θ4 = 0 is the representative; θ4 + θ6 is kept
    match = np.asarray(sol)[wrist[0]]
    assert joint_distance(match[:3], q[:3]) < 1e-9
    assert match[3] == 0.0  # the representative, set exactly by design
    assert np.isclose(wrap(match[3] + match[5]), wrap(q[3] + q[5]))
    # with near, θ4 comes from near and the original is recovered exactly
    with pytest.warns(SingularityWarning):
        sol = ARM.ik(T, near=q)
    assert joint_distance(sol[0], q) < 1e-9


def test_wrist_singular_theta5_pi():
    q = np.array([-0.4, -0.2, 0.5, 0.3, np.pi, -1.0])
    T = ARM.fk(q)
    with pytest.warns(SingularityWarning, match="θ4 - θ6"):
        sol = ARM.ik(T, near=q)
    assert len(sol) == 7
    assert sol.flags[0] == ("wrist",) and sol[0][4] == np.pi  # θ5 snapped to exactly π by design
    for row in sol:
        assert _pose_error(ARM, row, T) < 1e-9
    assert joint_distance(sol[0], q) < 1e-9


def test_shoulder_singular_cylinder():
    q = _shoulder_singular_q()
    T = ARM.fk(q)
    p = T[:3, 3]
    assert np.isclose(np.hypot(p[0], p[1]), D3)  # the wrist centre is on the cylinder ρ = d3
    with pytest.warns(SingularityWarning, match="shoulder"):
        sol = ARM.ik(T, near=q)
    assert len(sol) == 4
    assert all(lab.startswith("left") for lab in sol.labels)
    assert all("shoulder" in f for f in sol.flags)
    for row in sol:
        assert _pose_error(ARM, row, T) < 1e-9
    assert joint_distance(sol[0], q) < 1e-7


def test_elbow_singular_stretched():
    t3 = np.arctan2(-D4, A3)  # a3 s3 + d4 c3 = 0: forearm in line with the upper arm
    q = np.array([0.5, -0.3, t3, 0.2, 1.0, 0.1])
    T = ARM.fk(q)
    # the wrist centre is at the maximal distance from the shoulder: |p|² = d3² + (a2 + sqrt(a3²+d4²))²
    assert np.isclose(T[:3, 3] @ T[:3, 3], D3**2 + (A2 + np.hypot(A3, D4)) ** 2)
    with pytest.warns(SingularityWarning, match="elbow"):
        sol = ARM.ik(T, near=q)
    assert len(sol) == 4
    assert all("/up/" in lab for lab in sol.labels)
    assert all("elbow" in f for f in sol.flags)
    for row in sol:
        assert _pose_error(ARM, row, T) < 1e-9
    assert joint_distance(sol[0], q) < 1e-6


def test_shoulder_elbow_and_wrist_singular_together():
    t3 = np.arctan2(-D4, A3)
    q = _shoulder_singular_q(t3)
    q[4] = 0.0
    T = ARM.fk(q)
    with pytest.warns(SingularityWarning):
        sol = ARM.ik(T, near=q)
    # left = right and up = down leave one arm branch, and its wrist is singular: one solution
    assert len(sol) == 1
    assert set(sol.flags[0]) == {"shoulder", "elbow", "wrist"}
    # two square roots of rounding noise (S1, S3 ~ 1e-8): the pose is met to ~1e-8, not 1e-12
    assert _pose_error(ARM, sol[0], T) < 1e-7


def _unreachable(sol, match: str) -> None:
    """The one policy for unreachable poses: no rows, success False, the reason in words, no NaN, no raise."""
    assert not sol.success and len(sol) == 0 and np.asarray(sol).shape == (0, 6)
    assert match in sol.reason
    with pytest.raises(IndexError, match=match):
        sol[0]


def test_out_of_reach_reports_the_reason():
    T = np.eye(4)
    T[:3, 3] = [1.2, 0.3, 0.4]
    _unreachable(ARM.ik(T), "out of reach")
    # a little beyond the stretched arm along the outer sphere
    r = np.sqrt(D3**2 + (A2 + np.hypot(A3, D4)) ** 2) * (1 + 1e-6)
    T[:3, 3] = r * np.array([1.0, 1.0, 1.0]) / np.sqrt(3.0)
    _unreachable(ARM.ik(T), "out of reach")


def test_too_close_to_the_base_axis_reports_the_reason():
    T = np.eye(4)
    T[:3, 3] = [0.05, 0.05, 0.3]  # ρ = 0.0707 < d3 = 0.15005
    _unreachable(ARM.ik(T), "too close to the base axis")


def test_batch_marks_unreachable_without_nan():
    q = _random_q(3, 4)
    T = ARM.fk(q)
    T[1, :3, 3] = [2.0, 0.0, 0.0]
    T[2, :3, 3] = [0.0, 0.0, 0.2]
    sol = ARM.ik_batch(T)
    assert sol.reachable.tolist() == [True, False, False]
    assert sol.valid[0].all() and not sol.valid[1:].any()
    assert np.isfinite(sol.q).all()
    assert "out of reach" in sol.reason[1]
    assert "too close to the base axis" in sol.reason[2]
    assert sol.reason[0] == ""


# ---------------------------------------------------------------- other lengths
@pytest.mark.parametrize(
    "lengths",
    [
        {"a2": 0.3, "a3": -0.05, "d3": -0.1, "d4": 0.5},
        {"a2": 1.0, "a3": 0.2, "d3": 0.0, "d4": 0.7},
        {"a2": 0.5, "a3": 0.0, "d3": 0.2, "d4": 0.3},
    ],
)
def test_non_default_lengths_round_trip(lengths):
    arm = Puma560(**lengths)
    q = _random_q(1000, 5)
    T = arm.fk(q)
    sol = arm.ik_batch(T)
    assert sol.valid.all()
    Tq = arm.fk(sol.q.reshape(-1, 6)).reshape(-1, 8, 4, 4)
    assert np.abs(Tq - T[:, None]).max() < 1e-9
    assert joint_distance(sol.q, q[:, None]).min(axis=1).max() < 1e-6


def test_d3_zero_wrist_on_the_base_axis():
    arm = Puma560(d3=0.0)
    q = np.array([0.7, -np.pi / 2, 0.0, 0.0, 0.5, 0.0])  # upper arm up, forearm along z0 (a3 sideways)
    # choose θ3 so that the wrist centre lands on the z0 axis: X = c2 vx - s2 vy = 0 with θ2 = -π/2 -> vy = 0
    q[2] = np.arctan2(-D4, A3) + np.pi  # a3 s3 + d4 c3 = 0 with the forearm folded back -> check below
    vx = A2 + A3 * np.cos(q[2]) - D4 * np.sin(q[2])
    vy = A3 * np.sin(q[2]) + D4 * np.cos(q[2])
    q[1] = np.arctan2(vx, vy)
    T = arm.fk(q)
    assert np.hypot(*T[:2, 3]) < 1e-12
    with pytest.warns(SingularityWarning, match="base_axis"):
        sol = arm.ik(T, near=q)
    assert all("base_axis" in f for f in sol.flags)
    for row in sol:
        assert _pose_error(arm, row, T) < 1e-9
    assert sol[0][0] == pytest.approx(q[0])  # θ1 taken from near


# ---------------------------------------------------------------- the distance the tests above rely on
def test_wrap_and_joint_distance_hand_worked():
    """joint_distance is the yardstick of every 'the original is among the solutions' check above:
    a distance that returned 0 would make them all pass, so it is pinned down by hand here."""
    assert np.allclose(
        wrap([np.pi, -np.pi, 3 * np.pi, 0.1 + 2 * np.pi, -0.1 - 4 * np.pi]), [np.pi, np.pi, np.pi, 0.1, -0.1]
    )
    assert wrap(-np.pi + 1e-9) == pytest.approx(-np.pi + 1e-9)  # just inside (-π, π]: unchanged
    assert joint_distance([np.pi - 0.1, 0.0], [-np.pi + 0.1, 0.0]) == pytest.approx(0.2)  # across ±π
    assert joint_distance([0.3, 0.0, 0.4], [0.0, 0.0, 0.0]) == pytest.approx(0.5)  # a 3-4-5 triangle
    assert joint_distance(np.zeros(6) + 1.0, np.zeros(6)) == pytest.approx(np.sqrt(6.0))
    d = joint_distance(np.zeros((4, 8, 6)), np.ones((4, 1, 6)))  # broadcast over branches
    assert d.shape == (4, 8) and np.allclose(d, np.sqrt(6.0))
    with pytest.raises(ValueError, match="q, q_ref: expected joint vectors of the same length"):
        joint_distance(np.zeros(6), np.zeros(5))


# ---------------------------------------------------------------- the result object and bad input
def test_result_object_behaves_like_an_array():
    q = np.array([0.1, -0.5, 0.3, 0.4, 0.6, -0.7])
    sol = ARM.ik(ARM.fk(q))
    assert len(sol) == 8 and np.asarray(sol).shape == (8, 6)
    assert np.array_equal(sol[2], np.asarray(sol)[2])
    assert np.allclose(sol.nearest(q), q)
    assert "8 solution(s)" in repr(sol) and "PUMA-560" in repr(sol)
    assert len(sol.labels) == len(set(sol.labels)) == 8


@pytest.mark.parametrize(
    "bad, match",
    [
        (np.eye(3), "4x4"),
        (np.full((4, 4), np.nan), "finite"),
        (np.diag([1.0, 2.0, 1.0, 1.0]), "rotation"),
        (np.diag([1.0, 1.0, -1.0, 1.0]), "reflection"),
        (np.vstack([np.eye(4)[:3], [[0.1, 0, 0, 1]]]), "last row"),
        ("eye", "4x4|real numbers"),
    ],
)
def test_bad_input_raises(bad, match):
    with pytest.raises(ValueError, match=match):
        ARM.ik(bad)
    with pytest.raises(ValueError):
        ARM.ik_batch(bad)


def test_bad_near_raises():
    T = ARM.fk(np.zeros(6) + 0.3)
    with pytest.raises(ValueError, match="near"):
        ARM.ik(T, near=np.zeros(5))
    with pytest.raises(ValueError, match="near"):
        ARM.ik(T, near=[np.nan] * 6)


def test_explicit_lengths_agree_with_the_defaults():
    q = _random_q(50, 6)
    T = ARM.fk(q)
    a = Puma560(A2, A3, D3, D4).ik_batch(T).q
    assert np.abs(ARM.fk(a.reshape(-1, 6)).reshape(-1, 8, 4, 4) - T[:, None]).max() < 1e-9
    with pytest.raises(ValueError, match="a2"):
        Puma560(a2=-1.0)


def test_scalar_fast_path_agrees_with_the_batch():
    """ik (plain floats, one pose) and ik_batch (numpy, N poses) are two codings of the same closed form:
    same branches, same angles, same flags, in general position and at every singular case."""
    cases = list(_random_q(200, 7))
    t3s = np.arctan2(-D4, A3)
    cases += [
        np.array([0.3, -0.6, 0.2, 0.9, 0.0, 0.4]),
        np.array([-0.4, -0.2, 0.5, 0.3, np.pi, -1.0]),
        _shoulder_singular_q(),
        np.array([0.5, -0.3, t3s, 0.2, 1.0, 0.1]),
        np.concatenate([_shoulder_singular_q(t3s)[:4], [0.0, 0.2]]),
    ]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SingularityWarning)
        for q in cases:
            T = ARM.fk(q)
            s = ARM.ik(T)
            b = ARM.ik_batch(T)
            keep = np.flatnonzero(b.valid[0])
            assert [BRANCH_LABELS[i] for i in keep] == list(s.labels)
            assert np.abs(wrap(np.asarray(s) - b.q[0, keep])).max() < 1e-12
            assert s.flags == tuple(b.keys(0, int(j)) for j in keep)
            assert (np.asarray(s) > -np.pi).all() and (np.asarray(s) <= np.pi).all()


def test_batch_near_fixes_the_free_wrist_angle():
    q = np.array([[0.3, -0.6, 0.2, 0.9, 0.0, 0.4], [0.1, -0.5, 0.3, 0.4, 0.6, -0.7]])
    sol = ARM.ik_batch(ARM.fk(q), near=q)
    k = int(np.argmax(sol.flags[0] & 4))
    assert sol.keys(0, k) == ("wrist",)
    assert sol.q[0, k, 3] == pytest.approx(0.9)  # θ4 from near
    assert joint_distance(sol.q[0, k], q[0]) < 1e-9
    assert not sol.flags[1].any()
    with pytest.raises(ValueError, match="near"):
        ARM.ik_batch(ARM.fk(q), near=np.zeros((2, 5)))
