"""The MK3's nearest attainable pose (Craig's Motoman L-3): against a brute search over the arm's
orientations with the position fixed, and by its properties (reached by ``ik``, the position kept, an
attainable goal unchanged, idempotent), its special cases and its input contract."""

from __future__ import annotations

import math

import numpy as np
import pytest

from puma_course.kinematics import MK3
from puma_course.transforms import axis_angle, homogeneous, rodrigues, rotx

ARM = MK3()


def tilted_goals(rng: np.random.Generator, n: int) -> list[np.ndarray]:
    """Reachable poses with their orientation turned about a random axis by 0.1-1.2 rad (position kept)."""
    out = []
    for q in rng.uniform(-math.pi, math.pi, (n, 5)):
        T = ARM.fk(q)
        axis = rng.normal(size=3)
        T[:3, :3] = rodrigues(axis, rng.uniform(0.1, 1.2)) @ T[:3, :3]
        out.append(T)
    return out


def rotation_angle(A: np.ndarray, B: np.ndarray) -> np.ndarray:
    """The angle of the rotation taking A onto B (both (..., 3, 3)): arccos((tr(Aᵀ B) - 1) / 2)."""
    tr = np.einsum("...ij,...ij->...", A, B)
    return np.arccos(np.clip((tr - 1.0) / 2.0, -1.0, 1.0))


def brute_nearest(T: np.ndarray) -> tuple[float, np.ndarray]:
    """The attainable orientation nearest T's, searched over the joints with the position fixed.

    With the tool point fixed (off the base axis), θ1 is its azimuth or that plus π (the arm plane holds
    it), and the orientation of ``fk`` depends on θ1, θ2 + θ3 + θ4 and θ5 only (the closed forms, checked
    by sympy in test_mk3.py): so a grid over (θ4, θ5) with θ2 = θ3 = 0, refined five times around the best,
    covers every attainable orientation. Returns the smallest angle and its rotation.
    """
    phi = math.atan2(T[1, 3], T[0, 3])
    best, best_R = np.inf, np.eye(3)
    for t1 in (phi, phi + math.pi):
        centre, half, n = np.zeros(2), math.pi, 241
        for _ in range(6):
            g4, g5 = np.meshgrid(centre[0] + np.linspace(-half, half, n), centre[1] + np.linspace(-half, half, n))
            Q = np.zeros((g4.size, 5))
            Q[:, 0], Q[:, 3], Q[:, 4] = t1, g4.ravel(), g5.ravel()
            Rs = ARM.fk(Q)[:, :3, :3]
            ang = rotation_angle(Rs, np.broadcast_to(T[:3, :3], Rs.shape))
            i = int(np.argmin(ang))
            centre, half, n = Q[i, [3, 4]], half * 8.0 / n, 41
            if ang[i] < best:
                best, best_R = float(ang[i]), Rs[i]
    return best, best_R


def test_an_attainable_goal_comes_back_unchanged():
    rng = np.random.default_rng(0)
    for q in rng.uniform(-math.pi, math.pi, (200, 5)):
        T = ARM.fk(q)
        T2, info = ARM.nearest_attainable(T)
        assert np.array_equal(T2, T)
        assert info.angle == 0.0 and info.unique and info.success and info.reason == ""
        assert not np.any(info.axis)


@pytest.mark.parametrize("seed", range(4))
def test_the_nearest_orientation_is_the_brute_search_minimum(seed):
    for T in tilted_goals(np.random.default_rng(seed), 5):
        T2, info = ARM.nearest_attainable(T)
        angle, R = brute_nearest(T)
        assert info.unique
        if info.along > 0.0:  # the projection's wrist point is out of reach: turned further (the next tests)
            assert info.angle > angle + 1e-3 and info.success
            continue
        assert abs(info.angle - angle) < 1e-6, (info.angle, angle)
        assert abs(float(rotation_angle(T[:3, :3], T2[:3, :3])) - angle) < 1e-6
        assert np.abs(T2[:3, :3] - R).max() < 1e-5  # the minimum is unique here


