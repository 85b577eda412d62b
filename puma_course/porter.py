"""Porter's PUMA-like chain: direct problem, inverse Ver.1 (explicit) and Ver.2 (geometric).

Source: J. Porter, "PUMA". One prismatic and five revolute joints; the
configuration is ``q = (α1, α2, q2, α3, α4, α5)`` with ``0 <= αi < 2π`` and
``q2 >= 0``; the constant lengths are ``l1, l3, l4`` (unitless).

Local-frame product (moving axes, right-multiplied; this module's definition,
checked against the source's scene-frame product and its printed ``p5``)::

    F05 = Rz(α1) Tz(l1) Ry(α2) Tx(q2) Ry(α3) Tz(-l3) Rz(α4) Tx(l4) Rx(α5)

The printed local product leaves out ``Tx(q2)``; the printed ``p5`` (whose
entries contain ``q2 - s3 l3 + c3 c4 l4``) puts it between ``Ry(α2)`` and
``Ry(α3)``.

Frames (:func:`frames`), each a 4x4 mapping its coordinates into the scene:

* F0 = I (scene, origin p0);
* F1 = Rz(α1) (origin p1 = p0; y1 is the axis of α2 and α3);
* F2 = F1 Tz(l1) Ry(α2) (origin p2 = l1 z0; x2 is the prismatic axis);
* F3 = F2 Tx(q2) Ry(α3) (origin p3 = p2 + q2 x2);
* F4 = F3 Tz(-l3) Rz(α4) (origin p4 = p3 - l3 z3, z4 = z3 is the axis of α4);
* F5 = F4 Tx(l4) Rx(α5) (origin p5 = p4 + l4 x4, x5 = x4 is the axis of α5).

Solution count: every pose is reachable (q2 has no upper bound) and, in
general position, has exactly **four** configurations with ``q2 >= 0``: two
arm planes (α1 and α1 + π) times two elbow points p3 = p4 ± l3 z4. Porter's
"eight" counts both signs of q2 (the second value of arctan in eq. 14).

Singular cases (reported by :func:`classify`, a :class:`PorterSingularityWarning`
and :class:`IKResult`): ``"p4_on_z0_axis"`` (α1 free), ``"planes_parallel"``
(c4 = 0: only α2 + α3 ± α5 is fixed), ``"q2_zero"`` (p3 = p2: only α2 + α3
is fixed). One representative per branch is returned: the configuration nearest
``near`` when given, else Porter's rule (minimal q2 for parallel planes) and the
"simplest" choice (α1 with s4 = 0, α2 = 0) for the others.

Unreachable poses: none without a stroke limit. With ``q2_max=`` the IK functions
return an empty (0, 6) array and emit :class:`PorterUnreachableWarning` (``solve``:
``success`` False and a ``reason``); never NaN, never a ValueError for a valid pose.
Invalid input (T not a 4x4 rigid transform, NaN, lengths <= 0) raises ``ValueError``.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import Any

import numpy as np

from ._validate import as_array, as_positive, as_transform
from .transforms import wrap_angle

__all__ = [
    "fk",
    "frames",
    "points",
    "ik_explicit",
    "ik_explicit_batch",
    "ik_geometric",
    "solve",
    "classify",
    "nearest",
    "sort_by_distance",
    "config_distance",
    "wrap_config",
    "angle",
    "IKResult",
    "PorterSingularityWarning",
    "PorterUnreachableWarning",
    "AXIS",
    "PARALLEL",
    "Q2_ZERO",
    "CASES",
]

TWO_PI = 2.0 * np.pi
ANGLES = np.array([0, 1, 3, 4, 5])  # indices of the revolute joints in q

AXIS = "p4_on_z0_axis"
PARALLEL = "planes_parallel"
Q2_ZERO = "q2_zero"
CASES = {
    AXIS: "p4 lies on the z0 axis: the arm plane, hence α1, is free (eq. 9 gives 0/0)",
    PARALLEL: "x5 is normal to the arm plane (c4 = 0, n024 ∥ x5): eqs. 11, 12, 14, 15 divide by c4 = 0; "
    "only α2 + α3 + α5 (s4 = 1) or α2 + α3 - α5 (s4 = -1) is fixed",
    Q2_ZERO: "q2 = 0 (p3 = p2): the prismatic axis, hence α2, is free; only α2 + α3 is fixed",
}
_BITS = {AXIS: 1, PARALLEL: 2, Q2_ZERO: 4}
TOL = 1e-12  # relative tolerance deciding "exactly singular" (lengths are scaled by l1 + l3 + l4 + |p5|)


class PorterSingularityWarning(UserWarning):
    """The pose is at a singular case of Porter's chain; a representative configuration was chosen."""


class PorterUnreachableWarning(UserWarning):
    """No configuration reaches the pose (only possible with a stroke limit ``q2_max``)."""


# --------------------------------------------------------------------------- direct problem


def _lengths(l1: Any, l3: Any, l4: Any) -> tuple[float, float, float]:
    return as_positive(l1, "l1"), as_positive(l3, "l3"), as_positive(l4, "l4")


def _q(q: Any) -> np.ndarray:
    q = as_array(q, "q", (6,), batch=True, what="a configuration (α1, α2, q2, α3, α4, α5) of shape (6,) or (N, 6)")
    return q


