"""Frame assignment one step at a time, and the standard DH link matrix.

Independent truths: the PUMA-560's table worked out by hand (Craig's), the rules themselves as
properties (X_i normal to Z_i and Z_{i+1}, O_i + a_i X_i on axis i+1, consecutive frames related by
Craig's link matrix of the row found), dh_from_axes (a second implementation), sympy's product of the
four elementary motions for the standard link matrix, and DHChain.fk for the conversion.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from puma_course import symbolic as S
from puma_course.kinematics import MK3, DHChain, Link, Puma560, mdh
from puma_course.kinematics.frame_assignment import d_theta, dh_from_axes, frame_steps
from puma_course.kinematics.standard_dh import standard_dh, standard_fk, standard_from_modified

H = math.pi / 2


def puma_axes(a2=0.4318, a3=0.0203, d3=0.15005, d4=0.4318):
    """The PUMA-560's joint axes at q = 0 from its drawing (not from its table): points and senses."""
    W = [a2 + a3, d3, -d4]
    points = [[0, 0, 0], [0, 0, 0], [a2, 0, 0], [a2 + a3, d3, 0], W, W]
    directions = [[0, 0, 1], [0, 1, 0], [0, 1, 0], [0, 0, -1], [0, 1, 0], [0, 0, -1]]
    return np.array(points, float), np.array(directions, float)


def test_the_pumas_table_by_hand():
    walk = frame_steps(*puma_axes())
    got = [(s.alpha_prev, s.a_prev, s.theta, s.d) for s in walk.steps]
    want = [(0, 0, 0, 0), (-H, 0, 0, 0), (0, 0.4318, 0, 0.15005), (-H, 0.0203, 0, 0.4318), (H, 0, 0, 0), (-H, 0, 0, 0)]
    assert np.allclose(got, want, atol=1e-12)
    assert [s.alpha_prev for s in walk.steps] == [0.0, -H, 0.0, -H, H, -H]  # twists exact
    assert [s.rule for s in walk.steps] == ["intersecting", "parallel", "skew", "intersecting", "intersecting", "last"]
    assert np.allclose(walk.base, np.eye(4))
    # the origin of {3} is where the normal to axis 4 meets axis 3: d3 sideways of the upper arm
    assert np.allclose(walk.steps[2].origin, [0.4318, 0.15005, 0])
    assert np.allclose(walk.steps[2].normal.foot2, [0.4521, 0.15005, 0])


def test_the_pumas_axes_as_drawn_are_the_models_axes_and_its_frames():
    arm = Puma560()
    P, U = puma_axes()
    F = arm.frames(np.zeros(6))
    walk = frame_steps(P, U)
    assert np.allclose(walk.frames, F, atol=1e-12)
    for i in range(6):  # the model's Z_i lies on the drawn line i, in the same sense
        assert np.allclose(F[i + 1, :3, 2], U[i])
        off = F[i + 1, :3, 3] - P[i]
        assert np.allclose(off - np.dot(off, U[i]) * U[i], 0, atol=1e-12)


@pytest.mark.parametrize("robot", [Puma560(), Puma560(a2=0.6, a3=-0.05, d3=0.0, d4=0.35), MK3()], ids=str)
def test_the_same_table_as_dh_from_axes(robot):
    F = robot.frames(np.zeros(robot.n))
    P, U = F[1:, :3, 3], F[1:, :3, 2]
    walk, derived = frame_steps(P, U), dh_from_axes(P, U)
    ours = [(lk.alpha_prev, lk.a_prev, lk.theta, lk.d) for lk in walk.links]
    theirs = [(lk.alpha_prev, lk.a_prev, lk.theta, lk.d) for lk in derived.chain.links]
    assert np.allclose(ours, theirs, atol=1e-9)
    assert np.allclose(walk.base, derived.base, atol=1e-9)


