"""The PUMA-560's geometric Jacobian in closed form: a few dozen products per pose, no frames formed.

The reference point is the origin of frame {6}, the wrist centre w (frames {4}, {5}, {6} share it),
so the joints of the wrist move no point of it and the Jacobian is block triangular (lecture 09). With
c1 = cos θ1, c23 = cos(θ2 + θ3), ... and the lengths of the table:

    v = a3 c23 - d4 s23,   h = -a3 s23 - d4 c23      (the forearm, {3} to w, in the arm plane)
    u = a2 c2 + v,         w = (c1 u - d3 s1, s1 u + d3 c1, h - a2 s2)

    z1 = (0, 0, 1),   z2 = z3 = (-s1, c1, 0),   z4 = (-c1 s23, -s1 s23, -c23),
    z5 = (c1 c23 s4 - s1 c4, s1 c23 s4 + c1 c4, -s23 s4),   z6 = third column of ^0R_6 (eq. 3.14),

    J_v = [ z1 × w,  z2 × w,  z3 × (w - p3),  0, 0, 0 ]
        = [ (-w_y, w_x, 0),  (c1 w_z, s1 w_z, -u),  (c1 h, s1 h, -v),  0, 0, 0 ],
    J_ω = [ z1, z2, z3, z4, z5, z6 ].

Derived by hand from the table, checked with sympy against the derivatives of the symbolic fk and
against :func:`~.jacobian.geometric_jacobian` (the column walk for any DH chain) in the tests. The
formulas are written once (``o`` is :data:`~._ops.SCALAR` for one pose, :data:`~._ops.ARRAY` for a
batch), as the closed-form fk and ik are.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ._ops import ARRAY, SCALAR

__all__ = ["puma560_jacobian_rows"]


def puma560_jacobian_rows(
    o: Any, q: list[Any], a2: float, a3: float, d3: float, d4: float
) -> tuple[Any, ...]:
    """The 36 entries of J row by row (v then ω): floats or (N,) arrays (the constant ``0.0``/``1.0`` stay floats).

    >>> J = puma560_jacobian_rows(SCALAR, [0.0] * 6, 0.4318, 0.0203, 0.15005, 0.4318)
    >>> [round(x, 5) + 0.0 for x in J[:6]]  # at qz the wrist centre is (a2 + a3, d3, -d4)
    [-0.15005, -0.4318, -0.4318, 0.0, 0.0, 0.0]
    """
    c1, s1, c2, s2 = o.cos(q[0]), o.sin(q[0]), o.cos(q[1]), o.sin(q[1])
    c4, s4, c5, s5 = o.cos(q[3]), o.sin(q[3]), o.cos(q[4]), o.sin(q[4])
    t23 = q[1] + q[2]
    c23, s23 = o.cos(t23), o.sin(t23)
    v = a3 * c23 - d4 * s23
    h = -a3 * s23 - d4 * c23
    u = a2 * c2 + v
    wx, wy, wz = c1 * u - d3 * s1, s1 * u + d3 * c1, h - a2 * s2
    g = c23 * c4 * s5 + s23 * c5
    c23s4 = c23 * s4
    return (
        -wy, c1 * wz, c1 * h, 0.0, 0.0, 0.0,
        wx, s1 * wz, s1 * h, 0.0, 0.0, 0.0,
        0.0, -u, -v, 0.0, 0.0, 0.0,
        0.0, -s1, -s1, -c1 * s23, c1 * c23s4 - s1 * c4, -c1 * g - s1 * s4 * s5,
        0.0, c1, c1, -s1 * s23, s1 * c23s4 + c1 * c4, -s1 * g + c1 * s4 * s5,
        1.0, 0.0, 0.0, -c23, -s23 * s4, s23 * c4 * s5 - c23 * c5,
    )  # fmt: skip


def puma560_jacobian(cols: list[Any], batch: int | None, lengths: tuple[float, float, float, float]) -> np.ndarray:
    """J (6, 6) for one pose (``cols`` six floats, ``batch`` None) or (N, 6, 6) for six (N,) arrays.

    ``cols`` comes validated (:func:`~.dh.split_q`); nothing here checks it again.
    """
    if batch is None:
        return np.fromiter(puma560_jacobian_rows(SCALAR, cols, *lengths), float, 36).reshape(6, 6)
    J = np.zeros((batch, 6, 6))
    for k, value in enumerate(puma560_jacobian_rows(ARRAY, cols, *lengths)):
        if not isinstance(value, float) or value != 0.0:  # the constant zeros are already there
            J[:, k // 6, k % 6] = value
    return J