def _frames(q: np.ndarray, l1: float, l3: float, l4: float) -> np.ndarray:
    """Frames F0..F5 for q (..., 6) -> (..., 6, 4, 4); no validation."""
    a1, a2, q2, a3, a4, a5 = np.moveaxis(q, -1, 0)
    c1, s1 = np.cos(a1), np.sin(a1)
    c2, s2 = np.cos(a2), np.sin(a2)
    c4, s4 = np.cos(a4), np.sin(a4)
    c5, s5 = np.cos(a5), np.sin(a5)
    a23 = a2 + a3
    c23, s23 = np.cos(a23), np.sin(a23)
    F = np.zeros(q.shape[:-1] + (6, 4, 4))
    F[..., :, 3, 3] = 1.0
    F[..., 0, :3, :3] = np.eye(3)
    # F1 = Rz(α1)
    y1 = np.stack([-s1, c1, np.zeros_like(c1)], axis=-1)
    u = np.stack([c1, s1, np.zeros_like(c1)], axis=-1)  # radial direction of the arm plane
    ez = np.broadcast_to(np.array([0.0, 0.0, 1.0]), u.shape)
    F[..., 1, :3, 0], F[..., 1, :3, 1], F[..., 1, :3, 2] = u, y1, ez

    def arm(a: np.ndarray, b: np.ndarray) -> np.ndarray:  # a u + b z0 (a vector of the arm plane)
        return a[..., None] * u + b[..., None] * ez

    # F2 = F1 Tz(l1) Ry(α2): x2 = c2 u - s2 z, z2 = s2 u + c2 z
    x2, z2 = arm(c2, -s2), arm(s2, c2)
    p2 = l1 * ez
    F[..., 2, :3, 0], F[..., 2, :3, 1], F[..., 2, :3, 2], F[..., 2, :3, 3] = x2, y1, z2, p2
    # F3 = F2 Tx(q2) Ry(α3)
    x3, z3 = arm(c23, -s23), arm(s23, c23)
    p3 = p2 + q2[..., None] * x2
    F[..., 3, :3, 0], F[..., 3, :3, 1], F[..., 3, :3, 2], F[..., 3, :3, 3] = x3, y1, z3, p3
    # F4 = F3 Tz(-l3) Rz(α4)
    x4 = c4[..., None] * x3 + s4[..., None] * y1
    y4 = -s4[..., None] * x3 + c4[..., None] * y1
    p4 = p3 - l3 * z3
    F[..., 4, :3, 0], F[..., 4, :3, 1], F[..., 4, :3, 2], F[..., 4, :3, 3] = x4, y4, z3, p4
    # F5 = F4 Tx(l4) Rx(α5)
    y5 = c5[..., None] * y4 + s5[..., None] * z3
    z5 = -s5[..., None] * y4 + c5[..., None] * z3
    F[..., 5, :3, 0], F[..., 5, :3, 1], F[..., 5, :3, 2], F[..., 5, :3, 3] = x4, y5, z5, p4 + l4 * x4
    return F


def frames(q: Any, l1: Any, l3: Any, l4: Any) -> np.ndarray:
    """The frames F0..F5 of the chain (scene coordinates), (6, 4, 4) or (N, 6, 4, 4).

    F1 = Rz(α1), F2 = F1 Tz(l1) Ry(α2), F3 = F2 Tx(q2) Ry(α3),
    F4 = F3 Tz(-l3) Rz(α4), F5 = F4 Tx(l4) Rx(α5); origins p0 = p1, p2, ..., p5
    (Porter's Fig. 1 points). Draw with ``plotting.draw_chain(ax, frames(q, ...))``.

    >>> F = frames([0, 0, 1, 0, 0, 0], 1, 1, 1)
    >>> F[:, :3, 3]
    array([[0., 0., 0.],
           [0., 0., 0.],
           [0., 0., 1.],
           [1., 0., 1.],
           [1., 0., 0.],
           [2., 0., 0.]])
    """
    q = _q(q)
    l1, l3, l4 = _lengths(l1, l3, l4)
    return _frames(q, l1, l3, l4)


def points(q: Any, l1: Any, l3: Any, l4: Any) -> np.ndarray:
    """The joint points p0..p5 (p1 = p0), (6, 3) or (N, 6, 3).

    >>> points([0, 0, 1, 0, 0, 0], 1, 1, 1)[-1]
    array([2., 0., 0.])
    """
    return frames(q, l1, l3, l4)[..., :3, 3]


def fk(q: Any, l1: Any, l3: Any, l4: Any) -> np.ndarray:
    """Direct problem: F05 = Rz(α1) Tz(l1) Ry(α2) Tx(q2) Ry(α3) Tz(-l3) Rz(α4) Tx(l4) Rx(α5).

    Maps coordinates of the end-effector frame F5 into the scene frame F0
    (Porter's eq. 6 with the corrected local-frame product). q (6,) -> (4, 4),
    (N, 6) -> (N, 4, 4), vectorised.

    >>> np.round(fk([0, 0, 2, 0, 0, 0], l1=1, l3=0.5, l4=0.25), 12) + 0.0
    array([[1.  , 0.  , 0.  , 2.25],
           [0.  , 1.  , 0.  , 0.  ],
           [0.  , 0.  , 1.  , 0.5 ],
           [0.  , 0.  , 0.  , 1.  ]])
    """
    q = _q(q)
    l1, l3, l4 = _lengths(l1, l3, l4)
    return _fk(q, l1, l3, l4)


