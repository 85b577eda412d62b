"""Choosing among inverse-kinematics solutions (:mod:`.ik`): the wrapped joint distance, the nearest row,
the start configuration kept at near-singular poses, repeated rows dropped, and a solver's flag bits as keys.

All are importable from :mod:`.ik` too, where the robots and the trajectories take them.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from .._validate import MAX_MAGNITUDE, as_array, as_count
from ..transforms import wrap_angle

__all__ = ["joint_distance", "keys_from_bits"]


def revolute_mask(revolute: Any, n: int) -> np.ndarray:
    """Which of n joints are angles: ``revolute`` as a boolean mask of shape (n,), all True when None."""
    if revolute is None:
        return np.ones(n, dtype=bool)
    mask = np.asarray(revolute)
    if mask.dtype != bool or mask.shape != (n,):
        raise ValueError(
            f"revolute: expected a boolean mask of shape ({n},) (one flag per joint), "
            f"got dtype {mask.dtype} and shape {mask.shape}"
        )
    return mask


def joint_distance(q: Any, q_ref: Any, revolute: Any = None) -> np.ndarray:
    """Euclidean distance between joint vectors over the last axis, angle differences wrapped.

    ``revolute`` (boolean mask, default all True) says which joints are angles: their
    differences are wrapped to (-π, π] (a step from 179° to -179° is 2°); the others (lengths)
    are compared as they are. Broadcasts over leading axes.

    >>> float(joint_distance([np.pi - 0.1, 0], [-np.pi + 0.1, 0]))  # across ±π: 0.2, not 2π - 0.2
    0.2
    >>> float(joint_distance([0.0, 3.0], [0.0, 0.0], revolute=[True, False]))  # a length: not wrapped
    3.0
    """
    # differences and their squares must stay finite (issue 31: lengths of ±1e300 gave inf)
    qa = as_array(q, "q", what="joint vectors", max_magnitude=MAX_MAGNITUDE)
    qb = as_array(q_ref, "q_ref", what="joint vectors", max_magnitude=MAX_MAGNITUDE)
    if qa.ndim == 0 or qb.ndim == 0 or qa.shape[-1] != qb.shape[-1]:
        raise ValueError(f"q, q_ref: expected joint vectors of the same length, got shapes {qa.shape} and {qb.shape}")
    rev = revolute_mask(revolute, qa.shape[-1])
    try:
        d = qa - qb
    except ValueError:
        raise ValueError(f"q, q_ref: expected shapes that broadcast, got {qa.shape} and {qb.shape}") from None
    d = np.where(rev, wrap_angle(d), d)
    return np.round(np.sqrt(np.einsum("...j,...j->...", d, d)), 15)


def nearest_index(Q: np.ndarray, q_ref: np.ndarray, revolute: np.ndarray, valid: np.ndarray | None = None) -> Any:
    """Index of the row of Q (..., k, n) nearest to q_ref (..., n), ignoring rows where ``valid`` is False.

    No validation (used in loops); ties go to the first row.

    >>> int(nearest_index(np.array([[0.0, 0.0], [3.0, 0.0]]), np.array([-3.0, 0.0]), np.array([True, True])))
    1
    """
    d = Q - q_ref[..., None, :]
    d = np.where(revolute, wrap_angle(d), d)
    cost = np.einsum("...kj,...kj->...k", d, d)
    if valid is not None:
        cost = np.where(valid, cost, np.inf)
    return np.argmin(cost, axis=-1)


def keep_start(q: np.ndarray, valid: np.ndarray, near: np.ndarray, T: np.ndarray, T_near: np.ndarray,
               revolute: np.ndarray, size: float) -> np.ndarray:  # fmt: skip
    """Rows q (N, k, n) with, for each pose whose ``near`` (N, n) reaches T to rounding (pose T_near), the valid
    row nearest ``near`` replaced by ``near`` itself (angles wrapped).

    At compound near-singular poses the closed forms fix only sums or differences of some angles well
    (their split is conditioned by 1 / sin of a tiny angle), so the start configuration could be missing
    with ``near`` given (issue 21). When ``near`` reproduces T to 1e-12 (rotation entries; positions to
    1e-12 x the robot's size) it *is* that solution, and the nearest representative is replaced by it.

    >>> q = np.array([[[0.0, 3.0], [1.0, 1.0]]]); ok = np.ones((1, 2), bool); T = np.eye(4)[None]
    >>> keep_start(q, ok, np.array([[0.1, 1.0]]), T, T, np.array([True, True]), 1.0)[0].tolist()
    [[0.0, 3.0], [0.1, 1.0]]
    """
    err = np.maximum(np.abs(T_near[:, :3, :3] - T[:, :3, :3]).max(axis=(-2, -1)),
                     np.abs(T_near[:, :3, 3] - T[:, :3, 3]).max(axis=-1) / size)  # fmt: skip
    D = near[:, None, :] - q
    D = np.where(revolute, wrap_angle(D), D)
    dist = np.where(valid, np.abs(D).max(axis=-1), np.inf)
    j = np.argmin(dist, axis=1)
    rows = np.flatnonzero((err <= 1e-12) & valid.any(axis=1))
    out = q.copy()
    nr = near[rows]
    inside = (nr > -np.pi) & (nr <= np.pi)  # already wrapped: kept bit for bit (wrapping may round)
    out[rows, j[rows]] = np.where(revolute & ~inside, wrap_angle(nr), nr)
    return out


def dedupe_mask(Q: np.ndarray, revolute: np.ndarray, tol: float = 1e-9) -> np.ndarray:
    """Mask of the rows of Q (k, n) that do not repeat an earlier row (within ``tol``, angles wrapped).

    >>> dedupe_mask(np.array([[0.0, 1.0], [2 * np.pi, 1.0], [0.5, 1.0]]), np.array([True, True])).tolist()
    [True, False, True]
    """
    if len(Q) < 2:
        return np.ones(len(Q), dtype=bool)
    D = Q[:, None, :] - Q[None, :, :]
    D = np.where(revolute, wrap_angle(D), D)
    close = np.sqrt(np.einsum("ijk,ijk->ij", D, D)) <= tol
    return ~np.any(np.tril(close, k=-1), axis=1)


def keys_from_bits(bits: int, flag_keys: Sequence[str]) -> tuple[str, ...]:
    """The keys whose bits are set in ``bits`` (bit i stands for ``flag_keys[i]``).

    >>> keys_from_bits(5, ("shoulder", "elbow", "wrist"))
    ('shoulder', 'wrist')
    """
    if (
        isinstance(flag_keys, (str, bytes))
        or not isinstance(flag_keys, (list, tuple))
        or not all(isinstance(k, str) for k in flag_keys)
    ):
        raise ValueError(f"flag_keys: expected a list of flag names (strings), got {flag_keys!r}"[:200])
    n = as_count(bits, "bits", maximum=2 ** len(flag_keys) - 1)  # a bit with no name is a mistake
    return tuple(k for i, k in enumerate(flag_keys) if n >> i & 1)
