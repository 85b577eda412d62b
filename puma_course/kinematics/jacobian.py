"""The geometric Jacobian of a DH chain: how the end effector's velocity follows the joint rates.

For Craig's frames, joint i turns about (or slides along) the axis z_i of frame {i}, through its
origin p_i. The end effector at p_e (the origin of the last frame) then moves with

    v = Σ J_v,i q̇_i,   ω = Σ J_ω,i q̇_i,
    revolute:  J_v,i = z_i × (p_e - p_i),   J_ω,i = z_i;
    prismatic: J_v,i = z_i,                 J_ω,i = 0,

all in base coordinates. ``J = [J_v; J_ω]`` is 6 x n. Where ``det J`` (6 x 6) vanishes the arm is
singular: some velocity of the end effector cannot be produced (lecture 09 factors it for the
PUMA-560 into the elbow, shoulder and wrist conditions).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .._validate import MAX_MAGNITUDE, as_mask
from .dh import DHChain
from .jacobian_columns import from_axes

__all__ = ["geometric_jacobian", "jacobian_from_axes"]


def _as_real(value: Any, name: str) -> np.ndarray:
    """A real float array (any shape), or ValueError naming the argument."""
    try:
        arr = np.asarray(value) if not isinstance(value, (str, bytes)) and value is not None else None
    except ValueError:  # ragged lists: numpy's "inhomogeneous shape" message does not name the argument
        arr = None
    real = arr is not None and (np.issubdtype(arr.dtype, np.integer) or np.issubdtype(arr.dtype, np.floating))
    if arr is None or arr.dtype == bool or not real:
        raise ValueError(f"{name}: expected an array of real numbers, got {value!r}")
    return arr.astype(float)


def jacobian_from_axes(axes: np.ndarray, points: np.ndarray, pe: np.ndarray, revolute: Any) -> np.ndarray:
    """The 6 x n geometric Jacobian from the joint axes, a point on each and the reference point.

    ``axes`` and ``points`` are (..., n, 3) in base coordinates (unit axes), ``pe`` (..., 3) the
    point whose velocity ``v`` the first three rows give, ``revolute`` an (n,) boolean mask:
    column i is [z_i × (p_e - o_i); z_i] for a revolute joint and [z_i; 0] for a prismatic one.

    >>> z = np.array([[0.0, 0.0, 1.0], [0.0, 0.0, 1.0]])
    >>> o = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
    >>> jacobian_from_axes(z, o, np.array([2.0, 0.0, 0.0]), [True, False])[:, :] + 0.0
    array([[0., 0.],
           [2., 0.],
           [0., 1.],
           [0., 0.],
           [0., 0.],
           [1., 0.]])
    """
    z, p, e = _as_real(axes, "axes"), _as_real(points, "points"), _as_real(pe, "pe")
    if z.ndim < 2 or z.shape[-1] != 3:
        raise ValueError(f"axes: expected joint axes of shape (..., n, 3), got an array of shape {z.shape}")
    if p.shape != z.shape:
        raise ValueError(f"points: expected the shape of axes {z.shape}, got {p.shape}")
    if e.shape != z.shape[:-2] + (3,):
        raise ValueError(f"pe: expected a point of shape {z.shape[:-2] + (3,)}, got {e.shape}")
    rev = as_mask(revolute, "revolute", z.shape[-2]) if z.ndim >= 2 else np.asarray(None)
    if rev.shape != (z.shape[-2],) or rev.dtype != bool:
        raise ValueError(f"revolute: expected a boolean mask of shape ({z.shape[-2]},), got {rev!r}")
    for arr, name in ((z, "axes"), (p, "points"), (e, "pe")):
        if not np.all(np.isfinite(arr)) or np.any(np.abs(arr) > MAX_MAGNITUDE):
            raise ValueError(f"{name}: expected finite numbers of magnitude at most {MAX_MAGNITUDE:g}, got {arr!r}")
    if np.any(np.abs(np.linalg.norm(z, axis=-1) - 1.0) > 1e-9):
        raise ValueError(f"axes: expected unit vectors (the joint axes' directions), got {z.tolist()}")
    return from_axes(z, p, e, rev)


def geometric_jacobian(chain: Any, q: Any) -> np.ndarray:
    """The 6 x n geometric Jacobian of a DH chain at q (n,), or (N, 6, n) for q (N, n); the end
    effector is the origin of the last DH frame (the tool transform, if any, is not included).

    One column walk of the chain (the frames as plain numbers, never as 4 x 4 arrays), then the
    columns of :func:`jacobian_from_axes` written out: the same formula, floats for one pose.
    Arms with a closed form (:class:`~.puma560.Puma560`) override ``jacobian`` with it.

    >>> from puma_course.kinematics import DHChain, Link
    >>> planar = DHChain([Link(0, 0), Link(0, 1.0), Link(0, 1.0)])  # two unit links and a last frame
    >>> np.round(geometric_jacobian(planar, [0.0, np.pi / 2, 0.0])[[0, 1, 5]], 12) + 0.0
    array([[-1., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 1.,  1.,  1.]])
    """
    if not isinstance(chain, DHChain):
        raise ValueError(f"chain: expected a DH chain (Puma560(), MK3(), DHChain(...)), got {type(chain).__name__}")
    return DHChain.jacobian(chain, q)  # the column walk, also for an arm whose jacobian is a closed form