def _fk(q: np.ndarray, l1: float, l3: float, l4: float) -> np.ndarray:
    """F05 only (closed form of the corrected product), q (..., 6) -> (..., 4, 4); no validation."""
    a1, a2, q2, a3, a4, a5 = np.moveaxis(q, -1, 0)
    c1, s1, c2, s2 = np.cos(a1), np.sin(a1), np.cos(a2), np.sin(a2)
    c4, s4, c5, s5 = np.cos(a4), np.sin(a4), np.cos(a5), np.sin(a5)
    c23, s23 = np.cos(a2 + a3), np.sin(a2 + a3)
    T = np.zeros(q.shape[:-1] + (4, 4))
    x3u, x3z = c23, -s23  # x3 = c23 u - s23 z0 (u = (c1, s1, 0) radial, y1 = (-s1, c1, 0))
    # x5 = x4 = c4 x3 + s4 y1
    x5x, x5y, x5z = c4 * x3u * c1 - s4 * s1, c4 * x3u * s1 + s4 * c1, c4 * x3z
    # y4 = -s4 x3 + c4 y1, z4 = z3 = s23 u + c23 z0
    y4x, y4y, y4z = -s4 * x3u * c1 - c4 * s1, -s4 * x3u * s1 + c4 * c1, -s4 * x3z
    z3x, z3y, z3z = s23 * c1, s23 * s1, c23
    T[..., 0, 0], T[..., 1, 0], T[..., 2, 0] = x5x, x5y, x5z
    T[..., 0, 1], T[..., 1, 1], T[..., 2, 1] = c5 * y4x + s5 * z3x, c5 * y4y + s5 * z3y, c5 * y4z + s5 * z3z
    T[..., 0, 2], T[..., 1, 2], T[..., 2, 2] = -s5 * y4x + c5 * z3x, -s5 * y4y + c5 * z3y, -s5 * y4z + c5 * z3z
    # p5 = p2 + q2 x2 - l3 z3 + l4 x5, x2 = c2 u - s2 z0
    r = q2 * c2 - l3 * s23  # radial coordinate of p4
    T[..., 0, 3] = r * c1 + l4 * x5x
    T[..., 1, 3] = r * s1 + l4 * x5y
    T[..., 2, 3] = l1 - q2 * s2 - l3 * c23 + l4 * x5z
    T[..., 3, 3] = 1.0
    return T


# --------------------------------------------------------------------------- helpers on configurations


def _configs(q: Any, name: str) -> np.ndarray:
    q = as_array(q, name, what="configurations of shape (..., 6)")
    if q.ndim == 0 or q.shape[-1] != 6:
        raise ValueError(f"{name}: expected configurations of shape (..., 6), got an array of shape {q.shape}")
    return q


def wrap_config(q: Any) -> np.ndarray:
    """Angles of q (..., 6) wrapped into [0, 2π); q2 unchanged.

    >>> wrap_config([-np.pi / 2, 7.0, 1.5, 0, 0, 2 * np.pi])[[0, 5]].round(6)
    array([4.712389, 0.      ])
    """
    return _wrap(_configs(q, "q"))


def _wrap(q: np.ndarray) -> np.ndarray:
    q = np.array(q, dtype=float)
    a = np.mod(q[..., ANGLES], TWO_PI)
    a[a >= TWO_PI] = 0.0  # np.mod(-1e-17, 2π) rounds to 2π
    q[..., ANGLES] = a
    return q


def _wrap_pi(a: np.ndarray) -> np.ndarray:
    return (np.asarray(a) + np.pi) % TWO_PI - np.pi


def config_distance(qa: Any, qb: Any) -> np.ndarray:
    """Distance between configurations: Euclidean, angle differences wrapped to [-π, π).

    >>> float(config_distance([0.1, 0, 1, 0, 0, 0], [2 * np.pi - 0.1, 0, 1, 0, 0, 0])).__round__(12)
    0.2
    """
    return _dist(_configs(qa, "qa"), _configs(qb, "qb"))


def _dist(qa: np.ndarray, qb: np.ndarray) -> np.ndarray:
    d = qa - qb
    d[..., ANGLES] = wrap_angle(d[..., ANGLES])  # ±π give the same distance either way
    return np.sqrt(np.sum(d * d, axis=-1))


def sort_by_distance(solutions: Any, q_ref: Any) -> np.ndarray:
    """The rows of ``solutions`` (k, 6) sorted by :func:`config_distance` to ``q_ref``, nearest first."""
    S = as_array(solutions, "solutions", (6,), batch=True).reshape(-1, 6)
    if len(S) == 0:
        return S
    return S[np.argsort(_dist(S, _configs(q_ref, "q_ref")), kind="stable")]


def nearest(solutions: Any, q_ref: Any) -> np.ndarray:
    """The configuration among ``solutions`` (k, 6) nearest to ``q_ref`` (wrapped-angle distance).

    Raises ValueError when there is no solution to choose from.

    >>> nearest([[0, 0, 1, 0, 0, 0], [np.pi, 0, 1, 0, 0, 0]], [3.0, 0, 1, 0, 0, 0]).round(6)
    array([3.141593, 0.      , 1.      , 0.      , 0.      , 0.      ])
    """
    S = as_array(solutions, "solutions", (6,), batch=True).reshape(-1, 6)
    if len(S) == 0:
        raise ValueError("solutions: expected at least one configuration to choose from, got none (unreachable pose)")
    return sort_by_distance(S, q_ref)[0]


def _dedupe(S: np.ndarray, tol: float = 1e-9) -> np.ndarray:
    D = _dist(S[:, None, :], S[None, :, :])
    dup = np.any(np.tril(D <= tol, k=-1), axis=1)  # equal to an earlier row
    return S[~dup]


# --------------------------------------------------------------------------- Ver.1 core (batched)


