"""Actuator space: the piston-to-joint map against the law of cosines by hand, round trips and derivatives."""

from __future__ import annotations

import numpy as np
import pytest

from puma_course.kinematics.spaces import actuator_from_joint, actuator_rate, joint_from_actuator


def test_hand_worked_triangles():
    assert actuator_from_joint(np.pi / 2, 3.0, 4.0) == pytest.approx(5.0)  # 3-4-5
    assert actuator_from_joint(np.pi / 3, 2.0, 2.0) == pytest.approx(2.0)  # equilateral
    assert joint_from_actuator(5.0, 3.0, 4.0) == pytest.approx(np.pi / 2)
    assert joint_from_actuator(7.0, 3.0, 4.0) == np.pi  # fully extended: γ = π exactly (snapped end)
    assert joint_from_actuator(1.0, 3.0, 4.0) == 0.0  # fully retracted: γ = 0 exactly
    assert joint_from_actuator(5.0, 3.0, 4.0, gamma0=0.5) == pytest.approx(np.pi / 2 - 0.5)


def test_round_trip_and_batch():
    theta = np.linspace(0.05, 2.9, 50)
    s = actuator_from_joint(theta, 0.3, 0.5, gamma0=0.1)
    assert s.shape == (50,) and np.allclose(joint_from_actuator(s, 0.3, 0.5, gamma0=0.1), theta, atol=1e-12)


def test_the_rate_is_the_derivative():
    theta, h = 1.1, 1e-6
    ds = (actuator_from_joint(theta + h, 0.3, 0.5) - actuator_from_joint(theta - h, 0.3, 0.5)) / (2 * h)
    assert actuator_rate(theta, 1.0, 0.3, 0.5) == pytest.approx(ds, rel=1e-8)
    # nonlinear: the same joint speed needs different piston speeds at different angles
    assert actuator_rate(0.3, 1.0, 0.3, 0.5) != pytest.approx(actuator_rate(1.5, 1.0, 0.3, 0.5))


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: joint_from_actuator(8.0, 3.0, 4.0), "^s: expected piston lengths between"),
        (lambda: joint_from_actuator(0.5, 3.0, 4.0), "^s: expected piston lengths between"),
        (lambda: actuator_from_joint(1.0, 0.0, 4.0), "^b: expected a positive length"),
        (lambda: actuator_from_joint(1j, 1.0, 4.0), "^theta: expected"),
        (lambda: actuator_rate(0.0, 1.0, 2.0, 2.0), "^theta: expected an angle where the piston has a length"),
    ],
)
def test_bad_input(call, match):
    with pytest.raises(ValueError, match=match):
        call()
