"""Porter's singular families: where the pose fixes a whole continuum of configurations.

* planes parallel (c4 = 0): for a given arm plane only α2 + α3 ± α5 is fixed; p3 runs around a
  circle about p4, and α23 = α2 + α3 is a free parameter;
* q2 = 0 (p3 = p2): only α2 + α3 is fixed;
* p4 on the z0 axis: the arm plane, hence α1, is free.

Without ``near`` one representative per branch is returned (Porter's rule: minimal q2 for parallel
planes; α2 = 0 for q2 = 0; the plane containing x5 for a free α1). With ``near`` the member of
the family nearest to it is chosen: :func:`nearest_parallel` searches α23, :func:`split_q2zero`
shares the fixed sum α2 + α3 with ``near``.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ...transforms import wrap_angle
from .._ops import ARRAY
from ..ik import joint_distance
from .explicit import complete

__all__ = ["nearest_parallel", "split_q2zero", "REVOLUTE"]

#: Which of Porter's joints are angles (q2, index 2, is a prismatic length).
REVOLUTE = np.array([True, True, False, True, True, True])


def split_q2zero(q: np.ndarray, near: np.ndarray) -> np.ndarray:
    """q2 = 0: only α23 = α2 + α3 is fixed; share the wrapped difference to ``near`` equally.

    >>> split_q2zero(np.array([0.0, 0.0, 0.0, 1.0, 0.0, 0.0]), np.zeros(6))[[1, 3]]
    array([0.5, 0.5])
    """
    q = q.copy()
    a23 = q[1] + q[3]
    e = float(wrap_angle(a23 - near[1] - near[3]))
    q[1] = near[1] + e / 2.0
    q[3] = a23 - q[1]
    return q


def nearest_parallel(R: np.ndarray, p: np.ndarray, L: tuple[float, float, float], a1: float, near: np.ndarray,
                     tol: float) -> np.ndarray:  # fmt: skip
    """Planes-parallel family in the arm plane α1: the member nearest ``near`` (a 1-D search in α23).

    A grid of 721 values of α23 brackets the minimum of the configuration distance, a golden-section
    search refines it, and the member of minimal q2 (which may have q2 = 0, where α2 is free too) is
    compared with the result.
    """
    l1, l3, l4 = L
    c1, s1 = math.cos(a1), math.sin(a1)
    # Rz(a1)^T R written out entry by entry: a matrix product (`@`) or np.linalg.norm may go through BLAS,
    # whose kernels (Haswell, Prescott, ...) round differently, and this search is decided on the result
    # (issue 21: up to 1.3e-8 between two OpenBLAS kernels)
    (r00, r01, _), (r10, r11, _), (r20, r21, _) = R.tolist()
    m = (c1 * r00 + s1 * r10, c1 * r01 + s1 * r11, -s1 * r00 + c1 * r10, -s1 * r01 + c1 * r11, r20, r21)
    px, py, pz = p.tolist()
    p4 = (px - l4 * r00, py - l4 * r10, pz - l4 * r20)
    r4, h = c1 * p4[0] + s1 * p4[1], p4[2] - l1
    s4 = 1.0 if m[2] >= 0 else -1.0
    a4 = math.atan2(s4, 0.0)

    def family(t: Any) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        a5, q2, a2 = complete(ARRAY, m, t, s4, 0.0, r4, h, l3)
        z = 0.0 * t
        return np.stack([a1 + z, a2, q2, t - a2, a4 + z, a5], axis=-1)

    def dist(t: Any) -> Any:
        return joint_distance(family(t), near, REVOLUTE)

    grid = np.linspace(-math.pi, math.pi, 721)
    t0 = grid[int(np.argmin(dist(grid)))]
    lo, hi = t0 - 2 * math.pi / 720, t0 + 2 * math.pi / 720
    g = (math.sqrt(5.0) - 1.0) / 2.0
    for _ in range(60):  # golden-section search
        m1, m2 = hi - g * (hi - lo), lo + g * (hi - lo)
        if dist(m1) < dist(m2):
            hi = m2
        else:
            lo = m1
    best = family(0.5 * (lo + hi))
    scale = l1 + l3 + l4 + math.hypot(px, py, pz)
    if math.hypot(r4, h) > tol * scale:  # the member of minimal q2: z3 = -(p4 - p2)/|p4 - p2|
        cand = family(math.atan2(-r4, -h))
        if cand[2] <= tol * scale:
            cand[2] = 0.0
            cand = split_q2zero(cand, near)
        if joint_distance(cand, near, REVOLUTE) < joint_distance(best, near, REVOLUTE):
            best = cand
    return best