def _complete(
    M1: np.ndarray, a23: np.ndarray, s4: np.ndarray, c4: np.ndarray, r4: np.ndarray, h: np.ndarray, l3: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Given the arm-plane rotation M1 = Rz(-α1) R, α23, (s4, c4) and p4's arm-plane coordinates
    (r4 radial, h = z - l1): return α5, q2, α2 (unresolved when q2 = 0) and the raw (c2 q2, s2 q2).

    α5 comes from the residual Rx(α5) = Rz(-α4) Ry(-α23) M1 (exact even when α23 is poorly
    determined near c4 = 0). Position, rotated-frame form of eq. 13 (no division by c1 c2 c4):
    c2 q2 = r4 + l3 s23 and s2 q2 = -(h + l3 c23).
    """
    c23, s23 = np.cos(a23), np.sin(a23)
    m01, m11, m21 = M1[..., 0, 1], M1[..., 1, 1], M1[..., 2, 1]
    b0 = c23 * m01 - s23 * m21  # (Ry(-α23) M1)[0, 1]
    b2 = s23 * m01 + c23 * m21  # (Ry(-α23) M1)[2, 1]
    a5 = np.arctan2(b2, -s4 * b0 + c4 * m11)
    c2q2 = r4 + l3 * s23
    s2q2 = -(h + l3 * c23)
    q2 = np.hypot(c2q2, s2q2)
    a2 = np.arctan2(s2q2, c2q2)
    return a5, q2, a2, np.stack([c2q2, s2q2], axis=-1)


def _scale(p: np.ndarray, l1: float, l3: float, l4: float) -> np.ndarray:
    return l1 + l3 + l4 + np.linalg.norm(p, axis=-1)


def _alpha1_simplest(R: np.ndarray) -> np.ndarray:
    """α1 for a free arm plane: the one with s4 = 0 (x5 in the arm plane), else 0."""
    x5 = R[..., :, 0]
    rho = np.hypot(x5[..., 0], x5[..., 1])
    return np.where(rho > 1e-9, np.arctan2(x5[..., 1], x5[..., 0]), 0.0)


def _ver1_batch(
    R: np.ndarray,
    p: np.ndarray,
    l1: float,
    l3: float,
    l4: float,
    alpha1: np.ndarray | None = None,
    tol: float = TOL,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Ver.1 for N poses: (N, 4, 6) configurations (unwrapped), (N, 4) flag bits, (N, 4, 2) w = (c2 q2, s2 q2).

    Branch order: (α1, c4 > 0), (α1, c4 < 0), (α1 + π, c4 > 0), (α1 + π, c4 < 0).
    ``alpha1`` (N,) overrides α1 where it is finite (used for the free arm plane).
    """
    N = R.shape[0]
    L = _scale(p, l1, l3, l4)
    p4 = p - l4 * R[..., :, 0]  # eq. 17: p4 = p5 - l4 x5
    rxy = np.hypot(p4[:, 0], p4[:, 1])
    on_axis = rxy <= tol * L
    a1 = np.arctan2(p4[:, 1], p4[:, 0])  # eq. 9 with arctan2
    a1 = np.where(on_axis, _alpha1_simplest(R), a1)
    if alpha1 is not None:
        a1 = np.where(np.isfinite(alpha1) & on_axis, alpha1, a1)
    A1 = np.stack([a1, a1 + np.pi], axis=1)  # (N, 2): the two values of arctan
    c1, s1 = np.cos(A1), np.sin(A1)
    # M1 = Rz(-α1) R: rows 0 and 1 rotated
    M1 = np.empty((N, 2, 3, 3))
    M1[..., 0, :] = c1[..., None] * R[:, None, 0, :] + s1[..., None] * R[:, None, 1, :]
    M1[..., 1, :] = -s1[..., None] * R[:, None, 0, :] + c1[..., None] * R[:, None, 1, :]
    M1[..., 2, :] = R[:, None, 2, :]
    s4 = M1[..., 1, 0]  # eq. 8 / 10: s4 = c1 x5_2 - s1 x5_1
    c4a = np.hypot(M1[..., 0, 0], M1[..., 2, 0])  # |c4|
    parallel = c4a <= tol
    r4 = c1 * p4[:, None, 0] + s1 * p4[:, None, 1]
    h = p4[:, None, 2] - l1 + 0.0 * r4
    sg = np.array([1.0, -1.0])
    c4 = c4a[..., None] * sg  # (N, 2, 2): the two values of arcsin (α4 and π - α4)
    s4b = s4[..., None]
    a4 = np.arctan2(s4b, c4)
    # eq. 12/16: c23 c4 = c1 x5_1 + s1 x5_2 = M1[0,0], s23 c4 = -x5_3 = -M1[2,0]
    a23 = np.arctan2(-sg * M1[..., 2, 0][..., None], sg * M1[..., 0, 0][..., None])
    if np.any(parallel):
        # planes parallel (c4 = 0): Porter's rule, minimal q2: z3 = -(p4 - p2)/|p4 - p2| in the arm plane
        dn = np.hypot(r4, h)
        a23_rule = np.where(dn > tol * L[:, None], np.arctan2(-r4, -h), 0.0)
        a23 = np.where(parallel[..., None], a23_rule[..., None], a23)
    a5, q2, a2, w = _complete(M1[:, :, None], a23, s4b, c4, r4[..., None], h[..., None], l3)
    q2zero = q2 <= tol * L[:, None, None]
    a2 = np.where(q2zero, 0.0, a2)  # the simplest representative: α2 = 0
    Q = np.empty((N, 2, 2, 6))
    Q[..., 0] = A1[..., None]
    Q[..., 1], Q[..., 2], Q[..., 3], Q[..., 4], Q[..., 5] = a2, q2, a23 - a2, a4, a5
    flags = np.zeros((N, 2, 2), dtype=int)
    flags += (on_axis[:, None, None] * _BITS[AXIS] + parallel[..., None] * _BITS[PARALLEL]).astype(int)
    flags += q2zero * _BITS[Q2_ZERO]
    return Q.reshape(N, 4, 6), flags.reshape(N, 4), w.reshape(N, 4, 2)


def _ver1_scalar(T: list, l1: float, l3: float, l4: float, tol: float = TOL) -> list | None:
    """The same formulas as :func:`_ver1_batch` for one pose in plain floats (fast path).

    Returns the four configurations, or None when the pose is within ``tol`` of a singular
    case (then the batched path, which holds the representative rules, is used).
    """
    (r00, r01, _, px), (r10, r11, _, py), (r20, r21, _, pz) = T[0], T[1], T[2]
    L = l1 + l3 + l4 + math.sqrt(px * px + py * py + pz * pz)
    p4x, p4y, p4z = px - l4 * r00, py - l4 * r10, pz - l4 * r20
    if math.hypot(p4x, p4y) <= tol * L:
        return None
    out = []
    base = math.atan2(p4y, p4x)
    h = p4z - l1
    for a1 in (base, base + math.pi):
        c1, s1 = math.cos(a1), math.sin(a1)
        m00, m01 = c1 * r00 + s1 * r10, c1 * r01 + s1 * r11
        m10, m11 = -s1 * r00 + c1 * r10, -s1 * r01 + c1 * r11
        m20, m21 = r20, r21
        c4a = math.hypot(m00, m20)
        if c4a <= tol:
            return None
        s4 = m10
        r4 = c1 * p4x + s1 * p4y
        for sg in (1.0, -1.0):
            c4 = sg * c4a
            a4 = math.atan2(s4, c4)
            a23 = math.atan2(-sg * m20, sg * m00)
            c23, s23 = math.cos(a23), math.sin(a23)
            b0 = c23 * m01 - s23 * m21
            b2 = s23 * m01 + c23 * m21
            a5 = math.atan2(b2, -s4 * b0 + c4 * m11)
            c2q2, s2q2 = r4 + l3 * s23, -(h + l3 * c23)
            q2 = math.hypot(c2q2, s2q2)
            if q2 <= tol * L:
                return None
            a2 = math.atan2(s2q2, c2q2)
            out.append((a1, a2, q2, a23 - a2, a4, a5))
    return out


def ik_explicit_batch(T: Any, l1: Any, l3: Any, l4: Any) -> tuple[np.ndarray, np.ndarray]:
    """Ver.1 for a batch of poses: (N, 4, 6) configurations and (N, 4) singular-case bit flags.

    Vectorised (no loop over N). Branch j of pose i: α1 = atan2(p4) + π (j // 2), c4 sign
    (+, -)[j % 2]. Angles wrapped into [0, 2π); q2 >= 0. At singular cases the branches hold
    Porter's representatives (minimal q2, α2 = 0, α1 with s4 = 0) and may coincide; the flag
    bits are 1 = p4 on the z0 axis, 2 = planes parallel, 4 = q2 = 0 (0 = general position).

    >>> Q, flags = ik_explicit_batch(fk([[0.3, 0.2, 1.0, 0.4, 0.5, 0.6]], 1, 0.5, 0.3), 1, 0.5, 0.3)
    >>> Q.shape, flags.tolist()
    ((1, 4, 6), [[0, 0, 0, 0]])
    >>> bool(np.allclose(fk(Q[0], 1, 0.5, 0.3), fk([0.3, 0.2, 1.0, 0.4, 0.5, 0.6], 1, 0.5, 0.3)))
    True
    """
    l1, l3, l4 = _lengths(l1, l3, l4)
    T = as_transform(T, "T", batch=True)
    squeeze = T.ndim == 2
    T = T.reshape(-1, 4, 4)
    Q, flags, _ = _ver1_batch(T[:, :3, :3], T[:, :3, 3], l1, l3, l4)
    Q = wrap_config(Q)
    if squeeze:
        return Q[0], flags[0]
    return Q, flags


# --------------------------------------------------------------------------- results, classification


@dataclass
class IKResult:
    """Solutions of an inverse problem with a report: behaves like the (k, 6) array of solutions.

    ``singular`` names the singular cases met (keys of :data:`CASES`); ``reason`` explains them
    or why there is no solution; ``success`` is False only when no configuration reaches the pose.
    """

    solutions: np.ndarray
    singular: tuple[str, ...] = ()
    reason: str = ""
    method: str = "explicit"

    @property
    def success(self) -> bool:
        return len(self.solutions) > 0

    def __array__(self, dtype: Any = None, copy: Any = None) -> np.ndarray:
        return np.asarray(self.solutions, dtype=dtype)

    def __len__(self) -> int:
        return len(self.solutions)

    def __getitem__(self, item: Any) -> Any:
        return self.solutions[item]

    def __iter__(self):
        return iter(self.solutions)

    @property
    def shape(self) -> tuple[int, ...]:
        return self.solutions.shape


def _names(bits: int) -> tuple[str, ...]:
    return tuple(n for n, b in _BITS.items() if bits & b)


def _prepare(T: Any, l1: Any, l3: Any, l4: Any) -> tuple[np.ndarray, float, float, float]:
    l1, l3, l4 = _lengths(l1, l3, l4)
    T = as_transform(T, "T")
    return T, l1, l3, l4


def classify(T: Any, l1: Any, l3: Any, l4: Any, tol: float = TOL) -> list[str]:
    """Names of the singular cases of the pose T (empty list in general position).

    A case is listed when it affects at least one solution branch: ``"p4_on_z0_axis"``,
    ``"planes_parallel"``, ``"q2_zero"`` (descriptions in :data:`CASES`). ``tol`` is relative
    to l1 + l3 + l4 + |p5| for lengths and absolute for c4.

    >>> classify(fk([0, 0, 1, 0, 0, 0], 1, 1, 1), 1, 1, 1)
    []
    >>> classify(fk([0, 0, 1, 0, np.pi / 2, 0], 1, 1, 1), 1, 1, 1)
    ['planes_parallel']
    """
    T, l1, l3, l4 = _prepare(T, l1, l3, l4)
    _, flags, _ = _ver1_batch(T[None, :3, :3], T[None, :3, 3], l1, l3, l4, tol=tol)
    return list(_names(int(np.bitwise_or.reduce(flags[0]))))


def _refine_parallel(
    R: np.ndarray, p: np.ndarray, l1: float, l3: float, l4: float, a1: float, near: np.ndarray
) -> np.ndarray:
    """Planes-parallel family for the arm plane α1: the member nearest ``near`` (1-D search in α23)."""
    c1, s1 = np.cos(a1), np.sin(a1)
    Rz = np.array([[c1, s1, 0.0], [-s1, c1, 0.0], [0.0, 0.0, 1.0]])
    M1 = Rz @ R
    p4 = p - l4 * R[:, 0]
    r4, h = c1 * p4[0] + s1 * p4[1], p4[2] - l1
    s4 = float(np.sign(M1[1, 0])) or 1.0
    a4 = np.arctan2(s4, 0.0)

    def family(t: np.ndarray) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        z = 0.0 * t
        a5, q2, a2, _ = _complete(np.broadcast_to(M1, t.shape + (3, 3)), t, s4 + z, z, r4 + z, h + z, l3)
        return np.stack([a1 + 0 * t, a2, q2, t - a2, a4 + 0 * t, a5], axis=-1)

    grid = np.linspace(-np.pi, np.pi, 721)
    d = config_distance(family(grid), near)
    t0 = grid[int(np.argmin(d))]
    lo, hi = t0 - TWO_PI / 720, t0 + TWO_PI / 720
    g = (np.sqrt(5.0) - 1.0) / 2.0
    for _ in range(60):  # golden-section search
        m1, m2 = hi - g * (hi - lo), lo + g * (hi - lo)
        if config_distance(family(m1), near) < config_distance(family(m2), near):
            hi = m2
        else:
            lo = m1
    best = family(np.array(0.5 * (lo + hi)))
    # the member of minimal q2 (z3 = -(p4 - p2)/|p4 - p2|): when it has q2 = 0, α2 is free too
    # and the split rule may bring it nearer than any member with q2 > 0
    L = float(_scale(p, l1, l3, l4))
    if np.hypot(r4, h) > TOL * L:
        cand = family(np.array(np.arctan2(-r4, -h)))
        if cand[2] <= TOL * L:
            cand = _split_q2zero(cand, near)
        if config_distance(cand, near) < config_distance(best, near):
            best = cand
    return best


def _split_q2zero(q: np.ndarray, near: np.ndarray) -> np.ndarray:
    """q2 = 0: only α23 = α2 + α3 is fixed; share the wrapped difference to ``near`` equally."""
    q = q.copy()
    a23 = q[1] + q[3]
    e = float(_wrap_pi(a23 - near[1] - near[3]))
    q[1] = near[1] + e / 2.0
    q[3] = a23 - q[1]
    return q


def _finish(
    S: np.ndarray,
    bits: int,
    T: np.ndarray,
    l1: float,
    l3: float,
    l4: float,
    near: np.ndarray | None,
    q2_max: float | None,
    method: str,
) -> IKResult:
    S = _wrap(S)
    # at singular poses keep only configurations that really reach T (a guard: in exact arithmetic
    # all do) and drop coinciding representatives; general-position branches are distinct (they
    # differ by π in α1 or in α2 + α3)
    L = _scale(T[:3, 3], l1, l3, l4)
    if bits and len(S):
        err = np.abs(_fk(S, l1, l3, l4) - T).max(axis=(-2, -1)) / max(1.0, L)
        S = _dedupe(S[err < 1e-8])
    reason = "; ".join(CASES[n] for n in _names(bits))
    if q2_max is not None:
        over = S[:, 2] > q2_max
        if np.all(over):
            need = float(S[:, 2].min()) if len(S) else float("nan")
            why = f"unreachable: every configuration needs q2 > q2_max = {q2_max:g} (smallest q2 is {need:.6g})"
            return IKResult(np.zeros((0, 6)), _names(bits), why, method)
        S = S[~over]
    if near is not None and len(S) > 1:
        S = S[np.argsort(_dist(S, near), kind="stable")]
    return IKResult(S, _names(bits), reason, method)


def solve(
    T: Any,
    l1: Any,
    l3: Any,
    l4: Any,
    near: Any = None,
    *,
    method: str = "explicit",
    q2_max: float | None = None,
) -> IKResult:
    """Inverse problem with a report: an :class:`IKResult` (solutions, singular cases, reason).

    ``method`` is ``"explicit"`` (Ver.1, all configurations) or ``"geometric"`` (Ver.2, the
    two of Porter's construction). ``near`` (6,) sorts the solutions nearest first and picks
    the representatives of singular families nearest to it. ``q2_max`` (optional stroke of
    the prismatic joint) makes far poses unreachable: then ``solutions`` is empty (0, 6),
    ``success`` is False and ``reason`` says why.

    >>> res = solve(fk([0.3, 0.2, 1.0, 0.4, 0.5, 0.6], 1, 0.5, 0.3), 1, 0.5, 0.3)
    >>> len(res), res.singular, res.success
    (4, (), True)
    >>> solve(fk([0.3, 0.2, 9.0, 0.4, 0.5, 0.6], 1, 0.5, 0.3), 1, 0.5, 0.3, q2_max=2.0).success
    False
    """
    T, l1, l3, l4 = _prepare(T, l1, l3, l4)
    if near is not None:
        near = as_array(near, "near", (6,), what="a configuration (α1, α2, q2, α3, α4, α5)")
    if q2_max is not None:
        q2_max = as_positive(q2_max, "q2_max")
    if method == "explicit":
        return _solve_explicit(T, l1, l3, l4, near, q2_max)
    if method == "geometric":
        return _solve_geometric(T, l1, l3, l4, near, q2_max)
    raise ValueError(f"method: expected 'explicit' or 'geometric', got {method!r}")


def _solve_explicit(
    T: np.ndarray, l1: float, l3: float, l4: float, near: np.ndarray | None, q2_max: float | None
) -> IKResult:
    fast = _ver1_scalar(T.tolist(), l1, l3, l4)
    if fast is not None:  # general position: the four branches, pure-Python arithmetic
        return _finish(np.array(fast), 0, T, l1, l3, l4, near, q2_max, "explicit")
    R, p = T[None, :3, :3], T[None, :3, 3]
    alpha1 = None if near is None else np.array([near[0]])
    Q, flags, _ = _ver1_batch(R, p, l1, l3, l4, alpha1=alpha1)
    S, F = Q[0], flags[0]
    bits = int(np.bitwise_or.reduce(F))
    if near is not None and bits:
        S = S.copy()
        for j in range(4):
            if F[j] & _BITS[PARALLEL]:
                S[j] = _refine_parallel(T[:3, :3], T[:3, 3], l1, l3, l4, float(S[j, 0]), near)
            if S[j, 2] <= TOL * _scale(T[:3, 3], l1, l3, l4):
                S[j] = _split_q2zero(S[j], near)
    return _finish(S, bits, T, l1, l3, l4, near, q2_max, "explicit")


def _report(res: IKResult) -> None:
    if not res.success:
        warnings.warn(f"Porter IK ({res.method}): {res.reason}", PorterUnreachableWarning, stacklevel=3)
    elif res.singular:
        warnings.warn(
            f"Porter IK ({res.method}): singular pose [{', '.join(res.singular)}]: {res.reason}; "
            "a representative configuration per branch is returned",
            PorterSingularityWarning,
            stacklevel=3,
        )


def ik_explicit(T: Any, l1: Any, l3: Any, l4: Any, near: Any = None, *, q2_max: float | None = None) -> np.ndarray:
    """Inverse problem, Ver.1 (explicit, eqs. 8-16 re-derived): every configuration reaching T.

    Returns a (k, 6) array of distinct configurations (α1, α2, q2, α3, α4, α5), angles in
    [0, 2π), q2 >= 0: k = 4 in general position (α1 or α1 + π, times the two values of
    arcsin in eq. 10; the sign of q2 removes the second arctan value of eq. 14). With
    ``near`` the rows are sorted nearest first. Singular poses (see :data:`CASES`) emit a
    :class:`PorterSingularityWarning` and return one representative per branch; an
    unreachable pose (only with ``q2_max``) emits :class:`PorterUnreachableWarning` and
    returns an empty (0, 6) array. Use :func:`solve` for the same with a report object.

    Formulas: α1 = atan2(p4_2, p4_1) (+π), p4 = p5 - l4 x5 (eq. 9); in the arm frame
    M1 = Rz(-α1) R: s4 = M1[1,0] (eq. 8), c4 = ±|(M1[0,0], M1[2,0])| (eq. 10), α2 + α3 =
    atan2(-M1[2,0]/c4, M1[0,0]/c4) (eqs. 12, 16), α5 from Rx(α5) = Rz(-α4) Ry(-α23) M1
    (eq. 11), and q2 (c2, s2) = (r4 + l3 s23, l1 - p4_3 - l3 c23) with r4 = c1 p4_1 + s1 p4_2
    (eqs. 13-15 without the division by c1 c2 c4).

    >>> q = [0.3, 0.2, 1.0, 0.4, 0.5, 0.6]
    >>> sols = ik_explicit(fk(q, 1, 0.5, 0.3), 1, 0.5, 0.3, near=q)
    >>> sols.shape, np.round(sols[0], 12).tolist() == q
    ((4, 6), True)
    """
    res = solve(T, l1, l3, l4, near, method="explicit", q2_max=q2_max)
    _report(res)
    return res.solutions


# --------------------------------------------------------------------------- Ver.2 (geometric)


def angle(v: Any, w: Any, n: Any) -> float:
    """Signed angle from v to w about the reference normal n (right-hand rule), in (-π, π].

    Porter's angle(): cos α = <v; w> / (|v||w|) and sin α = <n; v × w> / (|v||w|). The printed
    definition puts the cross product v × w (a vector) where sin α (a number) is needed; the
    component along the joint axis n is the one meant.

    >>> round(angle([1, 0, 0], [0, 1, 0], [0, 0, 1]), 12), round(angle([1, 0, 0], [0, 1, 0], [0, 0, -1]), 12)
    (1.570796326795, -1.570796326795)
    """
    v, w, n = (as_array(x, name, (3,)) for x, name in ((v, "v"), (w, "w"), (n, "n")))
    for x, name in ((v, "v"), (w, "w"), (n, "n")):
        if not np.any(x):
            raise ValueError(
                f"{name}: expected a non-zero 3-vector (the angle is undefined for a zero vector), got zeros"
            )
    return float(np.arctan2(np.dot(n, np.cross(v, w)), np.dot(v, w)))


def _cross(a: tuple, b: tuple) -> tuple:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _dot(a: tuple, b: tuple) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _sub(a: tuple, b: tuple) -> tuple:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def _axpy(k: float, a: tuple, b: tuple) -> tuple:  # b + k a
    return (b[0] + k * a[0], b[1] + k * a[1], b[2] + k * a[2])


def _norm(a: tuple) -> float:
    return math.sqrt(_dot(a, a))


def _angle(v: tuple, w: tuple, n: tuple) -> float:  # angle() about n, plain floats
    return math.atan2(_dot(n, _cross(v, w)), _dot(v, w))


def _solve_geometric(
    T: np.ndarray, l1: float, l3: float, l4: float, near: np.ndarray | None, q2_max: float | None
) -> IKResult:
    """Ver.2 with plain-float 3-vectors (p0 = 0 is kept in the formulas for readability)."""
    t = T.tolist()
    x5 = (t[0][0], t[1][0], t[2][0])
    z5 = (t[0][2], t[1][2], t[2][2])
    p5 = (t[0][3], t[1][3], t[2][3])
    L = l1 + l3 + l4 + _norm(p5)
    bits = 0
    p0 = (0.0, 0.0, 0.0)
    p2 = (0.0, 0.0, l1)  # eq. 17: p2 = p0 + l1 z0
    p4 = _axpy(-l4, x5, p5)  # eq. 17: p4 = p5 - l4 x5
    # normal of the plane P through p0, p2, p4: (p2 - p0) x (p4 - p0), i.e. the joint axis y1
    # (the printed order (p4 - p0) x (p2 - p0) gives -y1 and flips the signs of α2, α3, α4)
    n = _cross(_sub(p2, p0), _sub(p4, p0))
    nn = _norm(n)
    if nn <= TOL * L * L:  # p4 on the z0 axis: the plane P is free
        bits |= _BITS[AXIS]
        a1 = float(near[0]) if near is not None else float(_alpha1_simplest(T[:3, :3]))
        n = (-math.sin(a1), math.cos(a1), 0.0)
    else:
        a1 = math.atan2(p4[1], p4[0])
        n = (n[0] / nn, n[1] / nn, n[2] / nn)
    # eq. 19: z4 ⊥ n, z4 ⊥ x5, |z4| = 1  ->  z4 = ±(n x x5)/|n x x5|; p3 = p4 ± l3 z4 (eq. 18 with l3)
    m = _cross(n, x5)
    mn = _norm(m)
    if mn <= TOL:  # n ∥ x5: planes parallel, p3 on a circle about p4; Porter: minimal q2
        bits |= _BITS[PARALLEL]
        d = _sub(p4, p2)
        dn = _norm(d)
        if near is not None:  # the member of the family nearest to ``near``
            a23 = float(_refine_parallel(T[:3, :3], T[:3, 3], l1, l3, l4, a1, near)[[1, 3]].sum())
            z = (math.sin(a23) * math.cos(a1), math.sin(a23) * math.sin(a1), math.cos(a23))
            P3 = [_axpy(l3, z, p4)]
        elif dn > TOL * L:
            P3 = [_axpy(-l3 / dn, d, p4)]
        else:  # p4 = p2: every p3 on the circle gives q2 = l3; take z4 = z0 (simplest)
            P3 = [_axpy(l3, (0.0, 0.0, 1.0), p4)]
    else:
        z4 = (m[0] / mn, m[1] / mn, m[2] / mn)
        P3 = [_axpy(l3, z4, p4), _axpy(-l3, z4, p4)]
    sols = []
    for p3 in P3:
        z4 = _sub(p3, p4)
        z4 = (z4[0] / l3, z4[1] / l3, z4[2] / l3)
        q2 = _norm(_sub(p3, p2))
        a4 = _angle(n, x5, z4) + math.pi / 2
        a5 = _angle(_sub(p3, p4), z5, x5)
        if q2 <= TOL * L:  # p3 = p2: α2 free, only α2 + α3 = angle(p2 - p0, p4 - p3) - π is fixed
            bits |= _BITS[Q2_ZERO]
            a2 = 0.0
            a3 = _angle(_sub(p2, p0), _sub(p4, p3), n) - math.pi - a2
        else:
            a2 = _angle(_sub(p2, p0), _sub(p3, p2), n) - math.pi / 2
            a3 = _angle(_sub(p3, p2), _sub(p4, p3), n) - math.pi / 2
        q = np.array([a1, a2, q2, a3, a4, a5])
        if near is not None and q2 <= TOL * L:
            q = _split_q2zero(q, near)
        sols.append(q)
    return _finish(np.array(sols), bits, T, l1, l3, l4, near, q2_max, "geometric")


def ik_geometric(T: Any, l1: Any, l3: Any, l4: Any, near: Any = None, *, q2_max: float | None = None) -> np.ndarray:
    """Inverse problem, Ver.2 (geometric construction, eqs. 17-19): Porter's two configurations.

    p2 = p0 + l1 z0, p4 = p5 - l4 x5 (eq. 17); the plane P through p0, p2, p4 with normal
    n = (p2 - p0) × (p4 - p0) (= y1); z4 ⊥ n and ⊥ x5 (eq. 19), p3 = p4 ± l3 z4 (eq. 18, with
    l3 where the source prints l4); then α1 = atan2(p4_2, p4_1), α2 = angle(p2 - p0, p3 - p2)
    - π/2, q2 = |p3 - p2|, α3 = angle(p3 - p2, p4 - p3) - π/2 (both about n), α4 =
    angle(n, x5) + π/2 (about z4), α5 = angle(p3 - p4, z5) (about x5), with :func:`angle`.

    Returns (k, 6), k = 2 in general position (a subset of :func:`ik_explicit`'s four: the
    construction keeps one arm plane); k = 1 for parallel planes (minimal q2, Porter's rule).
    Warnings, ``near`` and ``q2_max`` as in :func:`ik_explicit`.

    >>> q = [0.3, 0.2, 1.0, 0.4, 0.5, 0.6]
    >>> sols = ik_geometric(fk(q, 1, 0.5, 0.3), 1, 0.5, 0.3, near=q)
    >>> sols.shape, np.round(sols[0], 12).tolist() == q
    ((2, 6), True)
    """
    res = solve(T, l1, l3, l4, near, method="geometric", q2_max=q2_max)
    _report(res)
    return res.solutions
