"""Euler angles: ZYZ (the wrist angles of lectures 08 and 09) and roll-pitch-yaw, with their singularity.

Both sets describe a rotation by three turns about coordinate axes. Each has a *gimbal lock*: at
θ = 0 or π (ZYZ) or pitch = ±90° (RPY) the first and third axes line up, only the sum or the
difference of the first and third angles is defined, and a representative must be chosen. Here
that case is decided with an explicit tolerance (:data:`EULER_SINGULAR_TOL` on the sine) and
snapped: the middle angle is set exactly to its boundary value and the third angle to the
representative the caller gives (default 0), so the rotation is still reproduced exactly.

Angles are radians; batches put the batch axis first: (N, 3, 3) rotations give (N, 3) angles.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ._validate import as_angle, as_rotation, check_broadcast
from .transforms import rotx, roty, rotz, wrap_angle  # noqa: F401  (the examples below use them)

__all__ = ["rotation_from_zyz", "zyz_from_rotation", "rotation_from_rpy", "rpy_from_rotation", "EULER_SINGULAR_TOL"]


def rotation_from_zyz(phi: Any, theta: Any, psi: Any) -> np.ndarray:
    """Rz(φ) Ry(θ) Rz(ψ): the ZYZ Euler-angle rotation (turns about the moving axes, in that order).

    Angles broadcast: numbers give (3, 3), arrays of shape (N,) give (N, 3, 3).

    >>> np.allclose(rotation_from_zyz(0.1, 0.2, 0.3), rotz(0.1) @ roty(0.2) @ rotz(0.3))
    True
    """
    a, b, c = as_angle(phi, "phi"), as_angle(theta, "theta"), as_angle(psi, "psi")
    check_broadcast(phi=a.shape, theta=b.shape, psi=c.shape)
    (ca, sa), (cb, sb), (cc, sc) = ((np.cos(x), np.sin(x)) for x in np.broadcast_arrays(a, b, c))
    # entry by entry, no matrix product: a BLAS kernel would decide the last bit (README)
    return _matrix(
        (ca * cb * cc - sa * sc, -(ca * cb * sc) - sa * cc, ca * sb),
        (sa * cb * cc + ca * sc, -(sa * cb * sc) + ca * cc, sa * sb),
        (-(sb * cc), sb * sc, cb),
    )


def _matrix(*rows: tuple[np.ndarray, np.ndarray, np.ndarray]) -> np.ndarray:
    """The (..., 3, 3) array of nine entries of one shape, given row by row."""
    R = np.empty(rows[0][0].shape + (3, 3))
    for i, row in enumerate(rows):
        for j, entry in enumerate(row):
            R[..., i, j] = entry
    return R + 0.0  # no -0.0


#: sin θ below this counts as the gimbal-lock case of an Euler-angle set (then only φ ± ψ is defined).
EULER_SINGULAR_TOL = 1e-9


def zyz_from_rotation(R: Any, *, psi: Any = 0.0) -> np.ndarray:
    """ZYZ Euler angles (φ, θ, ψ), θ in [0, π], with Rz(φ) Ry(θ) Rz(ψ) = R; (3,) or (N, 3).

    Singular when sin θ < :data:`EULER_SINGULAR_TOL` (gimbal lock: the first and last axes are
    parallel). Then θ is snapped to exactly 0 or π, only φ + ψ (θ = 0) or φ − ψ (θ = π) is
    defined, and ψ takes the value ``psi`` given (default 0): R is still reproduced exactly.

    >>> np.round(zyz_from_rotation(rotation_from_zyz(0.1, 0.2, 0.3)), 12)
    array([0.1, 0.2, 0.3])
    >>> zyz_from_rotation(rotz(0.5))  # θ = 0: φ + ψ = 0.5, ψ = 0 chosen
    array([0.5, 0. , 0. ])
    """
    R = as_rotation(R, "R", batch=True)
    psi_rep = as_angle(psi, "psi")
    check_broadcast(R=R.shape[:-2], psi=psi_rep.shape)
    sin_t = np.hypot(R[..., 0, 2], R[..., 1, 2])
    singular = sin_t < EULER_SINGULAR_TOL
    up = R[..., 2, 2] > 0
    theta = np.where(singular, np.where(up, 0.0, np.pi), np.arctan2(sin_t, R[..., 2, 2]))
    phi = np.arctan2(R[..., 1, 2], R[..., 0, 2])
    psi_out = np.arctan2(R[..., 2, 1], -R[..., 2, 0])
    # φ + ψ (θ < π/2) or φ − ψ (θ > π/2) from well-conditioned entries, exactly for any θ:
    # r11 + r22 = (1 + cθ) cos(φ + ψ), r21 − r12 = (1 + cθ) sin(φ + ψ),
    # r22 − r11 = (1 − cθ) cos(φ − ψ), −r21 − r12 = (1 − cθ) sin(φ − ψ).
    # Near gimbal lock φ and ψ alone come from entries of size sin θ (relative error eps / sin θ, 1e-7 just
    # above the snap); only their difference (θ ~ 0) or sum (θ ~ π) may carry that error, which moves R by
    # sin θ times it, so the well-conditioned combination is imposed, half on each angle.
    r00, r01, r10, r11 = R[..., 0, 0], R[..., 0, 1], R[..., 1, 0], R[..., 1, 1]
    total = np.where(up, np.arctan2(r10 - r01, r00 + r11), np.arctan2(-r10 - r01, r11 - r00))
    half = wrap_angle(total - np.where(up, phi + psi_out, phi - psi_out)) / 2
    phi, psi_out = wrap_angle(phi + half), wrap_angle(np.where(up, psi_out + half, psi_out - half))
    # gimbal lock: R = Rz(φ + ψ) (θ = 0) or Rz(φ - ψ) Ry(π) (θ = π); ψ is the representative given
    phi = np.where(singular, wrap_angle(np.where(up, total - psi_rep, total + psi_rep)), phi)
    psi_out = np.where(singular, psi_rep, psi_out)
    return np.stack(np.broadcast_arrays(phi, theta, psi_out), axis=-1) + 0.0


def rotation_from_rpy(roll: Any, pitch: Any, yaw: Any) -> np.ndarray:
    """Roll-pitch-yaw: Rz(yaw) Ry(pitch) Rx(roll), i.e. roll about the fixed x axis, then pitch
    about the fixed y axis, then yaw about the fixed z axis (equivalently Z-Y-X about the moving axes).

    >>> np.allclose(rotation_from_rpy(0.1, 0.2, 0.3), rotz(0.3) @ roty(0.2) @ rotx(0.1))
    True
    """
    y, p, r = as_angle(yaw, "yaw"), as_angle(pitch, "pitch"), as_angle(roll, "roll")
    check_broadcast(yaw=y.shape, pitch=p.shape, roll=r.shape)
    (cy, sy), (cp, sp), (cr, sr) = ((np.cos(x), np.sin(x)) for x in np.broadcast_arrays(y, p, r))
    # entry by entry, no matrix product (see rotation_from_zyz)
    return _matrix(
        (cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr),
        (sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr),
        (-sp, cp * sr, cp * cr),
    )


def rpy_from_rotation(R: Any, *, roll: Any = 0.0) -> np.ndarray:
    """Roll-pitch-yaw angles (roll, pitch, yaw), pitch in [-π/2, π/2], with
    Rz(yaw) Ry(pitch) Rx(roll) = R; (3,) or (N, 3).

    Singular when cos(pitch) < :data:`EULER_SINGULAR_TOL` (pitch = ±90°, gimbal lock): pitch is
    snapped to exactly ±π/2, only yaw − roll (pitch = +π/2) or yaw + roll (pitch = −π/2) is
    defined, and roll takes the value ``roll`` given (default 0).

    >>> np.round(rpy_from_rotation(rotation_from_rpy(0.1, 0.2, 0.3)), 12)
    array([0.1, 0.2, 0.3])
    >>> np.round(rpy_from_rotation(roty(np.pi / 2) @ rotx(0.4)), 12) + 0.0  # gimbal lock
    array([ 0.        ,  1.57079633, -0.4       ])
    """
    R = as_rotation(R, "R", batch=True)
    roll_rep = as_angle(roll, "roll")
    check_broadcast(R=R.shape[:-2], roll=roll_rep.shape)
    cos_p = np.hypot(R[..., 0, 0], R[..., 1, 0])
    singular = cos_p < EULER_SINGULAR_TOL
    down = R[..., 2, 0] < 0  # pitch = +π/2 when r31 = -sin(pitch) = -1
    pitch = np.where(singular, np.where(down, np.pi / 2, -np.pi / 2), np.arctan2(-R[..., 2, 0], cos_p))
    roll_out = np.arctan2(R[..., 2, 1], R[..., 2, 2])
    yaw = np.arctan2(R[..., 1, 0], R[..., 0, 0])
    # yaw − roll (pitch > 0) or yaw + roll (pitch < 0) from well-conditioned entries, exactly for any pitch:
    # r23 − r12 = (1 + sp) sin(y − r), r13 + r22 = (1 + sp) cos(y − r),
    # −r23 − r12 = (1 − sp) sin(y + r), r22 − r13 = (1 − sp) cos(y + r); imposed as in zyz_from_rotation
    r01, r02, r11, r12 = R[..., 0, 1], R[..., 0, 2], R[..., 1, 1], R[..., 1, 2]
    diff = np.where(down, np.arctan2(r12 - r01, r02 + r11), np.arctan2(-r12 - r01, r11 - r02))
    half = wrap_angle(diff - np.where(down, yaw - roll_out, yaw + roll_out)) / 2
    yaw, roll_out = wrap_angle(yaw + half), wrap_angle(np.where(down, roll_out - half, roll_out + half))
    # gimbal lock: with pitch = +π/2, R = [[0, s(r-y), c(r-y)], [0, c(r-y), -s(r-y)], [-1, 0, 0]]
    # (so yaw - roll is fixed); with pitch = -π/2, yaw + roll is fixed
    yaw = np.where(singular, wrap_angle(np.where(down, roll_rep + diff, diff - roll_rep)), yaw)
    roll_out = np.where(singular, roll_rep, roll_out)
    return np.stack(np.broadcast_arrays(roll_out, pitch, yaw), axis=-1) + 0.0
