"""Joint, actuator and Cartesian space (Meghdari's lecture): the map from an actuator to its joint.

A manipulator's configuration can be described in three spaces: **joint space** (the joint
variables q), **Cartesian space** (the position and orientation of the hand, ``robot.fk(q)``), and
**actuator space** (what the drives measure). They differ when a joint is driven through a linkage:
here a linear actuator (a piston of length s) pushes a revolute joint, attached at distance b from
the joint axis on one link and at distance c on the other. The triangle (b, c, s) fixes the angle
γ between the two attachment arms (law of cosines), and the joint angle is θ = γ - γ0 (γ0 the
angle between the arms at θ = 0):

    s² = b² + c² - 2 b c cos(θ + γ0),     ṡ = (b c sin(θ + γ0) / s) θ̇.

The map is nonlinear, so a constant piston speed does not give a constant joint speed.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .._validate import MAX_MAGNITUDE, as_array, as_robot_length, check_broadcast

__all__ = ["actuator_from_joint", "joint_from_actuator", "actuator_rate"]


def _arms(b: Any, c: Any) -> tuple[float, float]:
    return as_robot_length(b, "b", positive=True), as_robot_length(c, "c", positive=True)


def actuator_from_joint(theta: Any, b: float, c: float, gamma0: float = 0.0) -> Any:
    """The piston length s for the joint angle θ (radians; a number or an array).

    >>> float(actuator_from_joint(np.pi / 2, 3.0, 4.0))  # a right angle between arms 3 and 4
    5.0
    """
    b, c = _arms(b, c)
    g0 = float(as_array(gamma0, "gamma0", (), what="an angle in radians (a number)"))
    t = as_array(theta, "theta", what="a joint angle in radians (a number or an array)")
    g = t + g0
    s = np.hypot(b - c * np.cos(g), c * np.sin(g))  # = sqrt(b² + c² - 2 b c cos γ), no cancellation
    return float(s) if s.ndim == 0 else s


def joint_from_actuator(s: Any, b: float, c: float, gamma0: float = 0.0) -> Any:
    """The joint angle θ in [-γ0, π - γ0] for the piston length s (a number or an array).

    γ = atan2(4 · area, b² + c² - s²) with the triangle's area from Heron's formula: accurate at
    both ends of the stroke. Lengths outside |b - c| <= s <= b + c cannot close the triangle and
    raise ``ValueError``; within 1e-12 (b + c) of an end they are snapped onto it.

    >>> round(float(joint_from_actuator(5.0, 3.0, 4.0)), 12) == round(np.pi / 2, 12)
    True
    """
    b, c = _arms(b, c)
    g0 = float(as_array(gamma0, "gamma0", (), what="an angle in radians (a number)"))
    sv = as_array(s, "s", what="a piston length (a number or an array)")
    tol = 1e-12 * (b + c)
    lo, hi = abs(b - c), b + c
    if np.any(sv < lo - tol) or np.any(sv > hi + tol):
        raise ValueError(f"s: expected piston lengths between |b - c| = {lo:g} and b + c = {hi:g}, "
                         f"got values from {float(sv.min()):g} to {float(sv.max()):g}")  # fmt: skip
    sv = np.clip(sv, lo, hi)
    area4 = np.sqrt(np.maximum((b + c + sv) * (-b + c + sv) * (b - c + sv) * (b + c - sv), 0.0))
    g = np.arctan2(area4, b * b + c * c - sv * sv)
    out = g - g0
    return float(out) if out.ndim == 0 else out


def actuator_rate(theta: Any, theta_dot: Any, b: float, c: float, gamma0: float = 0.0) -> Any:
    """The piston speed ṡ = (b c sin(θ + γ0) / s) θ̇ for the joint speed θ̇ at the angle θ.

    >>> round(float(actuator_rate(np.pi / 2, 1.0, 3.0, 4.0)), 12)  # 3 · 4 / 5
    2.4
    """
    b, c = _arms(b, c)
    g0 = float(as_array(gamma0, "gamma0", (), what="an angle in radians (a number)"))
    t = as_array(theta, "theta", what="a joint angle in radians (a number or an array)")
    w = as_array(theta_dot, "theta_dot", what="a joint speed in rad/s (a number or an array)",
                 max_magnitude=MAX_MAGNITUDE)  # (b c / s) θ̇ must stay finite (issue 31: 1.5e308 gave inf)
    check_broadcast(theta=t.shape, theta_dot=w.shape)  # not numpy's "could not be broadcast" (issue 21)
    s = np.asarray(actuator_from_joint(t, b, c, g0))
    if np.any(s <= 1e-15 * (b + c)):
        raise ValueError("theta: expected an angle where the piston has a length (s > 0), got one folding it to 0")
    out = b * c * np.sin(t + g0) / s * w
    return float(out) if np.ndim(out) == 0 else out
