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

__all__ = ["geometric_jacobian"]


def geometric_jacobian(chain: Any, q: Any) -> np.ndarray:
    """The 6 x n geometric Jacobian of a DH chain at q (n,), or (N, 6, n) for q (N, n); the end
    effector is the origin of the last DH frame (the tool transform, if any, is not included).

    >>> from puma_course.kinematics import DHChain, Link
    >>> planar = DHChain([Link(0, 0), Link(0, 1.0), Link(0, 1.0)])  # two unit links and a last frame
    >>> np.round(geometric_jacobian(planar, [0.0, np.pi / 2, 0.0])[[0, 1, 5]], 12) + 0.0
    array([[-1., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 1.,  1.,  1.]])
    """
    from .dh import DHChain

    if not isinstance(chain, DHChain):
        raise ValueError(f"chain: expected a DH chain (Puma560(), MK3(), DHChain(...)), got {type(chain).__name__}")
    F = chain.frames(q)
    n = chain.n
    F = F[..., : n + 1, :, :]  # drop a tool frame, if any
    z = F[..., 1:, :3, 2]  # joint axes z_1..z_n: (..., n, 3)
    p = F[..., 1:, :3, 3]  # points on them
    pe = F[..., n, :3, 3][..., None, :]
    rev = np.asarray(chain.revolute)[:, None]
    Jv = np.where(rev, np.cross(z, pe - p), z)
    Jw = np.where(rev, z, 0.0)
    return np.concatenate([np.swapaxes(Jv, -1, -2), np.swapaxes(Jw, -1, -2)], axis=-2)
