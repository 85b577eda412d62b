"""Tests of Porter's PUMA-like chain (puma_course.kinematics.porter): direct problem and both inverse methods.

Truths used (never the module's own output): hand-worked poses, an independent composition
with ``transforms`` (trotz, transz, ...), geometric invariants of the chain (rod lengths,
coplanarity), round trips fk(ik(T)) = T and the original configuration among the solutions.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from puma_course import transforms as tf
from puma_course.kinematics import IKSolutions, Porter, SingularityWarning
from puma_course.kinematics.ik import joint_distance
from puma_course.kinematics.porter import REVOLUTE, angle

L1, L3, L4 = 1.0, 0.5, 0.3
LEN = (L1, L3, L4)
TWO_PI = 2 * np.pi
ARM = Porter(*LEN)
AXIS, PARALLEL, Q2_ZERO = "p4_on_z0_axis", "planes_parallel", "q2_zero"


def dist(a, b) -> np.ndarray:
    """The configuration distance (angles wrapped, q2 as it is)."""
    return joint_distance(a, b, REVOLUTE)


def explicit(T, **kw) -> np.ndarray:
    return np.asarray(ARM.ik(T, **kw))


def geometric(T, **kw) -> np.ndarray:
    return np.asarray(ARM.ik(T, method="geometric", **kw))


def random_q(rng: np.random.Generator, n: int, q2_min: float = 0.05) -> np.ndarray:
    q = rng.uniform(0.0, TWO_PI, (n, 6))
    q[:, 2] = rng.uniform(q2_min, 2.0, n)
    return q


def fk_by_transforms(q) -> np.ndarray:
    """The local-frame product composed with the transforms module (independent of porter)."""
    a1, a2, q2, a3, a4, a5 = q
    return tf.compose_moving(
        tf.trotz(a1), tf.transz(L1), tf.troty(a2), tf.transx(q2), tf.troty(a3), tf.transz(-L3), tf.trotz(a4),
        tf.transx(L4), tf.trotx(a5),
    )  # fmt: skip


def in_space(S: np.ndarray) -> bool:
    """Angles in (-π, π] (the course's one range for revolute joints), q2 >= 0, all finite."""
    S = np.asarray(S)
    ang = S[:, [0, 1, 3, 4, 5]]
    return bool(np.all((ang > -np.pi) & (ang <= np.pi)) and np.all(S[:, 2] >= 0) and np.all(np.isfinite(S)))


def quiet(fn, *a, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SingularityWarning)
        return fn(*a, **kw)


# ----------------------------------------------------------------------------- direct problem


def test_fk_hand_worked():
    # q = 0: p2 = (0,0,l1), p3 = p2, p4 = p3 - l3 z = (0,0,l1-l3), p5 = p4 + l4 x
    T = ARM.fk(np.zeros(6))
    np.testing.assert_allclose(T, tf.transl([L4, 0, L1 - L3]), atol=1e-15)
    # α1 = π/2, q2 = 2: the arm plane is the y-z plane, p5 = (0, 2 + l4, l1 - l3), x5 = e2
    T = ARM.fk([np.pi / 2, 0, 2.0, 0, 0, 0])
    np.testing.assert_allclose(T[:3, 3], [0, 2 + L4, L1 - L3], atol=1e-15)
    np.testing.assert_allclose(T[:3, 0], [0, 1, 0], atol=1e-15)
    # α2 = -π/2 points the prismatic axis up: p3 = (0, 0, l1 + q2); α3 = π/2 then brings z3 along -x... :
    # z3 = Ry(α2 + α3) e3 = e3, p4 = p3 - l3 e3, x4 = Ry(0) e1 = e1
    T = ARM.fk([0, -np.pi / 2, 1.5, np.pi / 2, 0, 0])
    np.testing.assert_allclose(T[:3, 3], [L4, 0, L1 + 1.5 - L3], atol=1e-15)


def test_fk_matches_independent_composition_and_batches():
    rng = np.random.default_rng(1)
    Q = random_q(rng, 50)
    T = ARM.fk(Q)
    assert T.shape == (50, 4, 4)
    for q, Tq in zip(Q, T, strict=True):
        np.testing.assert_allclose(Tq, fk_by_transforms(q), atol=1e-13)
    np.testing.assert_allclose(ARM.fk(Q[7]), T[7], atol=0)


def test_frames_geometry():
    rng = np.random.default_rng(2)
    Q = random_q(rng, 200)
    F = ARM.frames(Q)
    assert F.shape == (200, 6, 4, 4)
    R = F[..., :3, :3]
    np.testing.assert_allclose(np.swapaxes(R, -1, -2) @ R, np.broadcast_to(np.eye(3), R.shape), atol=1e-13)
    np.testing.assert_allclose(np.linalg.det(R), 1.0, atol=1e-13)
    p = ARM.points(Q)
    np.testing.assert_allclose(p[:, 0], 0.0, atol=0)
    np.testing.assert_allclose(p[:, 1], 0.0, atol=0)
    np.testing.assert_allclose(p[:, 2], np.broadcast_to([0, 0, L1], (200, 3)), atol=0)
    np.testing.assert_allclose(np.linalg.norm(p[:, 3] - p[:, 2], axis=1), Q[:, 2], atol=1e-13)
    np.testing.assert_allclose(np.linalg.norm(p[:, 4] - p[:, 3], axis=1), L3, atol=1e-13)
    np.testing.assert_allclose(np.linalg.norm(p[:, 5] - p[:, 4], axis=1), L4, atol=1e-13)
    # p0, p2, p3, p4 lie in the vertical arm plane with normal y1 = (-s1, c1, 0)
    y1 = np.stack([-np.sin(Q[:, 0]), np.cos(Q[:, 0]), 0 * Q[:, 0]], axis=1)
    for k in (3, 4):
        np.testing.assert_allclose(np.einsum("ni,ni->n", p[:, k], y1), 0.0, atol=1e-13)
    # p3 - p4 = l3 z4 is perpendicular to x5 (Ver.2's second condition)
    x5 = F[:, 5, :3, 0]
    np.testing.assert_allclose(np.einsum("ni,ni->n", p[:, 3] - p[:, 4], x5), 0.0, atol=1e-13)
    np.testing.assert_allclose(F[:, 5], ARM.fk(Q), atol=0)


# ----------------------------------------------------------------------------- inverse, general position


def test_ver1_round_trip_many_poses_batched():
    rng = np.random.default_rng(3)
    N = 5000
    Q = random_q(rng, N)
    T = ARM.fk(Q)
    b = ARM.ik_batch(T)
    S, flags = b.q, b.flags
    assert S.shape == (N, 4, 6) and not flags.any()
    back = ARM.fk(S.reshape(-1, 6)).reshape(N, 4, 4, 4)
    assert np.abs(back - T[:, None]).max() < 1e-12
    assert dist(S, Q[:, None, :]).min(axis=1).max() < 1e-9  # the original is among them
    assert in_space(S.reshape(-1, 6))


def test_ver1_scalar_round_trip_count_and_original():
    rng = np.random.default_rng(4)
    Q = random_q(rng, 400)
    for q in Q:
        T = ARM.fk(q)
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # general position: no warning at all
            S = explicit(T)
        # Four solutions, by an argument independent of eqs. 8-16: p4 = p5 - l4 x5 is fixed; the
        # vertical plane through z0 and p4 can be entered with α1 or α1 + π; z3 must lie in that
        # plane and be perpendicular to x5 (x5 = x4 ⊥ z4 = z3): two unit vectors ±z3; then
        # p3 = p4 + l3 z3 and q2 x2 = p3 - p2 with q2 >= 0 fix q2 and α2 uniquely, and α4, α5
        # follow from the rotation. 2 x 2 = 4 (Porter's 8 counts q2 < 0 as well).
        assert S.shape == (4, 6)
        assert in_space(S)
        assert np.abs(ARM.fk(S) - T).max() < 1e-12
        assert dist(S, q).min() < 1e-9
        # the four are distinct and form two point sequences p0..p5 differing in p3 only
        D = dist(S[:, None], S[None])
        assert D[~np.eye(4, dtype=bool)].min() > 1e-6
        pts = ARM.points(S)
        p3 = np.unique(np.round(pts[:, 3], 9), axis=0)
        assert len(p3) == 2
        same = pts[:, [0, 1, 2, 4, 5]]
        np.testing.assert_allclose(same, np.broadcast_to(same[0], same.shape), atol=1e-12)


def test_ver2_round_trip_and_subset_of_ver1():
    rng = np.random.default_rng(5)
    for q in random_q(rng, 300):
        T = ARM.fk(q)
        G = geometric(T)
        S = explicit(T)
        assert G.shape == (2, 6) and in_space(G)
        assert np.abs(ARM.fk(G) - T).max() < 1e-12
        for g in G:
            assert dist(S, g).min() < 1e-9
        # Ver.2 keeps the arm plane with p4 on the positive side: α1 = atan2(p4_2, p4_1)
        p4 = T[:3, 3] - L4 * T[:3, 0]
        assert np.allclose(np.cos(G[:, 0] - np.arctan2(p4[1], p4[0])), 1.0)


def test_near_sorts_and_nearest():
    rng = np.random.default_rng(6)
    for q in random_q(rng, 50):
        T = ARM.fk(q)
        S = explicit(T, near=q)
        d = dist(S, q)
        assert np.all(np.diff(d) >= 0) and d[0] < 1e-9
        np.testing.assert_allclose(ARM.ik(T, near=q).nearest(q), S[0])
        G = geometric(T, near=q)
        assert np.all(np.diff(dist(G, q)) >= 0)


def test_nearest_hand_worked_and_distance_wraps():
    S = np.array([[0.0, 0, 1, 0, 0, 0], [np.pi, 0, 1, 0, 0, 0], [6.2, 0, 1, 0, 0, 0]])
    sol = IKSolutions(S, revolute=REVOLUTE)
    np.testing.assert_allclose(sol.nearest([0.05, 0, 1, 0, 0, 0]), S[0])
    np.testing.assert_allclose(sol.nearest([6.22, 0, 1, 0, 0, 0]), S[2])  # 0.02 from 6.2, 0.0632 from 0
    d = dist([0.1, 0, 1, 0, 0, 0], [TWO_PI - 0.1, 0, 1.5, 0, 0, 0])
    np.testing.assert_allclose(d, np.hypot(0.2, 0.5))
    with pytest.raises(ValueError, match="unreachable"):
        IKSolutions(np.zeros((0, 6)), success=False, reason="unreachable pose", revolute=REVOLUTE).nearest(np.zeros(6))


def test_angle_function_signed():
    assert angle([1, 0, 0], [0, 1, 0], [0, 0, 1]) == pytest.approx(np.pi / 2)
    assert angle([1, 0, 0], [0, 1, 0], [0, 0, -1]) == pytest.approx(-np.pi / 2)
    assert angle([1, 0, 0], [-1, 1e-300, 0], [0, 0, 1]) == pytest.approx(np.pi)
    assert angle([2, 0, 0], [1, 0, 1], [0, -1, 0]) == pytest.approx(np.pi / 4)
    # the angle to or from a zero vector is undefined (it used to come back as 0 without a word)
    for args, name in [
        (([0, 0, 0], [1, 0, 0], [0, 0, 1]), "v"),
        (([1, 0, 0], [0, 0, 0], [0, 0, 1]), "w"),
        (([1, 0, 0], [0, 1, 0], [0, 0, 0]), "n"),
    ]:
        with pytest.raises(ValueError, match=f"^{name}: expected a non-zero 3-vector"):
            angle(*args)
    with pytest.raises(ValueError, match="^v: expected shape \\(3,\\)"):
        angle([1, 0], [0, 1, 0], [0, 0, 1])


# ----------------------------------------------------------------------------- singular cases

# configurations placing the pose exactly at each singular case (l1, l3, l4 = 1, 0.5, 0.3)
SINGULAR = {
    # p4 on the z0 axis: radial coordinate q2 c2 - l3 s23 = 0 with α23 = π/2
    "axis": ([0.7, -0.5, L3 / np.cos(0.5), np.pi / 2 + 0.5, 0.4, 0.5], {AXIS}),
    # c4 = 0 (α4 = ±π/2): x5 normal to the arm plane
    "parallel+": ([0.7, 0.3, 1.2, 0.4, np.pi / 2, 0.5], {PARALLEL}),
    "parallel-": ([4.0, 5.3, 0.8, 2.4, 3 * np.pi / 2, 1.5], {PARALLEL}),
    # q2 = 0: p3 = p2
    "q2zero": ([0.7, 0.3, 0.0, 0.4, 0.9, 0.5], {Q2_ZERO}),
    # p4 = p2 (on the axis) with c4 = 0: α1 free, and for that α1 the planes are parallel
    "p4=p2": ([0.7, 0.3, L3, np.pi / 2, np.pi / 2, 0.5], {AXIS}),
    # the zero configuration: p3 = p2 and p4 on the axis
    "zero": ([0.0, 0.0, 0.0, 0.0, 0.0, 0.0], {AXIS, Q2_ZERO}),
    # all three at once: q2 = 0, p4 = p2 + l3 (-z3) on the axis needs z3 = ±z0
    "all": ([1.1, 0.4, 0.0, -0.4, np.pi / 2, 0.2], {AXIS, Q2_ZERO}),
}


@pytest.mark.parametrize("name", list(SINGULAR))
@pytest.mark.parametrize("method", ["explicit", "geometric"])
def test_singular_cases_exact(name, method):
    q, cases = SINGULAR[name]
    T = ARM.fk(q)
    assert set(ARM.classify(T)) == cases
    fn = explicit if method == "explicit" else geometric
    with pytest.warns(SingularityWarning, match=sorted(cases)[0]):
        S = fn(T)
    assert len(S) >= 1 and in_space(S)
    assert np.abs(ARM.fk(S) - T).max() < 1e-12
    # with near= the representative nearest to the original is the original itself
    with pytest.warns(SingularityWarning):
        Sn = fn(T, near=np.array(q))
    assert np.abs(ARM.fk(Sn) - T).max() < 1e-12
    p4 = T[:3, 3] - L4 * T[:3, 0]
    same_plane = AXIS in cases or np.cos(q[0] - np.arctan2(p4[1], p4[0])) > 0
    if method == "explicit" or same_plane:  # Ver.2 keeps only the arm plane α1 = atan2(p4_2, p4_1)
        assert dist(Sn[0], q) < 1e-9
    res = quiet(ARM.ik, T, method=method)
    assert res.success and set(res.singular) <= cases | {PARALLEL} and all(res.messages[k] for k in res.singular)
    if method == "geometric":  # Ver.2's representatives are among Ver.1's (same rules)
        S1 = quiet(explicit, T)
        for g in S:
            assert dist(S1, g).min() < 1e-9


def test_batch_and_scalar_paths_agree():
    # two code paths (numpy batch, plain floats) for the same formulas, including singular poses
    rng = np.random.default_rng(10)
    Q = np.vstack([random_q(rng, 100), np.array([v[0] for v in SINGULAR.values()])])
    T = ARM.fk(Q)
    b = ARM.ik_batch(T)
    B, flags = b.q, b.flags
    assert flags[:100].sum() == 0 and np.all(flags[100:].any(axis=1))
    for Tk, Bk, Vk in zip(T, B, b.valid, strict=True):
        S = quiet(explicit, Tk)
        assert all(dist(Bk[Vk], s).min() < 1e-12 for s in S)


def test_singular_rules_without_near():
    # parallel planes: Porter's rule, minimal q2 = | |p4 - p2| - l3 |, one representative per arm plane
    q = SINGULAR["parallel+"][0]
    T = ARM.fk(q)
    p4 = T[:3, 3] - L4 * T[:3, 0]
    qmin = abs(np.linalg.norm(p4 - [0, 0, L1]) - L3)
    S = quiet(explicit, T)
    assert S.shape == (2, 6)
    np.testing.assert_allclose(S[:, 2], qmin, atol=1e-12)
    G = quiet(geometric, T)
    assert G.shape == (1, 6) and dist(S, G[0]).min() < 1e-9
    # the solutions form a continuum in q2: asked for the one near q (q2 = 1.2, well above the minimum),
    # the solver returns another member of the family, with its own q2, that reaches T as well
    assert q[2] > qmin + 0.1
    Sn = quiet(explicit, T, near=q)
    assert Sn[0][2] == pytest.approx(q[2], abs=1e-9) and np.abs(ARM.fk(Sn[0]) - T).max() < 1e-12
    assert np.abs(Sn[0][2] - S[:, 2]).min() > 0.1  # a different member than the representatives
    # α1 free: the simplest representative has s4 = 0 (x5 in the arm plane), so α4 ∈ {0, π}
    S = quiet(explicit, ARM.fk(SINGULAR["axis"][0]))
    assert np.allclose(np.sin(S[:, 4]), 0.0, atol=1e-12)
    # q2 = 0: α2 = 0 is the representative
    S = quiet(explicit, ARM.fk(SINGULAR["q2zero"][0]))
    assert np.allclose(S[S[:, 2] < 1e-12][:, 1], 0.0)


@pytest.mark.parametrize("name", ["axis", "parallel+", "parallel-", "q2zero", "p4=p2", "zero", "all"])
def test_near_singular_poses(name):
    q0 = np.array(SINGULAR[name][0])
    rng = np.random.default_rng(7)
    for eps in (1e-13, 1e-11, 1e-9, 1e-7, 1e-5, 1e-3):
        for _ in range(10):
            q = q0 + eps * rng.standard_normal(6)
            q[2] = abs(q[2])
            T = ARM.fk(q)
            S = quiet(explicit, T, near=q)
            G = quiet(geometric, T, near=q)
            assert in_space(S) and in_space(G)
            assert np.abs(ARM.fk(S) - T).max() < 1e-9
            assert np.abs(ARM.fk(G) - T).max() < 1e-9
            # ill-conditioned near a singularity: the original is recovered to ~1e-15 / eps,
            # except next to the double singularities (p4 = p2 with c4 = 0; p4 on the axis with
            # q2 = 0 and c4 = 0) where a tiny change of pose moves the solutions by O(1)
            if name not in ("p4=p2", "all") and eps >= 1e-7:
                assert dist(S[0], q) < 1e-6


angles = st.one_of(
    st.floats(0, TWO_PI, allow_nan=False),
    st.sampled_from([0.0, np.pi / 2, np.pi, 3 * np.pi / 2, -np.pi / 2, 1e-9, np.pi / 2 + 1e-9]),
)
q2s = st.one_of(st.floats(0, 3, allow_nan=False), st.sampled_from([0.0, 1e-12, 1e-7, L3, L3 / np.cos(0.5)]))


@settings(derandomize=True, max_examples=300, deadline=None)
@given(a1=angles, a2=angles, q2=q2s, a3=angles, a4=angles, a5=angles)
def test_hypothesis_round_trip_including_singular(a1, a2, q2, a3, a4, a5):
    q = np.array([a1, a2, q2, a3, a4, a5])
    T = ARM.fk(q)
    for fn in (explicit, geometric):
        S = quiet(fn, T)
        assert 1 <= len(S) <= 4 and in_space(S)
        assert np.abs(ARM.fk(S) - T).max() < 1e-9
    S = quiet(explicit, T, near=q)
    assert np.abs(ARM.fk(S) - T).max() < 1e-9
    if not ARM.classify(T, tol=1e-6):
        assert dist(S[0], q) < 1e-7


def test_scaled_lengths():
    rng = np.random.default_rng(8)
    for lens in [(1000.0, 250.0, 80.0), (1e-3, 2e-3, 5e-4)]:
        for q in random_q(rng, 20):
            q[2] *= lens[0]
            T = Porter(*lens).fk(q)
            S = np.asarray(Porter(*lens).ik(T, near=q))
            assert np.abs(Porter(*lens).fk(S) - T).max() < 1e-12 * max(1.0, lens[0] * 4)
            assert dist(S[0], q) < 1e-9 * max(1.0, lens[0])


# ----------------------------------------------------------------------------- unreachable, bad input


def test_unreachable_with_stroke_limit():
    q = [0.3, 0.2, 5.0, 0.4, 0.5, 0.6]
    T = ARM.fk(q)
    short = Porter(*LEN, q2_max=2.0)
    res = short.ik(T)
    assert not res.success and "unreachable" in res.reason and "q2_max" in res.reason
    assert np.asarray(res).shape == (0, 6)
    assert not short.ik(T, method="geometric").success and np.asarray(short.ik(T, method="geometric")).shape == (0, 6)
    b = short.ik_batch(T)
    assert not b.reachable[0] and "q2_max" in b.reason[0] and not b.valid.any() and np.isfinite(b.q).all()
    # a stroke between the two values of q2 keeps the two solutions within it
    q2s = np.unique(np.round(explicit(T)[:, 2], 9))
    assert len(q2s) == 2
    S = np.asarray(Porter(*LEN, q2_max=q2s.mean()).ik(T))
    assert len(S) == 2 and np.all(S[:, 2] <= q2s.mean())


def test_every_pose_is_reachable_without_stroke_limit():
    # arbitrary rigid transforms (not generated by fk) all have solutions
    rng = np.random.default_rng(9)
    for _ in range(100):
        axis = rng.standard_normal(3)
        T = tf.homogeneous(tf.rodrigues(axis, rng.uniform(0, np.pi)), rng.uniform(-3, 3, 3))
        S = explicit(T)
        assert len(S) == 4 and np.abs(ARM.fk(S) - T).max() < 1e-12


def test_result_object_behaves_like_array():
    T = ARM.fk([0.3, 0.2, 1.0, 0.4, 0.5, 0.6])
    res = ARM.ik(T)
    assert np.asarray(res).shape == (4, 6) and res.shape == (4, 6) and len(res) == 4
    np.testing.assert_allclose(res[0], res.q[0])
    assert res.singular == () and res.success and res.method == "explicit"


@pytest.mark.parametrize(
    "T, match",
    [
        (np.eye(3), "4x4"),
        (np.full((4, 4), np.nan), "finite"),
        (np.diag([1.0, 1.0, 2.0, 1.0]), "rotation"),
        (np.array([[1.0, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 1, 1]]), "last row"),
        (np.diag([1.0, 1.0, -1.0, 1.0]), "reflection"),
        ("eye", "real numbers"),
    ],
)
def test_bad_pose_raises(T, match):
    for fn in (ARM.ik, lambda T: ARM.ik(T, method="geometric"), ARM.classify, ARM.ik_batch):
        with pytest.raises(ValueError, match=match):
            fn(T)


def test_bad_lengths_and_arguments_raise():
    T = np.eye(4)
    for bad in [(0.0, 1, 1), (1, -1, 1), (1, 1, np.nan)]:
        with pytest.raises(ValueError, match="l1|l3|l4"):
            Porter(*bad)
    with pytest.raises(ValueError, match="q"):
        ARM.fk(np.zeros(5))
    with pytest.raises(ValueError, match="near"):
        ARM.ik(T, near=np.zeros(3))
    with pytest.raises(ValueError, match="method"):
        ARM.ik(T, method="numeric")
    with pytest.raises(ValueError, match="method"):
        ARM.ik(T, method=np.array(["explicit", "geometric"]))  # was numpy's truth-value error
    with pytest.raises(ValueError, match="q2_max"):
        Porter(*LEN, q2_max=-1.0)
    for tol in (float("inf"), float("nan"), -1e-9, "1e-9", 0.5):  # inf gave 4 wrong "solutions"; NaN disabled checks
        with pytest.raises(ValueError, match="tol"):
            ARM.ik(T, tol=tol)
        with pytest.raises(ValueError, match="tol"):
            ARM.classify(T, tol=tol)


# ----------------------------------------------------------------------------- boundaries decided together


def test_both_arm_planes_are_classified_together_next_to_c4_zero():
    """Next to the planes-parallel family (c4 = 0) the front and back planes see the same |c4|, so both
    fall on the same side of the tolerance: never three solutions (two planes times a c4 sign that
    one plane counts as zero and the other does not). Before, at 1e-12 from the family, 34 of 200
    poses came back with three solutions."""
    rng = np.random.default_rng(31)
    counts = set()
    for _ in range(200):
        q = random_q(rng, 1)[0]
        q[4] = rng.choice([np.pi / 2, -np.pi / 2]) + 1e-12 * rng.standard_normal()
        T = ARM.fk(q)
        b = ARM.ik_batch(T)
        parallel = (b.flags[0] & 2) > 0
        front, back = parallel[:2][b.valid[0, :2]], parallel[2:][b.valid[0, 2:]]
        assert front.all() == back.all()  # the same decision in both planes
        S = quiet(explicit, T)
        counts.add(len(S))
        assert np.abs(ARM.fk(S) - T).max() < 1e-9
    assert counts <= {2, 4} and 3 not in counts


def test_q2_zero_is_snapped_and_the_pairs_of_planes_agree():
    q = np.array(SINGULAR["q2zero"][0])
    b = ARM.ik_batch(ARM.fk(q))
    q2 = b.q[0, :, 2]
    assert (q2 == 0.0).sum() == 2  # exactly 0 by design: p3 = p2 is reached from both planes
    assert ((b.flags[0] & 4) > 0).sum() == 2


@pytest.mark.parametrize("q2", [1e3, 1e8, 1e12, 1e13, 1e40, 1e100, 1e149])
def test_far_poses_keep_their_relative_accuracy(q2):
    """Tolerances scale with a finite length and no square overflows: far poses are solved to the last
    digits by both methods (before: |p| >= 1e154 gave 4 wrong solutions, and Ver.2 called a pose with
    q2 >= 1e12 l1 unreachable, its on-axis test scaling as L² instead of L)."""
    q = np.array([0.3, 0.2, q2, 0.4, 0.5, 0.6])
    T = ARM.fk(q)
    for method, count in (("explicit", 4), ("geometric", 2)):
        sol = ARM.ik(T, method=method)
        assert sol.success and len(sol) == count and not sol.singular
        err = np.abs(ARM.fk(np.asarray(sol)) - T)
        assert err[:, :3, 3].max() / q2 < 1e-14 and err[:, :3, :3].max() < 1e-14
    with pytest.raises(ValueError, match="at most 1e\\+150"):
        ARM.ik(tf.homogeneous(np.eye(3), [1e154, 0.0, 0.0]))  # its square would overflow: refused


# ---- issue 25 (1g): Ver.2 extended to the back plane, against Ver.1 ------------------------------------------------


def test_ver2_on_both_planes_gives_ver1s_four_configurations():
    from puma_course.kinematics.ik import joint_distance as jd

    arm = Porter(1.0, 0.5, 0.3)
    rng = np.random.default_rng(257)
    for _ in range(30):
        q = rng.uniform(-2.5, 2.5, 6)
        q[2] = rng.uniform(0.2, 2.0)
        T = arm.fk(q)
        v1, v2 = arm.ik(T), arm.ik(T, method="geometric", planes="both")
        assert len(v2) == len(v1) == 4 and sorted(v2.labels) == sorted(v1.labels)
        for label, row in zip(v2.labels, v2, strict=True):
            d = [float(jd(row, r)) for r in v1]
            assert min(d) < 1e-9 and v1.labels[int(np.argmin(d))] == label  # the same row under the same name
            assert np.allclose(arm.fk(row), T, atol=1e-10)
        front = arm.ik(T, method="geometric")
        assert np.allclose(front.q, v2.q[:2])  # the front plane is unchanged


def test_ver2_back_plane_at_singular_poses_reaches_the_pose_or_adds_nothing():
    import warnings

    from puma_course.kinematics import SingularityWarning

    arm = Porter(1.0, 0.5, 0.3)
    T_par = arm.fk([0.3, 0.2, 1.0, 0.4, np.pi / 2, 0.6])  # c4 = 0: planes parallel
    T_ax = arm.fk([0.0, 0.0, 0.3, 0.0, 0.0, 0.0])
    T_ax[:3, 3] = [0.3, 0.0, 0.0]  # with x5 = x0, p4 = p5 - l4 x5 lies on the z0 axis
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SingularityWarning)
        for T in (T_par, T_ax):
            both = arm.ik(T, method="geometric", planes="both")
            front = arm.ik(T, method="geometric")
            assert both.success and all(np.allclose(arm.fk(r), T, atol=1e-9) for r in both)
            assert len(both) >= len(front)
        assert len(arm.ik(T_ax, method="geometric", planes="both")) == len(arm.ik(T_ax, method="geometric"))


def test_planes_is_checked():
    arm = Porter(1.0, 0.5, 0.3)
    T = arm.fk([0.3, 0.2, 1.0, 0.4, 0.5, 0.6])
    with pytest.raises(ValueError, match="planes"):
        arm.ik(T, planes="both")  # Ver.1 has both already
    with pytest.raises(ValueError, match="planes"):
        arm.ik(T, method="geometric", planes="back")