def test_the_result_is_reached_by_ik_keeps_the_position_and_turns_the_least():
    rng = np.random.default_rng(7)
    reached = 0
    for T in tilted_goals(rng, 300):
        T2, info = ARM.nearest_attainable(T)
        assert not ARM.ik(T).success or info.angle < 1e-9
        assert np.array_equal(T2[:3, 3], T[:3, 3]) and np.array_equal(T2[3], [0, 0, 0, 1])
        R = T2[:3, :3]
        assert np.allclose(R.T @ R, np.eye(3), atol=1e-12) and abs(np.linalg.det(R) - 1.0) < 1e-12
        # the approach in the arm plane: the vertical component of p × z5 vanishes (lecture 04 §6)
        assert abs(T2[0, 3] * T2[1, 2] - T2[1, 3] * T2[0, 2]) < 1e-9 * np.abs(T2[:2, 3]).max()
        # the angle by hand: asin |m · z| with m the plane's normal (-py, px, 0) / |(px, py)|
        m = np.array([-T[1, 3], T[0, 3], 0.0]) / math.hypot(T[0, 3], T[1, 3])
        if info.along == 0.0:
            assert abs(info.angle - math.asin(abs(m @ T[:3, 2]))) < 1e-12
        else:  # the projection's wrist point is out of reach: the approach turned further along the plane
            assert info.angle > math.asin(abs(m @ T[:3, 2])) and info.success
        # the goal turned about the reported axis by the reported angle
        assert np.allclose(rodrigues(info.axis, info.angle) @ T[:3, :3], R, atol=1e-12)
        axis, ang = axis_angle(R @ T[:3, :3].T)
        assert abs(ang - info.angle) < 1e-9 and np.allclose(axis, info.axis, atol=1e-8)
        assert abs(info.axis @ T[:3, 2]) < 1e-12  # the axis is perpendicular to the approach
        sol = ARM.ik(T2)
        assert bool(sol.success) == info.success
        if info.success:
            reached += 1
            assert all(np.abs(ARM.fk(q) - T2).max() < 1e-8 for q in sol.q)
        else:
            assert "out of reach" in info.reason
        again, info2 = ARM.nearest_attainable(T2)  # idempotent
        assert np.array_equal(again, T2) and info2.angle == 0.0
    assert reached > 100


def test_an_approach_perpendicular_to_the_plane_is_turned_down():
    # lecture 04 §6's refused pose: the tool at (400, 0, 300) pointing along y0, across the x0 z0 plane
    T = homogeneous(rotx(-np.pi / 2), [400.0, 0.0, 300.0])
    T2, info = ARM.nearest_attainable(T)
    assert np.allclose(T2[:3, :3], np.diag([1.0, -1.0, -1.0]), atol=1e-15)
    assert np.array_equal(T2[:3, 3], [400.0, 0.0, 300.0])
    assert abs(info.angle - math.pi / 2) < 1e-15 and not info.unique and info.success
    # every attainable orientation at this point is at least 90° away (the brute search agrees)
    assert abs(brute_nearest(T)[0] - math.pi / 2) < 1e-6


@pytest.mark.parametrize("tilt", [1e-7, 5e-7, 2e-6, 1e-4])
def test_an_approach_nearly_perpendicular_to_the_plane_gives_a_rotation_turned_the_least(tilt):
    # §6's goal with its approach tipped by `tilt` towards -z0 (in the plane): unique from 1e-6 rad on
    T = homogeneous(rotx(-np.pi / 2 - tilt), [400.0, 0.0, 300.0])
    T2, info = ARM.nearest_attainable(T)
    R = T2[:3, :3]
    assert np.allclose(R.T @ R, np.eye(3), atol=1e-12) and abs(np.linalg.det(R) - 1.0) < 1e-12
    assert abs(T2[1, 2]) < 1e-12 and info.success
    assert info.unique == (tilt > 1e-6)
    assert np.allclose(T2[:3, 2], [0.0, 0.0, -1.0], atol=1e-9)  # the projection and the choice agree here
    assert abs(float(rotation_angle(T[:3, :3], R)) - info.angle) < 1e-9
    assert abs(info.angle - (np.pi / 2 - tilt)) < 1e-9


