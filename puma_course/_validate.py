"""Input checks shared by the kinematics modules.

Every public function validates its arguments with these helpers so that a
mistake is reported as a ``ValueError`` naming the argument, what was expected
and what arrived, instead of a NaN or a broadcasting error three calls later.
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["as_array", "as_rotation", "as_transform", "as_positive"]


def _describe(value: Any) -> str:
    try:
        arr = np.asarray(value)
    except Exception:  # pragma: no cover - extremely exotic objects
        return type(value).__name__
    if arr.dtype == object or arr.dtype.kind in "USb":
        return f"{type(value).__name__} {value!r}"[:120]
    return f"array of shape {arr.shape}"


def as_array(
    value: Any,
    name: str,
    shape: tuple[int | None, ...] | None = None,
    *,
    batch: bool = False,
    what: str | None = None,
) -> np.ndarray:
    """Return ``value`` as a finite float64 array, or raise ``ValueError``.

    ``shape`` gives the trailing shape (``None`` = any size in that place).
    With ``batch=True`` one extra leading axis is allowed (a batch of N items).
    ``what`` is a human description of the expectation used in the message.
    """
    expected = what or (
        f"shape {shape}" + (f" or (N, {', '.join(map(str, shape))})" if batch and shape else "")
        if shape is not None
        else "numbers"
    )
    if isinstance(value, (str, bytes)):
        raise ValueError(f"{name}: expected {expected} of real numbers, got {type(value).__name__} {value!r}")
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(
            f"{name}: expected {expected} of real numbers, got a non-numeric value ({_describe(value)})"
        ) from None
    if shape is not None:
        nd = len(shape)
        ok_nd = arr.ndim == nd or (batch and arr.ndim == nd + 1)
        ok = ok_nd and all(s is None or s == a for s, a in zip(shape, arr.shape[arr.ndim - nd :], strict=True))
        if not ok:
            raise ValueError(f"{name}: expected {expected}, got an array of shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        where = arr.tolist() if arr.size <= 16 else "the array"
        raise ValueError(f"{name}: expected finite numbers, got NaN or infinity in {where}")
    return arr


def as_rotation(value: Any, name: str, *, batch: bool = False, tol: float = 1e-6) -> np.ndarray:
    """Return ``value`` as a 3x3 rotation matrix (orthonormal, det +1) or raise."""
    R = as_array(value, name, (3, 3), batch=batch)
    err = np.abs(np.swapaxes(R, -1, -2) @ R - np.eye(3)).max(axis=(-2, -1))
    if np.any(err > tol):
        raise ValueError(
            f"{name}: expected a rotation matrix (R^T R = I within {tol:g}), "
            f"but R^T R differs from I by {float(np.max(err)):.3g}"
        )
    det = np.linalg.det(R)
    if np.any(det < 0):
        raise ValueError(f"{name}: expected a rotation (det +1), got a reflection (det {float(np.min(det)):.3g})")
    return R


def as_transform(value: Any, name: str, *, batch: bool = False, tol: float = 1e-6) -> np.ndarray:
    """Return ``value`` as a 4x4 homogeneous transform or raise ``ValueError``.

    Checks: shape (4, 4) (or (N, 4, 4) with ``batch``), finite entries, last
    row exactly ``0 0 0 1`` (within ``tol``) and an orthonormal rotation part.
    """
    what = "a 4x4 homogeneous transform" + (" or (N, 4, 4)" if batch else "")
    T = as_array(value, name, (4, 4), batch=batch, what=what)
    last = T[..., 3, :]
    if np.any(np.abs(last - np.array([0.0, 0.0, 0.0, 1.0])) > tol):
        raise ValueError(
            f"{name}: expected the last row of a homogeneous transform to be [0, 0, 0, 1], "
            f"got {np.round(last, 6).tolist()}"
        )
    as_rotation(T[..., :3, :3], f"{name} (rotation part)", batch=batch, tol=tol)
    return T


def as_positive(value: Any, name: str) -> float:
    """Return ``value`` as a positive finite float or raise ``ValueError``."""
    arr = as_array(value, name, (), what="a single positive number")
    if not arr > 0:
        raise ValueError(f"{name}: expected a positive length, got {float(arr)}")
    return float(arr)
