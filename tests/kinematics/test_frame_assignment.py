"""Craig's frame-assignment rules as code: the common normal by hand, and tables derived from joint axes
that give back the lecture's PUMA-560 table and place every frame on its robot's axis."""

from __future__ import annotations

import math

import numpy as np
import pytest

from puma_course.kinematics import MK3, DHChain, Link, Puma560
from puma_course.kinematics.frame_assignment import common_normal, dh_from_axes


def test_common_normal_of_skew_lines_by_hand():
    # the z axis and the line through (1, 0, 5) along y: the normal is the unit segment along x at z = 5
    cn = common_normal([0, 0, 0], [0, 0, 1], [1, 0, 5], [0, 1, 0])
    assert cn.kind == "skew" and cn.a == 1.0
    assert np.allclose(cn.foot1, [0, 0, 5]) and np.allclose(cn.foot2, [1, 0, 5])
    assert np.allclose(cn.direction, [1, 0, 0])
    assert cn.alpha == -math.pi / 2  # e_z turns into e_y about +x by -90° (snapped exactly)
    # a 45° twist: Rot(x, 45°) e_z = (0, -s, c); the line through (2, 1, 1) along (0, -1, 1) passes
    # (2, 0, 2), straight out along x from (0, 0, 2) on the z axis
    cn = common_normal([0, 0, 0], [0, 0, 1], [2, 1, 1], [0, -1, 1])
    assert cn.a == pytest.approx(2.0) and cn.alpha == pytest.approx(math.pi / 4)
    assert np.allclose(cn.foot1, [0, 0, 2]) and np.allclose(cn.foot2, [2, 0, 2])


def test_common_normal_of_intersecting_and_parallel_lines():
    cn = common_normal([0, 0, 0], [0, 0, 1], [0, 0, 0], [0, 1, 0])
    assert cn.kind == "intersecting" and cn.a == 0.0
    assert np.allclose(cn.direction, [-1, 0, 0])  # +z x y by default
    assert np.allclose(common_normal([0, 0, 0], [0, 0, 1], [0, 0, 0], [0, 1, 0], hint=[1, 0, 0]).direction, [1, 0, 0])
    cn = common_normal([0, 0, 0], [0, 1, 0], [3, 5, 0], [0, 1, 0], at=[0, 2, 0])
    assert cn.kind == "parallel" and cn.a == pytest.approx(3.0) and cn.alpha == 0.0
    assert np.allclose(cn.foot1, [0, 2, 0]) and np.allclose(cn.foot2, [3, 2, 0])  # the normal through `at`
    same = common_normal([0, 0, 0], [1, 0, 0], [2, 0, 0], [-1, 0, 0])
    assert same.a == 0.0 and same.alpha == math.pi and abs(float(np.dot(same.direction, [1, 0, 0]))) < 1e-12


def test_the_pumas_axes_give_back_the_lectures_table():
    arm = Puma560()
    F = arm.frames(np.zeros(6))
    t = dh_from_axes(F[1:7, :3, 3], F[1:7, :3, 2])
    got = [(lk.alpha_prev, lk.a_prev, lk.d, lk.theta) for lk in t.chain.links]
    want = [(lk.alpha_prev, lk.a_prev, lk.d, lk.theta) for lk in arm.links]
    assert np.allclose(got, want, atol=1e-12)
    assert [lk.alpha_prev for lk in t.chain.links] == [lk.alpha_prev for lk in arm.links]  # twists snapped exactly
    assert np.allclose(t.base, np.eye(4))


def _on_the_same_axes(robot, derived, q):
    G, H = derived.base @ derived.chain.frames(q), robot.frames(q)
    for i in range(1, robot.n + 1):
        z, zr = G[:, i, :3, 2], H[:, i, :3, 2]
        assert np.allclose(np.abs(np.einsum("nj,nj->n", z, zr)), 1.0)
        d = G[:, i, :3, 3] - H[:, i, :3, 3]
        off = d - np.einsum("nj,nj->n", d, zr)[:, None] * zr
        assert np.abs(off).max() < 1e-9 * max(1.0, float(np.abs(H[..., :3, 3]).max()))


@pytest.mark.parametrize("seed", range(4))
def test_derived_frames_sit_on_the_robots_joint_axes_at_every_configuration(seed):
    """Any valid table puts Z_i on joint axis i for every q: a property independent of the choices made."""
    rng = np.random.default_rng(seed)
    robots = [Puma560(), MK3()]
    for kinds in (["R", "R", "P", "R", "R"], ["P", "R", "R", "P"]):  # a prismatic joint inside, and first
        links = [Link(rng.uniform(-3, 3), rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1), k) for k in kinds]
        robots.append(DHChain(links))
    q = rng.uniform(-2, 2, (20, 6))
    for robot in robots:
        F = robot.frames(np.zeros(robot.n))
        derived = dh_from_axes(F[1 : robot.n + 1, :3, 3], F[1 : robot.n + 1, :3, 2], [lk.kind for lk in robot.links])
        _on_the_same_axes(robot, derived, q[:, : robot.n])


def test_a_prismatic_first_joint_keeps_frame_1_on_its_axis():
    """Found by lecture 02's frame_steps: with X_0 taken from ``x0`` but θ1 = atan2(...) kept, frame {2}
    left its axis. By hand: slider along z_0, then a revolute axis along x through (0, 1, 0.5)."""
    t = dh_from_axes([[0, 0, 0], [0, 1, 0.5]], [[0, 0, 1], [1, 0, 0]], ["P", "R"])
    assert t.chain.links[0].theta == 0.0
    F = t.base @ t.chain.frames(np.zeros(2))
    o2, z2 = F[2, :3, 3], F[2, :3, 2]
    assert np.allclose(np.abs(z2), [1, 0, 0])
    assert np.allclose(o2[1:], [1.0, 0.5])  # on the axis x = t, y = 1, z = 0.5


def test_the_mk3_table_moves_d1_into_the_base():
    arm = MK3()
    F = arm.frames(np.zeros(5))
    t = dh_from_axes(F[1:6, :3, 3], F[1:6, :3, 2])
    assert [round(math.degrees(lk.alpha_prev)) for lk in t.chain.links] == [0, 90, 0, 0, 90]
    assert [lk.a_prev for lk in t.chain.links] == pytest.approx([0, 135, 250, 215, 0])
    assert t.base[2, 3] == pytest.approx(360.0)  # frame {0} = {1} at q1 = 0, 360 mm above the floor


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: common_normal([0, 0, 0], [0, 0, 0], [1, 0, 0], [0, 1, 0]), "^u1: expected a non-zero direction"),
        (lambda: common_normal([0, 0, 0], [0, 0, 1], [1j, 0, 0], [0, 1, 0]), "^p2: expected"),
        (lambda: dh_from_axes([[0, 0, 0]], [[0, 0, 1], [1, 0, 0]]), "^points, directions: expected one point"),
        (lambda: dh_from_axes([[0, 0, 0]], [[0, 0, 1]], ["X"]), "^kinds: expected 1 entries"),
        (lambda: dh_from_axes([[0, 0, 0]], [[0, 0, 0]]), r"^directions\[0\]: expected a non-zero direction"),
    ],
)
def test_bad_input(call, match):
    with pytest.raises(ValueError, match=match):
        call()
