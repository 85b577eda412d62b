"""A numerical inverse kinematics, damped least squares, as a cross-check of the closed forms.

From a start q0 the iteration moves the joints by

    Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e,      e = [ (p* - p) / ℓ ;  ω ],   R* Rᵀ = exp([ω]ₓ)

(Wampler's / Nakamura's damped least squares; Lynch & Park §6.2 and Corke §8.4.1 describe the
undamped Newton step it regularises). ``J`` is the geometric Jacobian with its linear rows divided
by the length scale ℓ, so metres and radians weigh alike. It converges to *one* configuration: the
closed-form branch whose basin of attraction holds q0, which is the nearest branch when q0 is close
to one but often not from far away (lecture 09 counts). It never enumerates branches: that is what
the closed forms are for.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._validate import as_count, as_length, as_tol, as_transform
from ..transforms import axis_angle, wrap_angle

__all__ = ["DLSResult", "ik_dls"]


def _dls_step(J: np.ndarray, e: np.ndarray, lam2: float) -> np.ndarray:
    """Jᵀ (J Jᵀ + λ² I)⁻¹ e without a BLAS or LAPACK call (elementwise sums and a Cholesky by hand), so the
    iteration, and the branch it converges to, are the same bits under every BLAS kernel.

    >>> J = np.array([[2.0, 0.0], [0.0, 1.0]]); e = np.array([2.0, 1.0])
    >>> _dls_step(J, e, 0.0).tolist()
    [1.0, 1.0]
    """
    m = J.shape[0]
    A = (J[:, None, :] * J[None, :, :]).sum(axis=-1) + lam2 * np.eye(m)
    L = np.zeros_like(A)
    for i in range(m):
        for j in range(i + 1):
            s = A[i, j] - float((L[i, :j] * L[j, :j]).sum())
            L[i, j] = math.sqrt(s) if i == j else s / L[j, j]
    y = np.zeros(m)
    for i in range(m):
        y[i] = (e[i] - float((L[i, :i] * y[:i]).sum())) / L[i, i]
    x = np.zeros(m)
    for i in reversed(range(m)):
        x[i] = (y[i] - float((L[i + 1 :, i] * x[i + 1 :]).sum())) / L[i, i]
    return (J * x[:, None]).sum(axis=0)


@dataclass(frozen=True)
class DLSResult:
    """The outcome of :func:`ik_dls`: ``q`` (n,), ``success``, ``iterations`` and the final ``residual``
    (position error / ℓ and rotation error in radians, the larger of the two)."""

    q: np.ndarray
    success: bool
    iterations: int
    residual: float


def _error(T: np.ndarray, goal: np.ndarray, length: float) -> np.ndarray:
    k, t = axis_angle(goal[:3, :3] @ T[:3, :3].T)
    return np.concatenate([(goal[:3, 3] - T[:3, 3]) / length, np.asarray(k, dtype=float) * float(t)])


def ik_dls(
    robot: Any,
    T: Any,
    q0: Any,
    *,
    damping: float = 0.05,
    length: float | None = None,
    tol: float = 1e-12,
    max_iter: int = 500,
) -> DLSResult:
    """Damped-least-squares IK of ``robot`` (any arm with ``fk`` and ``jacobian``) for the pose T from q0.

    ``length`` (ℓ) scales positions: by default 1 in metres (and for unitless chains), 1000 in mm.

    >>> from puma_course.kinematics import Puma560
    >>> arm = Puma560()
    >>> q = np.radians([30.0, -50.0, 20.0, 40.0, 60.0, -30.0])
    >>> res = ik_dls(arm, arm.fk(q), q + 0.2)
    >>> res.success, bool(np.allclose(res.q, q, atol=1e-8))
    (True, True)
    """
    if not (hasattr(robot, "fk") and hasattr(robot, "jacobian")):
        raise ValueError(f"robot: expected an arm with fk and jacobian (Puma560(), MK3(), Porter()), got {robot!r}")
    goal = as_transform(T, "T")
    q = robot.check_q(q0, "q0")
    if q.ndim != 1:
        raise ValueError(f"q0: expected one joint vector of shape ({robot.n},), got an array of shape {q.shape}")
    # issue 21: sizes whose squares overflow, tolerances float64 cannot honour, counts beyond memory refused
    damping = as_length(damping, "damping", positive=True, what="a positive damping λ (one number)")
    tol = as_tol(tol, "tol")
    if length is None:
        length = 1000.0 if getattr(robot, "units", "") == "mm" else 1.0
    length = as_length(length, "length", positive=True, what="a positive length scale ℓ (one number)")
    max_iter = as_count(max_iter, "max_iter", minimum=1, maximum=10**6)
    rev = np.asarray(robot.revolute, dtype=bool)
    q = q.astype(float).copy()
    lam2 = float(damping) ** 2
    e = _error(robot.fk(q), goal, length)
    it = 0
    while it < max_iter and float(np.max(np.abs(e))) > tol:
        J = robot.jacobian(q).copy()
        J[:3] /= length
        dq = _dls_step(J, e, lam2)
        q = q + dq
        q = np.where(rev, wrap_angle(q), q)
        e = _error(robot.fk(q), goal, length)
        it += 1
    residual = float(np.max(np.abs(e)))
    return DLSResult(q, residual <= max(tol, 1e-9), it, residual)