def test_a_tool_point_on_the_base_axis_keeps_the_goal():
    T = homogeneous(rotx(0.7), [0.0, 0.0, 700.0])
    T2, info = ARM.nearest_attainable(T)
    assert np.array_equal(T2, T) and info.angle == 0.0
    assert info.success == bool(ARM.ik(T).success)


def test_a_position_out_of_reach_keeps_the_nearest_orientation_and_says_why():
    T = homogeneous(rotx(0.5), [2000.0, 300.0, 300.0])
    T2, info = ARM.nearest_attainable(T)
    assert info.angle > 0.1 and not info.success and "out of reach" in info.reason
    assert abs(T2[0, 3] * T2[1, 2] - T2[1, 3] * T2[0, 2]) < 1e-9


@pytest.mark.parametrize(
    "call, fragment",
    [
        (lambda: ARM.nearest_attainable(np.eye(3)), "T: expected"),
        (lambda: ARM.nearest_attainable(np.full((4, 4), np.nan)), "T: expected"),
        (lambda: ARM.nearest_attainable(np.diag([2.0, 1.0, 1.0, 1.0])), "T (rotation part): expected a rotation"),
        (lambda: ARM.nearest_attainable(np.stack([np.eye(4)] * 2)), "T: expected one pose"),
        (lambda: ARM.nearest_attainable(np.eye(4), tol=-1.0), "tol: expected a small positive tolerance"),
        (lambda: ARM.nearest_attainable(np.eye(4), tol=1e-16), "tol: expected a tolerance"),
        (lambda: ARM.nearest_attainable("pose"), "T: expected"),
    ],
)
def test_bad_input(call, fragment):
    with pytest.raises(ValueError) as err:
        call()
    assert fragment in str(err.value)


# ---- the approach searched along the arm plane (issue 31): against a brute search with ik as the judge ----

GRID = np.radians(np.arange(-180.0, 180.0, 0.25))  # approach directions in the arm plane, 0.25° apart


