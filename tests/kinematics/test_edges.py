"""Issue 21, the kinematics at every edge: snaps keep the pose, a near-threshold pose keeps the start
configuration (with ``near=``), ``ik`` and ``ik_batch`` agree on both sides of every threshold, tolerances
cannot switch the singularity logic into wrong answers, and extreme sizes are refused or answered right.

The truth is always the forward kinematics (an independent product of link matrices for the PUMA:
:meth:`DHChain.fk`), never the solver's own output."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from puma_course.kinematics import DHChain, Puma560

ANGLES = st.floats(-3.1, 3.1, allow_nan=False)
NEAR_ZERO = st.sampled_from([0.0, 1e-12, -1e-12, 1e-9, -1e-9, 5e-8, -5e-8, 1e-7, -1e-7, 2e-7, -2e-7, 1e-6])


def _size(arm: Puma560) -> float:
    a2, a3, d3, d4 = arm.lengths.values()
    return a2 + math.hypot(a3, d4) + abs(d3)


def _pose_error(arm: Puma560, rows, T) -> float:
    """Largest entry error of the poses the rows reach, through the generic product of link matrices."""
    rows = np.asarray(rows, dtype=float).reshape(-1, 6)
    if not len(rows):
        return 0.0
    return float(np.abs(DHChain.fk(arm, rows) - T).max())


def _wrapped(a):
    return np.abs(np.arctan2(np.sin(a), np.cos(a)))


def _check_pose_start_and_batch(arm: Puma560, q, tol: float = 1e-7, start_tol: float = 1e-6) -> None:
    T = arm.fk(q)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sol = arm.ik(T, near=q, tol=tol)
        batch = arm.ik_batch(T[None], near=q[None], tol=tol)
    assert sol.success
    rows = np.array(list(sol))
    assert _pose_error(arm, rows, T) <= 1e-9 * _size(arm)
    assert _wrapped(rows - q).max(axis=1).min() <= start_tol  # the start configuration is among them
    brows = batch.q[0][batch.valid[0]]
    assert len(brows) == len(rows)  # ik and ik_batch: the same count on both sides of every threshold
    for r in rows:  # ... and the same rows
        assert _wrapped(brows - r).max(axis=1).min() <= 1e-12


@settings(derandomize=True, max_examples=3000, deadline=None)
@given(st.lists(ANGLES, min_size=6, max_size=6), NEAR_ZERO, st.sampled_from([1e-7, 1e-12, 1e-3]))
def test_puma_wrist_near_and_at_theta5_zero_keeps_the_pose_at_any_tol(q, t5, tol):
    # issue 21: tol=1e-16 gave pose errors 0.17-1.9 at θ5 = 0; the snap moved the hand up to 1e-7;
    # ik and ik_batch counted differently at θ5 = -1e-7
    q = np.array(q)
    q[4] = t5
    _check_pose_start_and_batch(Puma560(), q, tol)


@settings(derandomize=True, max_examples=3000, deadline=None)
@given(st.lists(ANGLES, min_size=6, max_size=6), NEAR_ZERO)
def test_puma_elbow_near_stretched_keeps_the_pose_and_the_start(q, dt3):
    arm = Puma560()
    a2, a3, d3, d4 = arm.lengths.values()
    q = np.array(q)
    q[2] = math.atan2(a3, d4) - math.pi / 2 + dt3  # S3 = 0 at dt3 = 0 (arm stretched)
    q[4] = math.copysign(min(max(abs(q[4]), 0.01), 3.13), q[4])  # the compound case is the wrist test's
    # within the elbow snap (S3 < 1e-7 size) θ3 is exactly the stretched angle, up to ~2e-7 rad from the
    # start; the wrist takes up that difference amplified by 1 / sin θ5: the start is that near
    _check_pose_start_and_batch(arm, q, start_tol=1e-6 + 4e-7 / abs(math.sin(q[4])))


def _on_axis_theta2(arm: Puma560, t3: float) -> float:
    """θ2 putting the wrist centre of a d3 = 0 arm on the base axis (reach X = 0), by bisection."""
    a2, a3, _, d4 = arm.lengths.values()

    def reach(t2: float) -> float:
        return a2 * math.cos(t2) + a3 * math.cos(t2 + t3) - d4 * math.sin(t2 + t3)

    lo, hi = -math.pi, 0.0
    grid = np.linspace(lo, hi, 64)
    vals = [reach(g) for g in grid]
    for g0, g1, v0, v1 in zip(grid[:-1], grid[1:], vals[:-1], vals[1:], strict=True):
        if v0 * v1 <= 0:
            lo, hi = g0, g1
            break
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        if (reach(lo) <= 0) == (reach(mid) <= 0):
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


@settings(derandomize=True, max_examples=1000, deadline=None)
@given(st.lists(ANGLES, min_size=6, max_size=6), st.sampled_from([0.0, 1e-12, -1e-12, 1e-9, 5e-8, -5e-8, 2e-7]))
def test_puma_d3_zero_wrist_near_the_base_axis_keeps_the_pose(q, dt2):
    # issue 21: Puma560(d3=0) snapped a wrist 5e-8 m from the base axis onto it (error 4.6e-8 m)
    arm = Puma560(d3=0.0)
    q = np.array(q)
    q[2] = min(max(q[2], -2.5), 0.5)
    q[1] = _on_axis_theta2(arm, q[2]) + dt2
    _check_pose_start_and_batch(arm, q)


@pytest.mark.parametrize("tol", [1e-16, 1e-13, 0.0, -1e-7])
def test_puma_refuses_a_tolerance_float64_cannot_honour(tol):
    # issue 21: tol=1e-16 switched the wrist singularity off and answered wrongly with success=True
    arm = Puma560()
    T = arm.fk(np.zeros(6))
    for f in (arm.ik, arm.ik_batch):
        with pytest.raises(ValueError, match=r"tol: .*1e-12 <= tol <= 0.01.*got|tol: expected a small positive"):
            f(T, tol=tol)


def test_puma_accepts_the_smallest_honoured_tolerance():
    arm = Puma560()
    q = np.array([0.3, -0.4, 0.2, 1.0, 0.0, 0.5])
    _check_pose_start_and_batch(arm, q, tol=1e-12)


# ---------------------------------------------------------------------------------------------------- MK3
def _mk3_wrist_near_axis_configs(n: int, seed: int) -> np.ndarray:
    """Configurations of the MK3 whose wrist point is 1e-7..1e-4 mm from the base axis (θ2 by bisection)."""
    from puma_course.kinematics import MK3

    d1, a1, a2, a3, d5 = MK3().lengths.values()
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < n:
        q = rng.uniform(-3, 3, 5)
        e = 10 ** rng.uniform(-7, -4) * rng.choice([-1, 1])

        def f(t2: float, q=q, e=e) -> float:
            return a1 + a2 * math.cos(t2) + a3 * math.cos(t2 + q[2]) - e

        g = np.linspace(-math.pi, math.pi, 400)
        v = [f(t) for t in g]
        idx = [i for i in range(399) if v[i] * v[i + 1] <= 0]
        if not idx:
            continue
        lo, hi = g[idx[0]], g[idx[0] + 1]
        for _ in range(100):
            mid = 0.5 * (lo + hi)
            if (f(lo) <= 0) == (f(mid) <= 0):
                lo = mid
            else:
                hi = mid
        q[1] = 0.5 * (lo + hi)
        out.append(q)
    return np.array(out)


def test_mk3_reaches_poses_with_the_wrist_point_microns_from_the_base_axis():
    # issue 21: up to 191 of 200 such poses were called "out of the arm plane"
    from puma_course.kinematics import MK3

    arm = MK3()
    size = sum(abs(v) for v in arm.lengths.values())
    Q = _mk3_wrist_near_axis_configs(200, seed=21)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for q in Q:
            T = arm.fk(q)
            sol = arm.ik(T, near=q)
            assert sol.success, sol.reason
            assert max(np.abs(DHChain.fk(arm, r) - T).max() for r in sol) <= 1e-9 * size
            assert _wrapped(np.array(list(sol)) - q).max(axis=1).min() <= 1e-6
        b = arm.ik_batch(arm.fk(Q), near=Q)
    assert b.reachable.all()


@pytest.mark.parametrize("tol", [1e-16, 1e-13])
def test_mk3_refuses_a_tolerance_float64_cannot_honour(tol):
    # issue 21: MK3.ik(fk(q), tol=1e-16) refused 37 of 200 reachable poses
    from puma_course.kinematics import MK3

    arm = MK3()
    with pytest.raises(ValueError, match=r"tol: expected a tolerance with 1e-12 <= tol <= 0.01 .*got 1e-1"):
        arm.ik(arm.fk(np.zeros(5)), tol=tol)


# ---------------------------------------------------------------------------------------------------- BLAS
_PORTER_PARALLEL = """
import sys, warnings
import numpy as np
from puma_course.kinematics import Porter
warnings.simplefilter("ignore")
arm = Porter()
rng = np.random.default_rng(21)
out = []
for k in range(60):
    q = rng.uniform(-3, 3, 6); q[2] = abs(q[2]) + 0.2; q[4] = np.pi / 2 * rng.choice([1, 3])
    near = q + rng.normal(0, 0.3, 6); near[2] = abs(near[2])
    sol = arm.ik(arm.fk(q), near=near)
    out.extend(float(v).hex() for r in sol for v in r)
