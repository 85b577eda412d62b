"""Porter's direct problem: the pose F05 and the frames F0..F5 of the chain.

Local-frame product (moving axes, right-multiplied; checked in the tests against the source's
scene-frame product and its printed p5):

    F05 = Rz(α1) Tz(l1) Ry(α2) Tx(q2) Ry(α3) Tz(-l3) Rz(α4) Tx(l4) Rx(α5)

The printed local product leaves out Tx(q2); the printed p5 (whose entries contain
q2 - s3 l3 + c3 c4 l4) puts it between Ry(α2) and Ry(α3).
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["fk_entries", "frames_array"]


def fk_entries(o: Any, q: list[Any], l1: float, l3: float, l4: float) -> tuple[Any, ...]:
    """F05 as 12 entries (rows of R | p) for q = (α1, α2, q2, α3, α4, α5); floats or arrays (``o``: ops)."""
    a1, a2, q2, a3, a4, a5 = q
    c1, s1, c2, s2 = o.cos(a1), o.sin(a1), o.cos(a2), o.sin(a2)
    c4, s4, c5, s5 = o.cos(a4), o.sin(a4), o.cos(a5), o.sin(a5)
    c23, s23 = o.cos(a2 + a3), o.sin(a2 + a3)
    # x3 = c23 u - s23 z0 with u = (c1, s1, 0) the radial direction of the arm plane, y1 = (-s1, c1, 0)
    x5x, x5y, x5z = c4 * c23 * c1 - s4 * s1, c4 * c23 * s1 + s4 * c1, -c4 * s23  # x5 = x4 = c4 x3 + s4 y1
    y4x, y4y, y4z = -s4 * c23 * c1 - c4 * s1, -s4 * c23 * s1 + c4 * c1, s4 * s23  # y4 = -s4 x3 + c4 y1
    z3x, z3y, z3z = s23 * c1, s23 * s1, c23  # z4 = z3 = s23 u + c23 z0
    r = q2 * c2 - l3 * s23  # radial coordinate of p4; p5 = p2 + q2 x2 - l3 z3 + l4 x5
    return (
        x5x, c5 * y4x + s5 * z3x, -s5 * y4x + c5 * z3x, r * c1 + l4 * x5x,
        x5y, c5 * y4y + s5 * z3y, -s5 * y4y + c5 * z3y, r * s1 + l4 * x5y,
        x5z, c5 * y4z + s5 * z3z, -s5 * y4z + c5 * z3z, l1 - q2 * s2 - l3 * c23 + l4 * x5z,
    )  # fmt: skip


def frames_array(q: np.ndarray, l1: float, l3: float, l4: float) -> np.ndarray:
    """Frames F0..F5 for validated q (..., 6): (..., 6, 4, 4), each mapping its coordinates into the scene.

    F1 = Rz(α1), F2 = F1 Tz(l1) Ry(α2), F3 = F2 Tx(q2) Ry(α3), F4 = F3 Tz(-l3) Rz(α4),
    F5 = F4 Tx(l4) Rx(α5); their origins are Porter's points p0 = p1, p2, ..., p5.
    """
    a1, a2, q2, a3, a4, a5 = np.moveaxis(q, -1, 0)
    c1, s1, c2, s2 = np.cos(a1), np.sin(a1), np.cos(a2), np.sin(a2)
    c4, s4, c5, s5 = np.cos(a4), np.sin(a4), np.cos(a5), np.sin(a5)
    c23, s23 = np.cos(a2 + a3), np.sin(a2 + a3)
    zero = np.zeros_like(c1)
    u = np.stack([c1, s1, zero], axis=-1)  # radial direction of the arm plane
    y1 = np.stack([-s1, c1, zero], axis=-1)  # the axis of α2 and α3
    ez = np.broadcast_to(np.array([0.0, 0.0, 1.0]), u.shape)

    def arm(a: np.ndarray, b: np.ndarray) -> np.ndarray:  # a u + b z0, a vector of the arm plane
        return a[..., None] * u + b[..., None] * ez

    x2, z2 = arm(c2, -s2), arm(s2, c2)
    x3, z3 = arm(c23, -s23), arm(s23, c23)
    x4 = c4[..., None] * x3 + s4[..., None] * y1
    y4 = -s4[..., None] * x3 + c4[..., None] * y1
    y5 = c5[..., None] * y4 + s5[..., None] * z3
    z5 = -s5[..., None] * y4 + c5[..., None] * z3
    p2 = l1 * ez
    p3 = p2 + q2[..., None] * x2
    p4 = p3 - l3 * z3
    F = np.zeros(q.shape[:-1] + (6, 4, 4))
    F[..., :, 3, 3] = 1.0
    F[..., 0, :3, :3] = np.eye(3)
    for k, (x, y, z, p) in enumerate(
        [(u, y1, ez, 0.0 * ez), (x2, y1, z2, p2), (x3, y1, z3, p3), (x4, y4, z3, p4), (x4, y5, z5, p4 + l4 * x4)],
        start=1,
    ):
        F[..., k, :3, 0], F[..., k, :3, 1], F[..., k, :3, 2], F[..., k, :3, 3] = x, y, z, p
    return F
