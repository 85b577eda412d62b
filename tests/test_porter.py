"""Tests of puma_course.porter: Porter's PUMA-like chain, direct problem and both inverse methods.

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

from puma_course import porter as P
from puma_course import transforms as tf

L1, L3, L4 = 1.0, 0.5, 0.3
LEN = (L1, L3, L4)
TWO_PI = 2 * np.pi


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
    S = np.asarray(S)
    ang = S[:, [0, 1, 3, 4, 5]]
    return bool(np.all((ang >= 0) & (ang < TWO_PI)) and np.all(S[:, 2] >= 0) and np.all(np.isfinite(S)))


def quiet(fn, *a, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", P.PorterSingularityWarning)
        return fn(*a, **kw)


# ----------------------------------------------------------------------------- direct problem


def test_fk_hand_worked():
    # q = 0: p2 = (0,0,l1), p3 = p2, p4 = p3 - l3 z = (0,0,l1-l3), p5 = p4 + l4 x
    T = P.fk(np.zeros(6), *LEN)
    np.testing.assert_allclose(T, tf.transl([L4, 0, L1 - L3]), atol=1e-15)
    # α1 = π/2, q2 = 2: the arm plane is the y-z plane, p5 = (0, 2 + l4, l1 - l3), x5 = e2
    T = P.fk([np.pi / 2, 0, 2.0, 0, 0, 0], *LEN)
    np.testing.assert_allclose(T[:3, 3], [0, 2 + L4, L1 - L3], atol=1e-15)
    np.testing.assert_allclose(T[:3, 0], [0, 1, 0], atol=1e-15)
    # α2 = -π/2 points the prismatic axis up: p3 = (0, 0, l1 + q2); α3 = π/2 then brings z3 along -x... :
    # z3 = Ry(α2 + α3) e3 = e3, p4 = p3 - l3 e3, x4 = Ry(0) e1 = e1
    T = P.fk([0, -np.pi / 2, 1.5, np.pi / 2, 0, 0], *LEN)
    np.testing.assert_allclose(T[:3, 3], [L4, 0, L1 + 1.5 - L3], atol=1e-15)


def test_fk_matches_independent_composition_and_batches():
    rng = np.random.default_rng(1)
    Q = random_q(rng, 50)
    T = P.fk(Q, *LEN)
    assert T.shape == (50, 4, 4)
    for q, Tq in zip(Q, T, strict=True):
        np.testing.assert_allclose(Tq, fk_by_transforms(q), atol=1e-13)
    np.testing.assert_allclose(P.fk(Q[7], *LEN), T[7], atol=0)


def test_frames_geometry():
    rng = np.random.default_rng(2)
    Q = random_q(rng, 200)
    F = P.frames(Q, *LEN)
    assert F.shape == (200, 6, 4, 4)
    R = F[..., :3, :3]
    np.testing.assert_allclose(np.swapaxes(R, -1, -2) @ R, np.broadcast_to(np.eye(3), R.shape), atol=1e-13)
    np.testing.assert_allclose(np.linalg.det(R), 1.0, atol=1e-13)
    p = P.points(Q, *LEN)
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
    np.testing.assert_allclose(F[:, 5], P.fk(Q, *LEN), atol=0)


# ----------------------------------------------------------------------------- inverse, general position


def test_ver1_round_trip_many_poses_batched():
    rng = np.random.default_rng(3)
    N = 5000
    Q = random_q(rng, N)
    T = P.fk(Q, *LEN)
    S, flags = P.ik_explicit_batch(T, *LEN)
    assert S.shape == (N, 4, 6) and not flags.any()
    back = P.fk(S.reshape(-1, 6), *LEN).reshape(N, 4, 4, 4)
    assert np.abs(back - T[:, None]).max() < 1e-12
    assert P.config_distance(S, Q[:, None, :]).min(axis=1).max() < 1e-9  # the original is among them
    assert in_space(S.reshape(-1, 6))


def test_ver1_scalar_round_trip_count_and_original():
    rng = np.random.default_rng(4)
    Q = random_q(rng, 400)
    for q in Q:
        T = P.fk(q, *LEN)
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # general position: no warning at all
            S = P.ik_explicit(T, *LEN)
        # Four solutions, by an argument independent of eqs. 8-16: p4 = p5 - l4 x5 is fixed; the
        # vertical plane through z0 and p4 can be entered with α1 or α1 + π; z3 must lie in that
        # plane and be perpendicular to x5 (x5 = x4 ⊥ z4 = z3): two unit vectors ±z3; then
        # p3 = p4 + l3 z3 and q2 x2 = p3 - p2 with q2 >= 0 fix q2 and α2 uniquely, and α4, α5
        # follow from the rotation. 2 x 2 = 4 (Porter's 8 counts q2 < 0 as well).
        assert S.shape == (4, 6)
        assert in_space(S)
        assert np.abs(P.fk(S, *LEN) - T).max() < 1e-12
        assert P.config_distance(S, q).min() < 1e-9
        # the four are distinct and form two point sequences p0..p5 differing in p3 only
        D = P.config_distance(S[:, None], S[None])
        assert D[~np.eye(4, dtype=bool)].min() > 1e-6
        pts = P.points(S, *LEN)
        p3 = np.unique(np.round(pts[:, 3], 9), axis=0)
        assert len(p3) == 2
        same = pts[:, [0, 1, 2, 4, 5]]
        np.testing.assert_allclose(same, np.broadcast_to(same[0], same.shape), atol=1e-12)


def test_ver2_round_trip_and_subset_of_ver1():
    rng = np.random.default_rng(5)
    for q in random_q(rng, 300):
        T = P.fk(q, *LEN)
        G = P.ik_geometric(T, *LEN)
        S = P.ik_explicit(T, *LEN)
        assert G.shape == (2, 6) and in_space(G)
        assert np.abs(P.fk(G, *LEN) - T).max() < 1e-12
        for g in G:
            assert P.config_distance(S, g).min() < 1e-9
        # Ver.2 keeps the arm plane with p4 on the positive side: α1 = atan2(p4_2, p4_1)
        p4 = T[:3, 3] - L4 * T[:3, 0]
        assert np.allclose(np.cos(G[:, 0] - np.arctan2(p4[1], p4[0])), 1.0)


def test_near_sorts_and_nearest():
    rng = np.random.default_rng(6)
    for q in random_q(rng, 50):
        T = P.fk(q, *LEN)
        S = P.ik_explicit(T, *LEN, near=q)
        d = P.config_distance(S, q)
        assert np.all(np.diff(d) >= 0) and d[0] < 1e-9
        np.testing.assert_allclose(P.nearest(S, q), S[0])
        G = P.ik_geometric(T, *LEN, near=q)
        assert np.all(np.diff(P.config_distance(G, q)) >= 0)


def test_nearest_hand_worked_and_distance_wraps():
    S = np.array([[0.0, 0, 1, 0, 0, 0], [np.pi, 0, 1, 0, 0, 0], [6.2, 0, 1, 0, 0, 0]])
    np.testing.assert_allclose(P.nearest(S, [0.05, 0, 1, 0, 0, 0]), S[0])
    np.testing.assert_allclose(P.nearest(S, [6.22, 0, 1, 0, 0, 0]), S[2])  # 0.02 from 6.2, 0.0632 from 0
    d = P.config_distance([0.1, 0, 1, 0, 0, 0], [TWO_PI - 0.1, 0, 1.5, 0, 0, 0])
    np.testing.assert_allclose(d, np.hypot(0.2, 0.5))
    with pytest.raises(ValueError, match="unreachable"):
        P.nearest(np.zeros((0, 6)), np.zeros(6))


def test_angle_function_signed():
    assert P.angle([1, 0, 0], [0, 1, 0], [0, 0, 1]) == pytest.approx(np.pi / 2)
    assert P.angle([1, 0, 0], [0, 1, 0], [0, 0, -1]) == pytest.approx(-np.pi / 2)
    assert P.angle([1, 0, 0], [-1, 1e-300, 0], [0, 0, 1]) == pytest.approx(np.pi)
    assert P.angle([2, 0, 0], [1, 0, 1], [0, -1, 0]) == pytest.approx(np.pi / 4)
    # the angle to or from a zero vector is undefined (it used to come back as 0 without a word)
    for args, name in [
        (([0, 0, 0], [1, 0, 0], [0, 0, 1]), "v"),
        (([1, 0, 0], [0, 0, 0], [0, 0, 1]), "w"),
        (([1, 0, 0], [0, 1, 0], [0, 0, 0]), "n"),
    ]:
        with pytest.raises(ValueError, match=f"^{name}: expected a non-zero 3-vector"):
            P.angle(*args)
    with pytest.raises(ValueError, match="^v: expected shape \\(3,\\)"):
        P.angle([1, 0], [0, 1, 0], [0, 0, 1])


# ----------------------------------------------------------------------------- singular cases

# configurations placing the pose exactly at each singular case (l1, l3, l4 = 1, 0.5, 0.3)
SINGULAR = {
    # p4 on the z0 axis: radial coordinate q2 c2 - l3 s23 = 0 with α23 = π/2
    "axis": ([0.7, -0.5, L3 / np.cos(0.5), np.pi / 2 + 0.5, 0.4, 0.5], {P.AXIS}),
    # c4 = 0 (α4 = ±π/2): x5 normal to the arm plane
    "parallel+": ([0.7, 0.3, 1.2, 0.4, np.pi / 2, 0.5], {P.PARALLEL}),
    "parallel-": ([4.0, 5.3, 0.8, 2.4, 3 * np.pi / 2, 1.5], {P.PARALLEL}),
    # q2 = 0: p3 = p2
    "q2zero": ([0.7, 0.3, 0.0, 0.4, 0.9, 0.5], {P.Q2_ZERO}),
    # p4 = p2 (on the axis) with c4 = 0: α1 free, and for that α1 the planes are parallel
    "p4=p2": ([0.7, 0.3, L3, np.pi / 2, np.pi / 2, 0.5], {P.AXIS}),
    # the zero configuration: p3 = p2 and p4 on the axis
    "zero": ([0.0, 0.0, 0.0, 0.0, 0.0, 0.0], {P.AXIS, P.Q2_ZERO}),
    # all three at once: q2 = 0, p4 = p2 + l3 (-z3) on the axis needs z3 = ±z0
    "all": ([1.1, 0.4, 0.0, -0.4, np.pi / 2, 0.2], {P.AXIS, P.Q2_ZERO}),
}


@pytest.mark.parametrize("name", list(SINGULAR))
@pytest.mark.parametrize("method", ["explicit", "geometric"])
def test_singular_cases_exact(name, method):
    q, cases = SINGULAR[name]
    T = P.fk(q, *LEN)
    assert set(P.classify(T, *LEN)) == cases
    fn = P.ik_explicit if method == "explicit" else P.ik_geometric
    with pytest.warns(P.PorterSingularityWarning, match=sorted(cases)[0]):
        S = fn(T, *LEN)
    assert len(S) >= 1 and in_space(S)
    assert np.abs(P.fk(S, *LEN) - T).max() < 1e-12
    # with near= the representative nearest to the original is the original itself
    with pytest.warns(P.PorterSingularityWarning):
        Sn = fn(T, *LEN, near=q)
    assert np.abs(P.fk(Sn, *LEN) - T).max() < 1e-12
    p4 = T[:3, 3] - L4 * T[:3, 0]
    same_plane = P.AXIS in cases or np.cos(q[0] - np.arctan2(p4[1], p4[0])) > 0
    if method == "explicit" or same_plane:  # Ver.2 keeps only the arm plane α1 = atan2(p4_2, p4_1)
        assert P.config_distance(Sn[0], q) < 1e-9
    res = P.solve(T, *LEN, method=method)
    assert res.success and set(res.singular) <= cases | {P.PARALLEL} and res.reason
    if method == "geometric":  # Ver.2's representatives are among Ver.1's (same rules)
        S1 = quiet(P.ik_explicit, T, *LEN)
        for g in S:
            assert P.config_distance(S1, g).min() < 1e-9


def test_batch_and_scalar_paths_agree():
    # two code paths (numpy batch, plain floats) for the same formulas, including singular poses
    rng = np.random.default_rng(10)
    Q = np.vstack([random_q(rng, 100), np.array([v[0] for v in SINGULAR.values()])])
    T = P.fk(Q, *LEN)
    B, flags = P.ik_explicit_batch(T, *LEN)
    assert flags[:100].sum() == 0 and np.all(flags[100:].any(axis=1))
    for Tk, Bk in zip(T, B, strict=True):
        S = quiet(P.ik_explicit, Tk, *LEN)
        assert all(P.config_distance(Bk, s).min() < 1e-12 for s in S)


def test_singular_rules_without_near():
    # parallel planes: Porter's rule, minimal q2 = | |p4 - p2| - l3 |, one representative per arm plane
    q = SINGULAR["parallel+"][0]
    T = P.fk(q, *LEN)
    p4 = T[:3, 3] - L4 * T[:3, 0]
    qmin = abs(np.linalg.norm(p4 - [0, 0, L1]) - L3)
    S = quiet(P.ik_explicit, T, *LEN)
    assert S.shape == (2, 6)
    np.testing.assert_allclose(S[:, 2], qmin, atol=1e-12)
    G = quiet(P.ik_geometric, T, *LEN)
    assert G.shape == (1, 6) and P.config_distance(S, G[0]).min() < 1e-9
    # the solutions form a continuum in q2: asked for the one near q (q2 = 1.2, well above the minimum),
    # the solver returns another member of the family, with its own q2, that reaches T as well
    assert q[2] > qmin + 0.1
    Sn = quiet(P.ik_explicit, T, *LEN, near=q)
    assert Sn[0][2] == pytest.approx(q[2], abs=1e-9) and np.abs(P.fk(Sn[0], *LEN) - T).max() < 1e-12
    assert np.abs(Sn[0][2] - S[:, 2]).min() > 0.1  # a different member than the representatives
    # α1 free: the simplest representative has s4 = 0 (x5 in the arm plane), so α4 ∈ {0, π}
    S = quiet(P.ik_explicit, P.fk(SINGULAR["axis"][0], *LEN), *LEN)
    assert np.allclose(np.sin(S[:, 4]), 0.0, atol=1e-12)
    # q2 = 0: α2 = 0 is the representative
    S = quiet(P.ik_explicit, P.fk(SINGULAR["q2zero"][0], *LEN), *LEN)
    assert np.allclose(S[S[:, 2] < 1e-12][:, 1], 0.0)


@pytest.mark.parametrize("name", ["axis", "parallel+", "parallel-", "q2zero", "p4=p2", "zero", "all"])
def test_near_singular_poses(name):
    q0 = np.array(SINGULAR[name][0])
    rng = np.random.default_rng(7)
    for eps in (1e-13, 1e-11, 1e-9, 1e-7, 1e-5, 1e-3):
        for _ in range(10):
            q = q0 + eps * rng.standard_normal(6)
            q[2] = abs(q[2])
            T = P.fk(q, *LEN)
            S = quiet(P.ik_explicit, T, *LEN, near=q)
            G = quiet(P.ik_geometric, T, *LEN, near=q)
            assert in_space(S) and in_space(G)
            assert np.abs(P.fk(S, *LEN) - T).max() < 1e-9
            assert np.abs(P.fk(G, *LEN) - T).max() < 1e-9
            # ill-conditioned near a singularity: the original is recovered to ~1e-15 / eps,
            # except next to the double singularities (p4 = p2 with c4 = 0; p4 on the axis with
            # q2 = 0 and c4 = 0) where a tiny change of pose moves the solutions by O(1)
            if name not in ("p4=p2", "all") and eps >= 1e-7:
                assert P.config_distance(S[0], q) < 1e-6


angles = st.one_of(
    st.floats(0, TWO_PI, allow_nan=False),
    st.sampled_from([0.0, np.pi / 2, np.pi, 3 * np.pi / 2, -np.pi / 2, 1e-9, np.pi / 2 + 1e-9]),
)
q2s = st.one_of(st.floats(0, 3, allow_nan=False), st.sampled_from([0.0, 1e-12, 1e-7, L3, L3 / np.cos(0.5)]))


@settings(derandomize=True, max_examples=300, deadline=None)
@given(a1=angles, a2=angles, q2=q2s, a3=angles, a4=angles, a5=angles)
def test_hypothesis_round_trip_including_singular(a1, a2, q2, a3, a4, a5):
    q = np.array([a1, a2, q2, a3, a4, a5])
    T = P.fk(q, *LEN)
    for fn in (P.ik_explicit, P.ik_geometric):
        S = quiet(fn, T, *LEN)
        assert 1 <= len(S) <= 4 and in_space(S)
        assert np.abs(P.fk(S, *LEN) - T).max() < 1e-9
    S = quiet(P.ik_explicit, T, *LEN, near=q)
    assert np.abs(P.fk(S, *LEN) - T).max() < 1e-9
    if not P.classify(T, *LEN, tol=1e-6):
        assert P.config_distance(S[0], q) < 1e-7


def test_scaled_lengths():
    rng = np.random.default_rng(8)
    for lens in [(1000.0, 250.0, 80.0), (1e-3, 2e-3, 5e-4)]:
        for q in random_q(rng, 20):
            q[2] *= lens[0]
            T = P.fk(q, *lens)
            S = P.ik_explicit(T, *lens, near=q)
            assert np.abs(P.fk(S, *lens) - T).max() < 1e-12 * max(1.0, lens[0] * 4)
            assert P.config_distance(S[0], q) < 1e-9 * max(1.0, lens[0])


# ----------------------------------------------------------------------------- unreachable, bad input


def test_unreachable_with_stroke_limit():
    q = [0.3, 0.2, 5.0, 0.4, 0.5, 0.6]
    T = P.fk(q, *LEN)
    with pytest.warns(P.PorterUnreachableWarning, match="unreachable"):
        S = P.ik_explicit(T, *LEN, q2_max=2.0)
    assert S.shape == (0, 6)
    res = P.solve(T, *LEN, q2_max=2.0)
    assert not res.success and "q2_max" in res.reason and np.asarray(res).shape == (0, 6)
    with pytest.warns(P.PorterUnreachableWarning):
        assert P.ik_geometric(T, *LEN, q2_max=2.0).shape == (0, 6)
    # a stroke between the two values of q2 keeps the two solutions within it
    q2s = np.unique(np.round(P.ik_explicit(T, *LEN)[:, 2], 9))
    assert len(q2s) == 2
    S = P.ik_explicit(T, *LEN, q2_max=q2s.mean())
    assert len(S) == 2 and np.all(S[:, 2] <= q2s.mean())


def test_every_pose_is_reachable_without_stroke_limit():
    # arbitrary rigid transforms (not generated by fk) all have solutions
    rng = np.random.default_rng(9)
    for _ in range(100):
        axis = rng.standard_normal(3)
        T = tf.homogeneous(tf.rodrigues(axis, rng.uniform(0, np.pi)), rng.uniform(-3, 3, 3))
        S = P.ik_explicit(T, *LEN)
        assert len(S) == 4 and np.abs(P.fk(S, *LEN) - T).max() < 1e-12


def test_result_object_behaves_like_array():
    T = P.fk([0.3, 0.2, 1.0, 0.4, 0.5, 0.6], *LEN)
    res = P.solve(T, *LEN)
    assert np.asarray(res).shape == (4, 6) and res.shape == (4, 6) and len(res) == 4
    np.testing.assert_allclose(res[0], res.solutions[0])
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
    for fn in (P.ik_explicit, P.ik_geometric, P.classify):
        with pytest.raises(ValueError, match=match):
            fn(T, *LEN)


def test_bad_lengths_and_arguments_raise():
    T = np.eye(4)
    for bad in [(0.0, 1, 1), (1, -1, 1), (1, 1, np.nan)]:
        with pytest.raises(ValueError, match="l1|l3|l4"):
            P.ik_explicit(T, *bad)
        with pytest.raises(ValueError, match="l1|l3|l4"):
            P.fk(np.zeros(6), *bad)
    with pytest.raises(ValueError, match="q"):
        P.fk(np.zeros(5), *LEN)
    with pytest.raises(ValueError, match="near"):
        P.ik_explicit(T, *LEN, near=np.zeros(3))
    with pytest.raises(ValueError, match="method"):
        P.solve(T, *LEN, method="numeric")
    with pytest.raises(ValueError, match="q2_max"):
        P.ik_explicit(T, *LEN, q2_max=-1.0)