def _check_rules(walk, P, U, q):
    n = len(walk.steps)
    for i, s in enumerate(walk.steps):
        assert np.allclose(s.z, U[i] / np.linalg.norm(U[i]))
        off = s.origin - P[i]  # the origin lies on axis i
        assert np.linalg.norm(off - np.dot(off, s.z) * s.z) < 1e-9
        assert abs(np.dot(s.x, s.z)) < 1e-12 and abs(np.linalg.norm(s.x) - 1) < 1e-12
        if i < n - 1:
            z1 = U[i + 1] / np.linalg.norm(U[i + 1])
            assert abs(np.dot(s.x, z1)) < 1e-9  # X_i is normal to both axes ...
            tip = s.origin + s.a * s.x  # ... and reaches axis i+1 after a_i
            w = tip - P[i + 1]
            assert np.linalg.norm(w - np.dot(w, z1) * z1) < 1e-9
            assert np.allclose(mdh(s.alpha, 0, 0, 0)[:3, 2], np.linalg.inv(s.frame)[:3, :3] @ z1)  # twist α_i
    F = walk.frames
    for i, s in enumerate(walk.steps):  # consecutive frames are related by the row found
        assert np.allclose(np.linalg.inv(F[i]) @ F[i + 1], mdh(s.alpha_prev, s.a_prev, s.theta, s.d), atol=1e-9)
    chain = walk.chain()  # and the chain moves on the axes: Z_i stays on axis i as the joints move
    G = walk.base @ chain.frames(q)
    assert G.shape == (len(q), n + 1, 4, 4)


@pytest.mark.parametrize("seed", range(6))
def test_random_skew_axes_obey_the_rules(seed):
    rng = np.random.default_rng(seed)
    n = 5
    P, U = rng.uniform(-2, 2, (n, 3)), rng.normal(size=(n, 3))
    kinds = ["P" if k else "R" for k in rng.integers(0, 2, n)]
    walk = frame_steps(P, U, kinds)
    assert all(s.rule in ("skew", "last") for s in walk.steps)
    _check_rules(walk, P, U, rng.uniform(-2, 2, (4, n)))


def test_a_prismatic_first_joint_keeps_frame_1_on_its_axis():
    """{0} and {1} share X at q = 0 (θ1 = 0), and the chain's frames stay on the given axes."""
    P, U = np.array([[0, 0, 0], [0, 1, 0.5]]), np.array([[0, 0, 1.0], [1, 0, 0]])
    walk = frame_steps(P, U, ["P", "R"])
    assert walk.steps[0].theta == 0.0 and walk.steps[0].d == pytest.approx(0.5)
    assert np.allclose(walk.base[:3, 0], [0, 1, 0]) and np.allclose(walk.base[:3, 3], 0)
    F = walk.base @ walk.chain().frames(np.zeros(2))
    assert np.allclose(F[2, :3, 3], [0, 1, 0.5]) and np.allclose(F[2, :3, 2], [1, 0, 0])
    _check_rules(walk, P, U, np.zeros((1, 2)))


def test_parallel_and_same_line_axes():
    # planar 3R: all axes along z; the normals lie in the plane of the first foot, d = 0
    P = np.array([[0, 0, 0.3], [1, 0, 0.7], [1.5, 0.5, -0.2]])
    U = np.array([[0, 0, 1.0]] * 3)
    walk = frame_steps(P, U)
    assert [s.rule for s in walk.steps] == ["parallel", "parallel", "last"]
    assert [s.d for s in walk.steps] == [0.0, 0.0, 0.0]
    assert [s.a_prev for s in walk.steps] == pytest.approx([0, 1, math.hypot(0.5, 0.5)])
    assert walk.steps[1].theta == pytest.approx(math.radians(45)) and walk.steps[2].theta == 0.0  # X1 to X2 turns
    same = frame_steps([[0, 0, 0], [0, 0, 2]], [[0, 0, 1], [0, 0, -1]])
    assert (
        same.steps[0].rule == "same line" and same.steps[0].a == 0.0 and same.steps[0].alpha == pytest.approx(math.pi)
    )


def test_describe_names_the_rule():
    walk = frame_steps(*puma_axes())
    texts = [s.describe("m") for s in walk.steps]
    assert texts[2].startswith("{3}: axes 3 and 4 are skew") and "α3 = -90°" in texts[2] and "d3 = 0.15 m" in texts[2]
    assert "intersect" in texts[0] and texts[5].startswith("{6}: the last axis")


