"""Pose tests shared by the judges: pose errors, wrapped joint distances, the rows of an answer."""

from __future__ import annotations

from typing import Any

import numpy as np

from ....transforms import wrap_angle

#: Tolerances of the pose tests: rotation entries, and positions relative to the mechanism's size.
ROT_TOL, POS_TOL = 1e-6, 1e-6


def as_floats(value: Any) -> np.ndarray | None:
    """``value`` as an array of floats, or None when it is not numbers."""
    try:
        return np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        return None


def pose_errors(Ts: np.ndarray, T: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(position error, rotation error) of poses ``Ts`` (m, 4, 4) against ``T`` (4, 4) or (m, 4, 4)."""
    d = np.asarray(Ts, dtype=float) - np.asarray(T, dtype=float)
    return np.max(np.abs(d[..., :3, 3]), axis=-1), np.max(np.abs(d[..., :3, :3]), axis=(-2, -1))


def pose_ok(Ts: Any, T: Any, scale: float = 1.0) -> np.ndarray:
    """Which of the poses ``Ts`` (m, 4, 4) equal ``T`` (position to 1e-6 of ``scale``, rotation to 1e-6).

    >>> pose_ok(np.stack([np.eye(4), 2 * np.eye(4)]), np.eye(4)).tolist()
    [True, False]
    """
    pos, rot = pose_errors(Ts, T)
    return (pos <= POS_TOL * max(1.0, scale)) & (rot <= ROT_TOL)


def offset_text(Ts: np.ndarray, T: np.ndarray) -> str:
    """How far the poses ``Ts`` are from ``T`` at most, in words (position, then orientation)."""
    pos, rot = pose_errors(Ts, T)
    return f"{float(np.max(pos)):.3g} in position and {float(np.max(rot)):.3g} in orientation"


def wrap_joints(d: np.ndarray, revolute: np.ndarray) -> np.ndarray:
    """Joint differences ``d`` with the revolute ones wrapped to (-π, π]."""
    return np.where(revolute, wrap_angle(d), d)


def joint_distance(a: np.ndarray, b: np.ndarray, revolute: np.ndarray) -> np.ndarray:
    """Wrapped joint distance (Euclidean; angle differences in (-π, π]), broadcasting over leading axes."""
    d = wrap_joints(a - b, revolute)
    return np.sqrt(np.sum(d * d, axis=-1))


def revolute_to_radians(rows: np.ndarray, revolute: np.ndarray) -> np.ndarray:
    """``rows`` with the revolute joints' values, read as degrees, turned into radians."""
    out = rows.copy()
    out[..., revolute] = np.radians(out[..., revolute])
    return out


def is_constant_transform(M: np.ndarray, scale: float) -> bool:
    """True when the transforms M (N, 4, 4) are all the same and not the identity."""
    return bool(np.all(pose_ok(M, M[0], scale)) and not pose_ok(M[:1], np.eye(4), scale)[0])
