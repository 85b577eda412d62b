"""Geometry of the three-step arm (source "2.3 Kinematics"): eq. (1), the arm axis (eq. 4), and the
two formulas every solver of the arm shares: the base angle and the shoulder-elbow-wrist triangle.

The formulas take an ``ops`` argument (:mod:`puma_course.kinematics._ops`): plain floats for the
lecture's one-target procedure, numpy arrays for the batched inverse kinematics.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..._validate import as_array

__all__ = ["arm_axis", "points_eq1", "base_angle", "triangle"]


def arm_axis(theta0: Any) -> np.ndarray:
    """The shoulder/elbow axis a = (sin θ0, -cos θ0, 0) of eq. (4); (3,) or (N, 3).

    a = r̂ x e_z with r̂ = (cos θ0, sin θ0, 0) the horizontal direction of the arm plane, so a
    positive turn about ``a`` lifts r̂ towards e_z: it *increases* θ1.

    >>> from puma_course.transforms import rodrigues
    >>> np.round(rodrigues(arm_axis(0.0), np.pi / 2) @ [1, 0, 0], 12) + 0.0
    array([0., 0., 1.])
    """
    what = "an angle in radians (a number or an array of shape (N,))"
    t = as_array(theta0, "theta0", what=what)
    if t.ndim > 1:
        raise ValueError(f"theta0: expected {what}, got an array of shape {t.shape}")
    return np.stack([np.sin(t), -np.cos(t), np.zeros_like(t)], axis=-1)


def points_eq1(o: Any, t0: Any, t1: Any, t2: Any, l1: float, l2: float) -> tuple[Any, ...]:
    """Elbow e and wrist centre w of eq. (1) as six coordinates (ex, ey, ez, wx, wy, wz); s = 0."""
    c0, s0 = o.cos(t0), o.sin(t0)
    r_e, z_e = l1 * o.cos(t1), l1 * o.sin(t1)
    r_w, z_w = r_e + l2 * o.cos(t1 + t2), z_e + l2 * o.sin(t1 + t2)
    return c0 * r_e, s0 * r_e, z_e, c0 * r_w, s0 * r_w, z_w


def base_angle(o: Any, wx: Any, wy: Any, tol: float, free: Any) -> tuple[Any, Any, Any]:
    """θ0 = atan2(w_y, w_x) (eq. 2 with its quadrant restored), ρ = |(w_x, w_y)| and the on-axis flag.

    Within ``tol`` of the base axis w counts as on it (snapped: ρ = 0, θ0 = ``free``), so the choice
    never hinges on the signs of two rounding residues.
    """
    rho = o.hypot(wx, wy)
    on_axis = rho <= tol
    return o.where(on_axis, free, o.atan2(wy, wx)), o.where(on_axis, 0.0, rho), on_axis


def triangle(o: Any, l1: float, l2: float, l3: Any, tol: float) -> tuple[Any, ...]:
    """The triangle (ℓ1, ℓ2, ℓ3 = |w|): θ at the shoulder (eq. 5) and β at the elbow, snapped at the boundaries.

    Returns (ℓ3 snapped, θ, β, stretched, folded). A wrist beyond, or within rounding (and ``tol``) of,
    the stretched (ℓ1 + ℓ2) or folded (|ℓ1 - ℓ2|) boundary is put on it: one factor of Heron's product is then
    exactly 0, so θ and β are exactly 0 or π there, on every machine. Both angles come from
    atan2(4·area, numerator of the law of cosines): given ℓ3 exactly, that is accurate to the last
    bit where arccos is not (lecture 08 measures both).
    """
    # Snapped only within rounding (1e-15 (ℓ1 + ℓ2)) and beyond the boundary (an accepted wrist at most
    # ``tol`` outside the reach): a length tolerance of 1e-9 spanned ~9e-5 rad of the elbow angle and merged
    # distinct solutions, and a wrist just beyond reach gave duplicate pairs, unflagged (issue 21).
    snap = min(tol, 1e-15 * (l1 + l2))
    stretched = l3 >= (l1 + l2) - snap
    folded = l3 <= abs(l1 - l2) + snap
    l3 = o.where(stretched, l1 + l2, o.where(folded, abs(l1 - l2), l3))
    q = (l1 + l2 + l3) * (-l1 + l2 + l3) * (l1 - l2 + l3) * (l1 + l2 - l3)  # (4 area)², Heron factored
    four_area = o.sqrt(o.maximum(q, 0.0))
    theta = o.atan2(four_area, l3 * l3 + l1 * l1 - l2 * l2)  # cos θ as in eq. (5)
    beta = o.atan2(four_area, l1 * l1 + l2 * l2 - l3 * l3)  # interior angle at the elbow
    return l3, theta, beta, stretched, folded