def test_d_theta_by_hand_and_its_checks():
    d, th = d_theta([0, 0, 2], [0, 0, 1], [1, 0, 0], [0, 0, -1], [-1, 0, 0])
    assert d == -2.0 and th == pytest.approx(math.pi)
    with pytest.raises(ValueError, match="^x_prev: expected a direction normal to z"):
        d_theta([0, 0, 1], [0, 0, 0], [1, 0, 1], [0, 0, 1], [1, 0, 0])
    with pytest.raises(ValueError, match="^origin: expected a point on the axis"):
        d_theta([0, 0, 1], [0, 0, 0], [1, 0, 0], [0.1, 0, 1], [1, 0, 0])


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: frame_steps([[0, 0, 0]], [[0, 0, 1], [1, 0, 0]]), "^points, directions: expected one point"),
        (lambda: frame_steps([[0, 0, 0]], [[0, 0, 0]]), r"^directions\[0\]: expected a non-zero direction"),
        (lambda: frame_steps([[0, 0, np.nan]], [[0, 0, 1]]), "^points: expected finite"),
        (lambda: frame_steps([[0, 0, 1j]], [[0, 0, 1]]), "^points: expected"),
        (lambda: frame_steps([[0, 0, 0]], [[0, 0, 1]], ["X"]), "^kinds: expected"),
        (lambda: frame_steps([[0, 0, 0]], [[0, 0, 1]], "R"), "^kinds: expected 1 entries"),
        (lambda: frame_steps([[0, 0, 0]], [[0, 0, 1]], x0=[0, 0, 2]), "^x0: expected a direction not along"),
        (lambda: frame_steps("abc", [[0, 0, 1]]), "^points: expected"),
        (lambda: d_theta([0, 0, 0], [0, 0, 0], [1, 0, 0], [0, 0, 1], [1, 0, 0]), "^z: expected a non-zero"),
        (lambda: standard_dh(0.1, None, 0.0, 0.0), "^d: expected"),
        (lambda: standard_dh([0.1, 0.2], 0.0, [1.0, 2.0, 3.0], 0.0), "^theta, d, a, alpha: expected arrays"),
        (lambda: standard_from_modified([]), "^links: expected a non-empty list"),
        (lambda: standard_from_modified([(0, 1, 0, 0)]), "^links: expected"),
        (lambda: standard_fk([(0.0, 0.0, 1.0, 0.0, "R")], [0.0, 1.0]), "^q: expected 1 joint values"),
        (lambda: standard_fk([(0.0, 0.0, 1.0, 0.0, "X")], [0.0]), "^rows: expected"),
        (lambda: standard_fk([(0.0, 0.0)], [0.0]), "^rows: expected"),
    ],
)
def test_bad_input(call, match):
    with pytest.raises(ValueError, match=match):
        call()


def test_standard_dh_is_the_product_of_its_four_motions():
    th, d, a, al = sp.symbols("theta d a alpha", real=True)
    M = S.rot("z", th) * S.trans("z", d) * S.trans("x", a) * S.rot("x", al)
    f = sp.lambdify((th, d, a, al), M, modules="numpy")
    rng = np.random.default_rng(5)
    for p in rng.uniform(-3, 3, (20, 4)):
        assert np.allclose(standard_dh(*p), np.array(f(*p), dtype=float))
    batch = rng.uniform(-3, 3, (7, 4))
    assert standard_dh(*batch.T).shape == (7, 4, 4)


@pytest.mark.parametrize("seed", range(4))
def test_the_moved_columns_give_the_same_chain(seed):
    rng = np.random.default_rng(seed)
    kinds = ["R", "P", "R", "R"]
    links = [Link(rng.uniform(-3, 3), rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1), k) for k in kinds]
    chain = DHChain(links)
    rows, base = standard_from_modified(links)
    for q in rng.uniform(-2, 2, (5, 4)):
        assert np.allclose(base @ standard_fk(rows, q), chain.fk(q))
        naive = [(lk.theta, lk.d, lk.a_prev, lk.alpha_prev, lk.kind) for lk in links]
        assert not np.allclose(standard_fk(naive, q), chain.fk(q))  # the modified rows read as standard: wrong


def test_the_puma_needs_no_base_transform():
    arm = Puma560()
    rows, base = standard_from_modified(arm.links)
    assert np.array_equal(base, np.eye(4))
    q = np.random.default_rng(3).uniform(-np.pi, np.pi, 6)
    assert np.allclose(standard_fk(rows, q), arm.fk(q))