print(" ".join(out))
"""


def test_porter_ik_near_at_parallel_planes_is_bit_identical_under_two_openblas_kernels():
    # issue 21: Porter's ik(near) at c4 = 0 differed by up to 1.3e-8 between Haswell and Prescott
    # (families.nearest_parallel used `@` and np.linalg.norm). Both of CI's kernels, in subprocesses,
    # so that this test catches it in either pass.
    import os
    import subprocess
    import sys
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    sys.path.insert(0, str(root / ".ci"))
    try:
        from openblas_kernels import kernels
    finally:
        sys.path.pop(0)
    k1, k2 = kernels()
    if not k1 or k1 == k2:
        pytest.skip("no two OpenBLAS kernels known for this CPU")
    outs = []
    for k in (k1, k2):
        env = {**os.environ, "OPENBLAS_CORETYPE": k}
        run = subprocess.run([sys.executable, "-c", _PORTER_PARALLEL], env=env, capture_output=True, text=True,
                             timeout=120, check=True)  # fmt: skip
        outs.append(run.stdout.split())
    assert len(outs[0]) > 100
    assert outs[0] == outs[1]


# ---------------------------------------------------------------------------------------------------- follow
@pytest.mark.parametrize("robot", ["puma", "porter"])
def test_follow_does_not_jump_at_an_exactly_singular_sample(robot):
    # issue 21: follow called ik_batch without near: PUMA θ4 went 1.114 -> 0 -> 1.095 through θ5 = 0,
    # Porter stepped 1.77 rad through c4 = 0
    from puma_course.kinematics import Porter
    from puma_course.kinematics.trajectories import follow

    if robot == "puma":
        arm = Puma560()
        qa = np.array([0.2, -0.5, 0.3, 1.114, -0.1, 0.4])
        qb = np.array([0.3, -0.4, 0.2, 1.095, 0.1, 0.5])
    else:
        arm = Porter()
        qa = np.array([0.3, 0.4, 0.5, 0.6, math.pi / 2 - 0.1, 0.2])
        qb = np.array([0.35, 0.45, 0.55, 0.65, math.pi / 2 + 0.1, 0.25])
    Q = qa + np.linspace(0.0, 1.0, 21)[:, None] * (qb - qa)  # sample 10 is exactly singular
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        jp = follow(arm, arm.fk(Q), Q[0])
    dq = float(np.linalg.norm(qb - qa)) / 20
    assert jp.start_jump < 1e-6
    assert jp.max_step < 3 * dq, jp.step


# ---------------------------------------------------------------------------------------------------- common normal
@pytest.mark.parametrize("delta", [5e-9, 1.2e-8, 1e-7, 1e-5, 0.3])
@pytest.mark.parametrize("seed", range(5))
def test_common_normal_of_nearly_parallel_lines(delta, seed):
    # issue 21: ZeroDivisionError 5e-9 rad from parallel, 35% off at 1.2e-8. Hand-worked in a local frame:
    # the z axis and the line through (0, 1, 0) along (sin δ, 0, cos δ) are 1 apart along y, with feet
    # (0, 0, 0) and (0, 1, 0); then the whole picture is moved rigidly (the truth moves with it).
    from puma_course.kinematics.frame_assignment import common_normal
    from puma_course.transforms import rodrigues

    rng = np.random.default_rng(seed)
    R = rodrigues(rng.normal(size=3), rng.uniform(0, 3))
    o = rng.uniform(-2, 2, 3)
    u2 = np.array([math.sin(delta), 0.0, math.cos(delta)])
    t0 = rng.uniform(-3, 3)
    cn = common_normal(o + R @ [0.0, 0.0, rng.uniform(-3, 3)], R[:, 2], o + R @ ([0.0, 1.0, 0.0] + t0 * u2), R @ u2)
    assert cn.kind == "skew"
    assert abs(cn.a - 1.0) <= 1e-6
    assert np.abs(cn.direction - R[:, 1]).max() <= 1e-6
    # where along the lines the normal sits moves by (rounding of the input) / δ², O(1) at δ = 5e-9: the
    # feet are checked for what they must be, on their lines and joined by a X
    for foot, p, u in ((cn.foot1, o, R[:, 2]), (cn.foot2, o + R[:, 1], R @ u2)):
        off = foot - p
        assert np.abs(off - np.dot(off, u) * u).max() <= 1e-6
    assert np.abs(cn.foot2 - cn.foot1 - cn.a * cn.direction).max() <= 1e-6
    if delta >= 1e-5:
        assert np.abs(cn.foot1 - o).max() <= 1e-6 and np.abs(cn.foot2 - (o + R[:, 1])).max() <= 1e-6
    assert abs(cn.alpha - delta) <= 1e-9  # about X = +y, z turns to (sin δ, 0, cos δ) by +δ


# ---------------------------------------------------------------------------------------------------- extreme sizes
def test_extreme_sizes_are_answered_right():
    # issue 21: rodrigues([1e200, 0, 0], 0.3) was the identity; porter.angle of 1e200 vectors NaN and of
    # 1e-200 vectors 0 instead of π/2
    from puma_course.kinematics.porter import angle
    from puma_course.transforms import rodrigues, rotx

    for big in (1e200, 1e-200, 1e-310, 1e150):
        assert np.abs(rodrigues([big, 0.0, 0.0], 0.3) - rotx(0.3)).max() <= 1e-15
    for size in (1e200, 1e-200, 1.0):
        v, w, n = np.array([size, 0.0, 0.0]), np.array([0.0, size, 0.0]), np.array([0.0, 0.0, size])
        assert angle(v, w, n) == math.pi / 2


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda: __import__("puma_course.kinematics", fromlist=["ThreeStepArm"]).ThreeStepArm(1.5e100, 1e100), "l1"),
        (lambda: __import__("puma_course.kinematics", fromlist=["ThreeStepArm"]).ThreeStepArm(1.0, 1e-100), "l2"),
        (lambda: Puma560(a3=1e150), "a3"),
        (
            lambda: __import__("puma_course.kinematics.spaces", fromlist=["x"]).joint_from_actuator(
                1e150, 1e150, 1e150
            ),
            "b",
        ),
        (lambda: __import__("puma_course.kinematics.trajectories", fromlist=["x"]).time_scaling(1e-200, 5), "duration"),
        (lambda: __import__("puma_course.kinematics.trajectories", fromlist=["x"]).time_scaling(1.0, 1e300), "n"),
        (
            lambda: DHChain([__import__("puma_course.kinematics", fromlist=["Link"]).Link(0, 0, 0, kind="P")]).fk(
                [1e308]
            ),
            "q",
        ),
        (lambda: __import__("puma_course.kinematics.ik", fromlist=["x"]).IKSolutions(np.array([[np.nan, 0.0]])), "q"),
    ],
)
def test_extreme_sizes_are_refused_naming_the_argument(call, name):
    # issue 21: ThreeStepArm(1.5e100, 1e100) returned 8 "valid" solutions 156% off; Puma560(a3=1e150) could
    # not solve its own fk; joint_from_actuator(1e150, ...) gave π/2 for π/3; time_scaling(1e-200, 5) NaN and
    # inf; a prismatic DHChain at 1e308 inf; IKSolutions took NaN rows; int8 lengths overflowed
    with pytest.raises(ValueError, match=rf"^{name}\b.*expected"):
        call()


def test_contract_junk_that_was_accepted():
    # issue 21: is_rotation(ones, tol=nan) was True; wrap_angle(None) NaN
    from puma_course.transforms import is_rotation, wrap_angle

    with pytest.raises(ValueError, match="^tol"):
        is_rotation(np.ones((3, 3)), tol=float("nan"))
    with pytest.raises(ValueError, match="^angle"):
        wrap_angle(None)
    assert is_rotation(np.eye(3)) and not is_rotation(np.ones((3, 3)))


def test_solve_three_steps_with_int8_lengths_computes_in_floats():
    # issue 21: int8 lengths overflowed to "l1 + l2 = -56"
    from puma_course.kinematics.three_step.procedure import solve_three_steps

    a = solve_three_steps([150.0, 20.0, 30.0], np.eye(3), np.int8(100), np.int8(100))
    b = solve_three_steps([150.0, 20.0, 30.0], np.eye(3), 100.0, 100.0)
    assert a.theta0 == b.theta0 and a.theta1 == b.theta1 and a.theta2 == b.theta2


# ---------------------------------------------------------------------------------------------------- three-step arm
@settings(derandomize=True, max_examples=500, deadline=None)
@given(st.lists(ANGLES, min_size=6, max_size=6), st.sampled_from([0.0, 1e-9, -1e-7, 1e-6, 2e-5, -5e-5, 9e-5]))
def test_three_step_elbow_near_stretched_keeps_every_solution(q, dt2):
    # issue 21: the elbow snap was a length tolerance spanning ~9e-5 rad of θ2: 8 of 100k poses lost half
    # their solutions, the start included
    from puma_course.kinematics import ThreeStepArm

    arm = ThreeStepArm(1.5, 1.0)
    q = np.array(q)
    q[2] = dt2
    q[4] = math.copysign(min(max(abs(q[4]), 0.05), 3.09), q[4])  # the wrist away from its own singularity
    T = arm.fk(q)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sol = arm.ik(T, near=q)
        b = arm.ik_batch(T[None], near=q[None])
    rows = np.array(list(sol))
    assert np.abs(arm.fk(rows) - T).max() <= 1e-9 * 2.5
    # the start is among them, within the conditioning of the stretched elbow (sqrt(eps) in θ2)
    assert _wrapped(rows - q).max(axis=1).min() <= 1e-6 + (0 if abs(dt2) > 1e-6 else 1e-6)
    assert b.valid.sum() == len(rows)
    if abs(dt2) >= 1e-6:  # elbow up and down are distinct solutions: both kept
        assert len(rows) == 8


def test_three_step_just_beyond_reach_gives_no_duplicate_pairs():
    # issue 21: a pose 2.5e-9 beyond reach got 8 "valid" solutions that were four duplicate pairs, unflagged
    from puma_course.kinematics import ThreeStepArm

    arm = ThreeStepArm(1.5, 1.0)
    T = arm.fk(np.array([0.3, 0.4, 0.0, 0.2, 0.5, 0.1]))
    w = T[:3, 3] - 0.0  # the tool is at the wrist centre for this arm
    for beyond in (0.0, 1e-12, 1e-9, 2.4e-9):
        Tb = T.copy()
        Tb[:3, 3] = w * (1.0 + beyond / np.linalg.norm(w))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            sol = arm.ik(Tb)
        rows = np.array(list(sol))
        assert len(rows) == 4 and all("elbow" in f for f in sol.flags)
        d = _wrapped(rows[:, None, :] - rows[None, :, :]).max(axis=-1) + np.eye(len(rows))
        assert d.min() > 1e-6  # distinct
        assert np.abs(arm.fk(rows)[:, :3, 3] - Tb[:3, 3]).max() <= 1e-9 * 2.5 + beyond


# ---------------------------------------------------------------------------------------------------- Euler angles
LOCK_OFFSETS = st.sampled_from([1.01e-9, -1.01e-9, 1.5e-9, -2e-9, 5e-9, -1e-8, 1e-7, -1e-6, 1e-5])


@settings(derandomize=True, max_examples=1000, deadline=None)
@given(ANGLES, ANGLES, ANGLES, LOCK_OFFSETS, st.booleans())
def test_euler_just_above_the_lock_snap_round_trips_on_products_of_rotations(a, b, c, d, other_end):
    # issue 21: ZYZ/RPY just above the 1e-9 snap round-tripped only to 1.1e-7 when R is a product of rotations
    # (its small entries then carry absolute, not relative, rounding); the truth is R itself
    from puma_course.euler import rotation_from_rpy, rotation_from_zyz, rpy_from_rotation, zyz_from_rotation
    from puma_course.transforms import rotx, roty, rotz

    th = (math.pi if other_end else 0.0) + d
    R = rotz(a) @ roty(b) @ roty(th - b) @ rotz(c)
    assert np.abs(rotation_from_zyz(*zyz_from_rotation(R)) - R).max() <= 1e-14
    p = (-math.pi / 2 if other_end else math.pi / 2) + d
    R = rotz(a) @ roty(b) @ roty(p - b) @ rotx(c)
    assert np.abs(rotation_from_rpy(*rpy_from_rotation(R)) - R).max() <= 1e-14


@settings(derandomize=True, max_examples=300, deadline=None)
@given(st.lists(ANGLES, min_size=6, max_size=6), LOCK_OFFSETS, st.booleans())
def test_three_step_wrist_just_above_the_lock_keeps_the_pose(q, d, other_end):
    # issue 21: ThreeStepArm.ik inherited the Euler error just above the wrist snap (pose error 1.6e-7)
    from puma_course.kinematics import ThreeStepArm
    from puma_course.transforms import roty, rotz

    arm = ThreeStepArm(1.5, 1.0)
    q = np.array(q)
    q[4] = (math.pi if other_end else 0.0) + d
    T = arm.fk(q)
    T[:3, :3] = T[:3, :3] @ rotz(q[5]).T @ roty(0.7).T @ roty(0.7) @ rotz(q[5])  # rounding as a product has it
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sol = arm.ik(T, near=q)
    rows = np.array(list(sol))
    assert len(rows) and np.abs(arm.fk(rows) - T).max() <= 1e-9 * 2.5


# ---------------------------------------------------------------------------------------------------- Porter ik_batch
@settings(derandomize=True, max_examples=400, deadline=None)
@given(st.lists(ANGLES, min_size=6, max_size=6), NEAR_ZERO, st.booleans(), st.sampled_from([0.0, 0.3, 1.2]),
       st.sampled_from([0.0, 0.05, 0.4]))  # fmt: skip
def test_porter_ik_and_ik_batch_agree_with_near_on_both_sides_of_c4_zero(q, d4, back, q2, noise):
    # issue 21: Porter's ik_batch ignored `near` at c4 = 0 (planes parallel), so ik and ik_batch differed there
    from puma_course.kinematics import Porter

    arm = Porter()
    q = np.array(q)
    q[2] = q2
    q[4] = (-math.pi / 2 if back else math.pi / 2) + d4
    T = arm.fk(q)
    near = q + noise * np.sin(np.arange(6) + 1.0)
    near[2] = abs(near[2])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sol = arm.ik(T, near=near)
        b = arm.ik_batch(T[None], near=near[None])
    rows = np.array(list(sol)).reshape(-1, 6)
    brows = b.q[0][b.valid[0]]
    assert len(brows) == len(rows)
    for r in rows:
        assert _wrapped(brows - r).max(axis=1).min() <= 1e-12


# ---------------------------------------------------------------------------------------------------- start kept
NEAR_OFFSETS = st.sampled_from([0.0, 1e-12, -1e-12, 1e-9, -1e-9, 5e-8, -5e-8, 1e-7, -1e-7, 1e-6])


@settings(derandomize=True, max_examples=3000, deadline=None)
@given(st.lists(ANGLES, min_size=6, max_size=6), NEAR_OFFSETS, NEAR_OFFSETS, NEAR_OFFSETS, st.booleans(),
       st.booleans(), st.booleans())  # fmt: skip
def test_porter_keeps_the_start_at_compound_near_singular_poses(q, d4, dq2, d23, back, q2_small, planar):
    # issue 21: with near=q0 and q0's pose, q0 was missing in 135 of 3,000 examples (worst 4 rad)
    from puma_course.kinematics import Porter

    arm = Porter()
    q = np.array(q)
    q[4] = (-math.pi / 2 if back else math.pi / 2) + d4  # c4 ~ 0: planes (nearly) parallel
    q[2] = abs(dq2) if q2_small else abs(q[2])  # q2 ~ 0
    if planar:
        q[3] = -q[1] + d23
    T = arm.fk(q)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sol = arm.ik(T, near=q)
        b = arm.ik_batch(T[None], near=q[None])
    rows = np.array(list(sol)).reshape(-1, 6)
    assert np.abs(arm.fk(rows) - T).max() <= 1e-9 * max(1.0, float(np.abs(T[:3, 3]).max()))
    d = np.abs(rows - q)
    d[:, [0, 1, 3, 4, 5]] = _wrapped(d[:, [0, 1, 3, 4, 5]])
    assert d.max(axis=1).min() <= 1e-12
    brows = b.q[0][b.valid[0]]
    assert len(brows) == len(rows)
    for r in rows:
        assert _wrapped(brows - r).max(axis=1).min() <= 1e-12


@settings(derandomize=True, max_examples=3000, deadline=None)
@given(st.lists(ANGLES, min_size=6, max_size=6), NEAR_OFFSETS, NEAR_OFFSETS, NEAR_OFFSETS, st.booleans(),
       st.booleans(), st.booleans())  # fmt: skip
def test_three_step_keeps_the_start_at_compound_near_singular_poses(q, d4, d2, d1, flipped, elbow, axis):
    # issue 21: with near=q0 and q0's pose, q0 was missing in 160 of 3,000 examples (worst 4 rad)
    from puma_course.kinematics import ThreeStepArm

    arm = ThreeStepArm(1.5, 1.0)
    q = np.array(q)
    q[4] = (math.pi if flipped else 0.0) + d4  # the wrist near its lock
    if elbow:
        q[2] = d2  # the elbow near stretched
    if axis:
        q[1] = math.pi / 2 + d1  # the wrist centre near the base axis (with a stretched elbow)
    T = arm.fk(q)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sol = arm.ik(T, near=q)
        b = arm.ik_batch(T[None], near=q[None])
    rows = np.array(list(sol)).reshape(-1, 6)
    assert np.abs(arm.fk(rows) - T).max() <= 1e-9 * 2.5
    assert _wrapped(rows - q).max(axis=1).min() <= 1e-12
    assert b.valid.sum() == len(rows)


# ---------------------------------------------------------------------------------------------------- the sizes
@pytest.mark.slow
def test_three_step_100k_random_poses_keep_all_eight_solutions_and_the_start():
    # issue 21, at the size that found it: 8 of 100k random poses lost half their solutions (the start included)
    # to the elbow snap. Seeded; the truth is the pose (fk of every returned row) and the start configuration.
    from puma_course.kinematics import ThreeStepArm

    arm = ThreeStepArm(1.5, 1.0)
    Q = np.random.default_rng(21).uniform(-3.1, 3.1, (100_000, 6))
    T = arm.fk(Q)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        b = arm.ik_batch(T, near=Q)
    counts = b.valid.sum(axis=1)
    assert (counts == 8).all(), np.bincount(counts)
    start = np.where(b.valid, _wrapped(b.q - Q[:, None, :]).max(axis=-1), np.inf).min(axis=1)
    assert start.max() <= 1e-6
    assert np.abs(arm.fk(b.q[b.valid]) - np.repeat(T, counts, axis=0)).max() <= 1e-9 * 2.5


def test_puma_ik_and_ik_batch_count_alike_at_theta5_minus_1e7():
    # issue 21: at θ5 = -1e-7, ik and ik_batch returned different counts for 11 of 200 poses
    arm = Puma560()
    Q = np.random.default_rng(21).uniform(-3.1, 3.1, (200, 6))
    Q[:, 4] = -1e-7
    T = arm.fk(Q)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        b = arm.ik_batch(T, near=Q)
        for i in range(len(Q)):
            sol = arm.ik(T[i], near=Q[i])
            rows = np.array(list(sol))
            brows = b.q[i][b.valid[i]]
            assert len(brows) == len(rows)
            for r in rows:
                assert _wrapped(brows - r).max(axis=1).min() <= 1e-12
            assert _pose_error(arm, rows, T[i]) <= 1e-9 * _size(arm)


@pytest.mark.parametrize("tol", [1e-10, 1e-15, 1e-300])
def test_common_normal_refuses_a_tolerance_below_what_rounding_allows(tol):
    # issue 21 (found by the contract sweep): with tol = 1e-15, lines 1e-14..1e-12 rad from parallel got feet
    # off by up to 1.0 (rounding / δ), 1.7% at 1e-14; below 1e-9 such lines must be called parallel or refused
    from puma_course.kinematics.frame_assignment import common_normal

    with pytest.raises(ValueError, match=r"^tol: expected a tolerance with 1e-09 <= tol"):
        common_normal([0, 0, 0], [0, 0, 1.0], [1.0, 0, 5], [0, 1.0, 0], tol=tol)


def test_is_rotation_honours_only_what_float64_can():
    # a product of twenty rotations is off orthonormal by up to 4e-15: a tolerance below 1e-12 is refused rather
    # than answering False for a rotation
    from puma_course.transforms import is_rotation, rodrigues

    rng = np.random.default_rng(0)
    R = np.eye(3)
    for _ in range(20):
        R = R @ rodrigues(rng.normal(size=3), rng.uniform(-3, 3))
    assert is_rotation(R, tol=1e-12)
    with pytest.raises(ValueError, match="^tol"):
        is_rotation(R, tol=1e-15)
