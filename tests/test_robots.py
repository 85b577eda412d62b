"""PUMA-560 and MK3 models: hand-worked poses and the closed forms of the lecture."""

from __future__ import annotations

import math

import numpy as np
import pytest

from puma_course.robots import mk3, puma560

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
    T = puma560().fk(np.zeros(6))
    assert np.allclose(T[:3, 3], [A2 + A3, D3, -D4])
    # With every θ = 0 only the twists act, all about x: -90 - 90 + 90 - 90 = -180 degrees.
    assert np.allclose(T[:3, :3], np.diag([1.0, -1.0, -1.0]))


def test_puma_second_hand_worked_pose():
    # θ1 = 90°, θ3 = -90°: the arm stretched horizontally, turned to point along +y.
    # Position: x = -d3, y = a2 + d4, z = a3.
    q = np.array([math.pi / 2, 0, -math.pi / 2, 0, 0, 0])
    assert np.allclose(puma560().fk(q)[:3, 3], [-D3, A2 + D4, A3])


def test_puma_named_configurations():
    r = puma560()
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
    assert np.allclose(puma560().fk(q)[:, :3, 3], craig_puma_position(q), atol=1e-12)
    r = puma560(a2=1.0, a3=0.2, d3=-0.3, d4=0.7)
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
        assert np.allclose(puma560().fk(q)[:3, 0], [r11, r21, r31], atol=1e-12)


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
    T = mk3().fk(np.zeros(5))
    assert np.allclose(T[:3, 3], [600, 0, 260])
    assert np.allclose(T[:3, 2], [0, 0, -1])


def test_mk3_ready_pose_hand_worked():
    # θ2 = 90°, θ3 = -90°: upper arm vertical (z = 360 + 250), forearm horizontal (x = 135 + 215),
    # tool down by 100.
    r = mk3()
    assert np.allclose(r.fk(r.q("qr"))[:3, 3], [350, 0, 510])


def test_mk3_matches_printed_closed_forms():
    rng = np.random.default_rng(3)
    r = mk3()
    for q in rng.uniform(-math.pi, math.pi, (100, 5)):
        assert np.allclose(r.fk(q), mk3_printed(q), atol=1e-9)


def test_batches_are_vectorised_shapes():
    q = np.zeros((3, 6))
    assert puma560().fk(q).shape == (3, 4, 4)
    assert puma560().frames(q).shape == (3, 7, 4, 4)
    assert mk3().fk(np.zeros((2, 5))).shape == (2, 4, 4)


@pytest.mark.parametrize(
    "call, fragment",
    [
        (lambda: puma560(a2="long"), "a2"),
        (lambda: puma560(d4=float("nan")), "d4: expected finite"),
        (lambda: puma560().fk(np.zeros(5)), "shape (6,)"),
        (lambda: mk3().fk(np.zeros(6)), "shape (5,)"),
        (lambda: mk3(d5=[1, 2]), "d5"),
    ],
)
def test_bad_input(call, fragment):
    with pytest.raises(ValueError) as err:
        call()
    assert fragment in str(err.value)
