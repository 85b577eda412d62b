"""The PUMA-560's published joint limits (issue 25): the cited numbers, their move into this model's
angles, and IK selection with them."""

from __future__ import annotations

import math

import numpy as np
import pytest

from puma_course.kinematics import MK3, Puma560
from puma_course.kinematics.joint_limits import FROM_CORKE_DEG, JOINT_LIMITS, PUBLISHED_QLIM_DEG

# Corke's Robotics Toolbox for MATLAB, models/mdl_puma560.m, 'qlim' of L(1)..L(6) in degrees (the limits it
# takes from Wang & Chen 1991), typed here from that file: the table the package cites.
CORKE_MDL_PUMA560_QLIM_DEG = [[-160, 160], [-45, 225], [-225, 45], [-110, 170], [-100, 100], [-266, 266]]

# The same file's standard-DH table (d, a, alpha) and named configurations.
CORKE_D = [0.0, 0.0, 0.15005, 0.4318, 0.0, 0.0]
CORKE_A = [0.0, 0.4318, 0.0203, 0.0, 0.0, 0.0]
CORKE_ALPHA = [math.pi / 2, 0.0, -math.pi / 2, math.pi / 2, -math.pi / 2, 0.0]
CORKE_CONFIGS = {"qr": [0, math.pi / 2, -math.pi / 2, 0, 0, 0]}  # the ready pose, arm up


def corke_fk(q):
    """Standard DH, written out here (Rz(θ) Tz(d) Tx(a) Rx(α) per link): Corke's model, independent of the package."""
    T = np.eye(4)
    for th, d, a, al in zip(q, CORKE_D, CORKE_A, CORKE_ALPHA, strict=True):
        ct, st, ca, sa = math.cos(th), math.sin(th), math.cos(al), math.sin(al)
        link = [[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st], [0, sa, ca, d], [0, 0, 0, 1]]
        T = T @ np.array(link)
    return T


RZ_PI = np.diag([-1.0, -1.0, 1.0, 1.0])  # this model's base frame in Corke's: turned by 180° about the base axis


def test_the_numbers_are_the_cited_table():
    assert np.array_equal(np.array(PUBLISHED_QLIM_DEG), np.array(CORKE_MDL_PUMA560_QLIM_DEG, dtype=float))
    spans = [hi - lo for lo, hi in PUBLISHED_QLIM_DEG]
    assert spans == [320, 270, 270, 280, 200, 532]  # the ranges Unimation quotes


def test_corke_angles_move_into_this_model_by_the_stated_offsets():
    arm = Puma560()
    off = np.radians(FROM_CORKE_DEG)
    rng = np.random.default_rng(25)
    for q in rng.uniform(-math.pi, math.pi, (50, 6)):
        assert np.allclose(arm.fk(q + off), RZ_PI @ corke_fk(q), atol=1e-12)
    # the ready arm (straight up) is the same arm in both; qz and qs point along each model's own x0
    assert np.allclose(np.array(CORKE_CONFIGS["qr"]) + off, arm.q("qr"))


def test_joint_limits_are_the_published_ranges_in_this_models_angles():
    arm = Puma560()
    assert arm.joint_limits is JOINT_LIMITS and not JOINT_LIMITS.flags.writeable
    expected = np.radians([[-160, 160], [-225, 45], [-225, 45], [-110, 170], [-100, 100], [-266, 266]])
    assert np.allclose(JOINT_LIMITS, expected, atol=1e-15)
    for name in ("qr", "qs", "qn", "qz"):  # the named configurations are arms a real PUMA can take
        q = arm.q(name)
        assert np.all((q >= JOINT_LIMITS[:, 0]) & (q <= JOINT_LIMITS[:, 1])), name
    assert np.allclose(arm.qlim, [[-math.pi, math.pi]] * 6)  # the sliders' range is unchanged
    assert MK3().joint_limits is None  # no source publishes the MK3's


def _inside_some_turn(q, lim):
    """Brute force: some q + 2πk (k = -2..2) inside [lo, hi] for every joint (all the PUMA's joints turn)."""
    k = np.arange(-2, 3)[:, None]
    turns = [v + 2 * np.pi * k for v in q]
    return all(np.any((t >= lo) & (t <= hi)) for t, (lo, hi) in zip(turns, lim, strict=True))


def test_ik_with_limits_drops_exactly_the_solutions_outside_and_keeps_the_pose():
    arm = Puma560()
    rng = np.random.default_rng(2525)
    dropped = kept_total = 0
    for q0 in rng.uniform(-math.pi, math.pi, (60, 6)):
        T = arm.fk(q0)
        every = arm.ik(T)
        kept = every.within_limits(arm.joint_limits)
        should = [lb for lb, q in zip(every.labels, every.q, strict=True) if _inside_some_turn(q, JOINT_LIMITS)]
        assert kept.labels == tuple(should)
        for q in kept:
            assert np.all((q >= JOINT_LIMITS[:, 0]) & (q <= JOINT_LIMITS[:, 1]))  # the value itself is inside
            assert np.allclose(arm.fk(q), T, atol=1e-9)  # and it reaches the pose
        dropped += len(every) - len(kept)
        kept_total += len(kept)
        assert kept.success == bool(should)
    assert dropped > 0 and kept_total > 0


def test_a_solution_outside_the_limits_is_dropped():
    arm = Puma560()
    q0 = np.radians([30.0, -50.0, 20.0, 40.0, 120.0, -30.0])  # θ5 = 120° is past the wrist's 100° stop
    every = arm.ik(T := arm.fk(q0))
    assert any(np.allclose(q, q0) for q in every)
    kept = every.within_limits(arm.joint_limits)
    assert not any(np.allclose(q, q0) for q in kept) and len(kept) < len(every)
    assert all(abs(q[4]) <= np.radians(100) for q in kept)
    assert all(np.allclose(arm.fk(q), T, atol=1e-9) for q in kept)


def test_an_angle_inside_only_after_a_turn_comes_back_turned():
    arm = Puma560()
    q0 = np.radians([10.0, -200.0, -30.0, 20.0, 40.0, 10.0])  # θ2 = -200°: reached by the real arm, wrapped to 160°
    every = arm.ik(T := arm.fk(q0))
    wrapped = [q for q in every if np.allclose(q[1], np.radians(160.0))]
    assert wrapped  # ik returns it wrapped into (-π, π]
    kept = every.within_limits(arm.joint_limits)
    match = [q for q in kept if np.allclose(q, q0)]
    assert match and np.allclose(arm.fk(match[0]), T, atol=1e-9)


@pytest.mark.filterwarnings("ignore::puma_course.kinematics.ik.SingularityWarning")  # θ5 = 0 at qz, qr, qs
@pytest.mark.parametrize("name", ["qz", "qr", "qs", "qn"])
def test_a_named_configuration_survives_its_own_ik_with_limits(name):
    arm = Puma560()
    q = arm.q(name)
    kept = arm.ik(arm.fk(q), near=q).within_limits(arm.joint_limits)
    assert kept.success and np.allclose(kept[0], q, atol=1e-9)
