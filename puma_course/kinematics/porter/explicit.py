"""Porter's inverse problem, Ver.1 (explicit, eqs. 8-16, re-derived): every configuration reaching F05.

In the arm plane, with p4 = p5 - l4 x5 (eq. 17) and M1 = Rz(-α1) R:

* α1 = atan2(p4_2, p4_1) or that + π (eq. 9 with atan2: the "two values of arctan");
* s4 = M1[1, 0] (eq. 8), c4 = ±|(M1[0, 0], M1[2, 0])| (eq. 10: the two values of arcsin);
* α2 + α3 = atan2(-M1[2, 0] / c4, M1[0, 0] / c4) (eqs. 12, 16);
* α5 from Rx(α5) = Rz(-α4) Ry(-α23) M1 (eq. 11, exact even when α23 is poorly determined);
* q2 (c2, s2) = (r4 + l3 s23, l1 - p4_3 - l3 c23) with r4 = c1 p4_1 + s1 p4_2 (eqs. 13-15 without
  the division by c1 c2 c4, which is zero on whole families of poses).

Four branches, in the order :data:`BRANCH_LABELS`: the arm plane entered "front" (α1 towards p4)
or "back" (α1 + π), times the sign of c4. Porter's "eight" also counts q2 < 0. The back plane
is computed from the front one by exact negations (c1, s1 -> -c1, -s1), so both planes decide
every singular boundary (c4 = 0, q2 = 0) on the same numbers: they are classified together.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["BRANCH_LABELS", "PLANE", "SIGN", "pose_terms", "complete", "branch", "alpha1_simplest"]

BRANCH_LABELS = ("front/c4+", "front/c4-", "back/c4+", "back/c4-")
PLANE = np.array([1.0, 1.0, -1.0, -1.0])  # +1: α1 towards p4; -1: α1 + π
SIGN = np.array([1.0, -1.0, 1.0, -1.0])  # the sign of c4


def alpha1_simplest(o: Any, r11: Any, r21: Any) -> Any:
    """α1 for a free arm plane (p4 on the z0 axis): the plane containing x5 (so s4 = 0), else 0."""
    return o.where(o.hypot(r11, r21) > 1e-9, o.atan2(r21, r11), 0.0)


def pose_terms(o: Any, R: tuple[Any, ...], P: tuple[Any, ...], L: tuple[float, float, float], tol: float,
               near_a1: Any) -> tuple[Any, ...]:  # fmt: skip
    """Terms shared by the four branches of one pose (floats or arrays, ``o``: ops).

    Returns α1 (front plane), the arm-plane rotation entries (m00, m01, m10, m11, m20, m21), s4,
    |c4|, the planes-parallel flag, p4's arm-plane coordinates (r4, h = z - l1), the length scale
    and the p4-on-the-axis flag. ``tol`` is relative to l1 + l3 + l4 + |p5| for lengths and
    absolute for c4.
    """
    r11, r12, _, r21, r22, _, r31, r32, _ = R
    px, py, pz = P
    l1, l3, l4 = L
    scale = l1 + l3 + l4 + o.hypot(px, o.hypot(py, pz))
    p4x, p4y, p4z = px - l4 * r11, py - l4 * r21, pz - l4 * r31  # eq. 17: p4 = p5 - l4 x5
    on_axis = o.hypot(p4x, p4y) <= tol * scale
    free = alpha1_simplest(o, r11, r21) if near_a1 is None else near_a1
    a1 = o.where(on_axis, free, o.atan2(p4y, p4x))  # eq. 9 with atan2
    c1, s1 = o.cos(a1), o.sin(a1)
    m00, m01 = c1 * r11 + s1 * r21, c1 * r12 + s1 * r22
    m10, m11 = -s1 * r11 + c1 * r21, -s1 * r12 + c1 * r22
    c4a = o.hypot(m00, r31)
    parallel = c4a <= tol
    r4, h = c1 * p4x + s1 * p4y, p4z - l1
    return a1, (m00, m01, m10, m11, r31, r32), m10, c4a, parallel, r4, h, scale, on_axis


def complete(o: Any, m: tuple[Any, ...], a23: Any, s4: Any, c4: Any, r4: Any, h: Any, l3: float) -> tuple[Any, ...]:
    """Given α23 = α2 + α3 (and s4, c4, p4's plane coordinates): α5 (eq. 11), q2 and α2 (eq. 13).

    Also the representatives' formula for a singular family, where α23 is a free parameter.
    """
    m00, m01, _, m11, _, m21 = m
    c23, s23 = o.cos(a23), o.sin(a23)
    b0, b2 = c23 * m01 - s23 * m21, s23 * m01 + c23 * m21  # (Ry(-α23) M1)[0, 1], [2, 1]
    a5 = o.atan2(b2, -s4 * b0 + c4 * m11)
    c2q2, s2q2 = r4 + l3 * s23, -(h + l3 * c23)
    return a5, o.hypot(c2q2, s2q2), o.atan2(s2q2, c2q2)


def branch(o: Any, terms: tuple[Any, ...], plane: Any, sign: Any, l3: float, tol: float) -> tuple[Any, ...]:
    """One branch (``plane`` ±1, ``sign`` of c4 ±1): the configuration and its singular flags.

    Boundaries are snapped: at c4 = 0 (planes parallel) c4 is exactly 0 and α23 follows Porter's
    rule (minimal q2: z3 = -(p4 - p2)/|p4 - p2|); at q2 = 0 q2 is exactly 0 and α2 = 0 (only
    α2 + α3 is fixed there).
    """
    a1, m, s4, c4a, parallel, r4, h, scale, _ = terms
    m00, m01, m10, m11, m20, m21 = m
    M = (plane * m00, plane * m01, plane * m10, plane * m11, m20, m21)  # the back plane: rows 0, 1 negated exactly
    S4, R4 = plane * s4, plane * r4
    c4 = o.where(parallel, 0.0, sign * c4a)
    S4 = o.where(parallel, o.where(S4 >= 0, 1.0, -1.0), S4)
    a4 = o.atan2(S4, c4)
    rule = o.where(o.hypot(R4, h) > tol * scale, o.atan2(-R4, -h), 0.0)
    a23 = o.where(parallel, rule, o.atan2(-sign * m20, sign * M[0]))  # eqs. 12, 16
    a5, q2, a2 = complete(o, M, a23, S4, c4, R4, h, l3)
    q2zero = q2 <= tol * scale
    a2 = o.where(q2zero, 0.0, a2)
    q2 = o.where(q2zero, 0.0, q2)
    return (o.where(plane > 0, a1, a1 + math.pi), a2, q2, a23 - a2, a4, a5), parallel, q2zero