def plane_directions(T: np.ndarray, betas: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Poses at T's position whose approach is cos β e_r + sin β e_z in T's arm plane (x5 along its normal),
    and each approach's angle from T's: the arm reaches such a pose exactly when it reaches its wrist point."""
    p = T[:3, 3]
    er = np.array([p[0], p[1], 0.0]) / math.hypot(p[0], p[1])
    m = np.array([-er[1], er[0], 0.0])
    Z = np.cos(betas)[:, None] * er + np.sin(betas)[:, None] * np.array([0.0, 0.0, 1.0])
    P = np.zeros((betas.size, 4, 4))
    P[:, :3, 0], P[:, :3, 1], P[:, :3, 2] = m, np.cross(Z, m), Z
    P[:, :3, 3], P[:, 3, 3] = p, 1.0
    return P, np.arccos(np.clip(Z @ T[:3, 2], -1.0, 1.0))


def attainable(P: np.ndarray) -> np.ndarray:
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # stretched or folded arms on the grid's edge
        return ARM.ik_batch(P).valid.any(axis=1)


def goal_family(rng: np.random.Generator, n: int, stretched: bool) -> list[np.ndarray]:
    """Reachable poses (nearly stretched ones if ``stretched``: θ3 within 0.3 rad of 0) turned by 0.2-1.5 rad
    about a random axis, the tool point at least 1 mm off the base axis: the issue's family, and a uniform one."""
    out = []
    while len(out) < n:
        q = rng.uniform(-math.pi, math.pi, 5)
        if stretched:
            q[2] = rng.uniform(-0.3, 0.3)
        T = ARM.fk(q)
        T[:3, :3] = rodrigues(rng.normal(size=3), rng.uniform(0.2, 1.5)) @ T[:3, :3]
        if math.hypot(T[0, 3], T[1, 3]) > 1.0:
            out.append(T)
    return out


def test_the_issue_example_is_turned_along_the_plane_not_refused():
    # p = (134.71, 191.34, -107.83) mm: the wrist points reachable for approaches β in [-154.48°, -1.62°] of the
    # arm plane (from e_r towards e_z). A goal 9.85° out of the plane whose projection is at β = +7.07°: the
    # projection's wrist point is out of reach, the direction 8.69° further along the plane is the nearest that
    # is not, arccos(cos 9.85° cos 8.69°) = 13.11° from the goal's approach.
    p = np.array([134.71, 191.34, -107.83])
    er = np.array([p[0], p[1], 0.0]) / math.hypot(p[0], p[1])
    m = np.array([-er[1], er[0], 0.0])
    s, b = math.radians(9.85), math.radians(-1.62225 + 8.69465)
    z = math.cos(s) * (math.cos(b) * er + math.sin(b) * np.array([0.0, 0.0, 1.0])) + math.sin(s) * m
    x = np.cross([0.0, 0.0, 1.0], z)
    x /= np.linalg.norm(x)
    T = homogeneous(np.column_stack([x, np.cross(z, x), z]), p)
    assert not ARM.ik(T).success
    projected = T.copy()
    projected[:3, :3] = rodrigues(np.cross(z, z - (m @ z) * m), s) @ T[:3, :3]
    assert "out of reach" in ARM.ik(projected).reason  # the old answer: turned 9.85°, then refused
    T2, info = ARM.nearest_attainable(T)
    assert info.success and info.unique
    assert abs(math.degrees(info.angle) - 13.11) < 0.005 and abs(math.degrees(info.along) - 8.69465) < 1e-3
    sol = ARM.ik(T2)
    assert len(sol) >= 1 and all(np.abs(ARM.fk(q)[:3, 3] - p).max() < 1e-9 for q in sol.q)
    assert abs(float(rotation_angle(T[:3, :3], T2[:3, :3])) - info.angle) < 1e-9
    P, ang = plane_directions(T, GRID)
    assert ang[attainable(P)].min() >= info.angle - 1e-12  # no grid direction nearer is reached


@pytest.mark.parametrize("stretched, seed", [(True, 31), (False, 32)])
def test_the_nearest_approach_agrees_with_a_brute_search_over_the_plane(stretched, seed):
    goals = goal_family(np.random.default_rng(seed), 1500, stretched)
    infos = [ARM.nearest_attainable(T) for T in goals]
    P = np.concatenate([plane_directions(T, GRID)[0] for T in goals])
    ok = attainable(P).reshape(len(goals), GRID.size)
    turned = refused = 0
    for T, (T2, info), reach in zip(goals, infos, ok, strict=True):
        _, ang = plane_directions(T, GRID)
        assert info.success or not reach.any()  # a grid direction the arm reaches: never refused
        if not info.success:
            refused += 1
            assert not reach.any() and "for every orientation" in info.reason
            continue
        turned += info.along > 0.0
        # the result: a rotation at the goal's position, its approach in the arm plane, reached by ik
        assert np.array_equal(T2[:3, 3], T[:3, 3])
        R = T2[:3, :3]
        assert np.allclose(R.T @ R, np.eye(3), atol=1e-12) and abs(np.linalg.det(R) - 1.0) < 1e-12
        sol = ARM.ik(T2)
        assert sol.success and all(np.abs(ARM.fk(q) - T2).max() < 1e-8 for q in sol.q)
        # turned the least that moves the approach there: the angle between the two approaches
        assert abs(float(rotation_angle(T[:3, :3], R)) - info.angle) < 1e-9
        assert abs(math.acos(min(1.0, float(T[:3, 2] @ R[:, 2]))) - info.angle) < 1e-7
        # no grid direction nearer than the returned one is reached; the nearest reached is at most a step away
        if reach.any():
            assert ang[reach].min() >= info.angle - 1e-9
            assert ang[reach].min() <= info.angle + math.radians(0.25)
    assert turned > 50 and refused < len(goals) // 10, (turned, refused)


def test_a_position_no_approach_serves_is_refused_with_the_circle_and_the_annulus():
    T = homogeneous(rotx(0.5), [700.0, 300.0, 300.0])  # the wrist point stays beyond a2 + a3 = 465 mm
    T2, info = ARM.nearest_attainable(T)
    assert not info.success and "for every orientation" in info.reason and "465" in info.reason
    P, _ = plane_directions(T, GRID)
    assert not attainable(P).any()
