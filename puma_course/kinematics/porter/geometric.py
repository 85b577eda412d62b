"""Porter's inverse problem, Ver.2 (the geometric construction, eqs. 17-19) and his angle() function.

p2 = p0 + l1 z0 and p4 = p5 - l4 x5 (eq. 17); p0, p2, p3, p4 lie in a plane P whose normal is
n = (p2 - p0) x (p4 - p0) (= y1; the printed order gives -y1 and flips the signs of α2, α3, α4);
z4 ⊥ n and z4 ⊥ x5 (eq. 19), so p3 = p4 ± l3 z4 (eq. 18, with l3 where the source prints l4); then
α1 = atan2(p4_2, p4_1), α2 = angle(p2 - p0, p3 - p2) - π/2, q2 = |p3 - p2|,
α3 = angle(p3 - p2, p4 - p3) - π/2 (both about n), α4 = angle(n, x5) + π/2 (about z4),
α5 = angle(p3 - p4, z5) (about x5).

The construction keeps one arm plane: two configurations in general position, a subset of Ver.1's
four; one for parallel planes (minimal q2, Porter's rule). Plain-float 3-vectors (one pose).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..._validate import as_array
from .families import nearest_parallel, split_q2zero

__all__ = ["angle", "construct"]

Vec = tuple[float, float, float]


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
    # Each vector scaled by a power of two near its size first (exact: the same bits for ordinary sizes),
    # since a dot or cross product of 1e200-long vectors overflows to NaN and of 1e-200-long ones
    # underflows to 0 (issue 21: NaN and 0 instead of π/2). The result does not depend on |v| and |w|;
    # it does on |n| (the printed formula's sin α = <n; v x w> / (|v||w|)), so n's power of two is
    # given back to the other term of atan2.
    (a, _), (b, _), (c, en) = (_scaled(x) for x in (v, w, n))
    return math.atan2(_dot(c, _cross(a, b)), math.ldexp(_dot(a, b), -en))


def _scaled(u: np.ndarray) -> tuple[Vec, int]:
    """u times 2^-e, with 2^e near its largest entry (exact), and e."""
    e = math.frexp(float(np.max(np.abs(u))))[1]
    x, y, z = (math.ldexp(t, -e) for t in u.tolist())
    return (x, y, z), e


def _cross(a: Vec, b: Vec) -> Vec:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _dot(a: Vec, b: Vec) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _sub(a: Vec, b: Vec) -> Vec:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def _axpy(k: float, a: Vec, b: Vec) -> Vec:  # b + k a
    return (b[0] + k * a[0], b[1] + k * a[1], b[2] + k * a[2])


def _norm(a: Vec) -> float:
    return math.hypot(a[0], a[1], a[2])


def _angle(v: Vec, w: Vec, n: Vec) -> float:
    return math.atan2(_dot(n, _cross(v, w)), _dot(v, w))


def construct(
    T: np.ndarray, L: tuple[float, float, float], near: np.ndarray | None, tol: float
) -> list[tuple[np.ndarray, tuple[str, ...]]]:
    """Ver.2 for one validated pose: [(configuration, singular keys), ...] (angles not yet wrapped).

    p0 = 0 is kept in the formulas for readability.
    """
    l1, l3, l4 = L
    t = T.tolist()
    x5: Vec = (t[0][0], t[1][0], t[2][0])
    z5: Vec = (t[0][2], t[1][2], t[2][2])
    p5: Vec = (t[0][3], t[1][3], t[2][3])
    scale = l1 + l3 + l4 + _norm(p5)
    keys: list[str] = []
    p0: Vec = (0.0, 0.0, 0.0)
    p2: Vec = (0.0, 0.0, l1)
    p4 = _axpy(-l4, x5, p5)
    n = _cross(_sub(p2, p0), _sub(p4, p0))
    nn = _norm(n)  # = l1 times the distance of p4 from the z0 axis
    if nn <= tol * scale * l1:  # p4 on the z0 axis: the plane P is free
        keys.append("p4_on_z0_axis")
        if near is not None:
            a1 = float(near[0])
        else:
            a1 = math.atan2(x5[1], x5[0]) if math.hypot(x5[0], x5[1]) > 1e-9 else 0.0
        n = (-math.sin(a1), math.cos(a1), 0.0)
    else:
        a1 = math.atan2(p4[1], p4[0])
        n = (n[0] / nn, n[1] / nn, n[2] / nn)
    # each candidate elbow point is p3 = p4 + l3 u with u a unit vector kept as such: p3 - p4 is
    # then exactly l3 u, never the difference of two large coordinates (which loses the digits of
    # α3 and α5 when q2 is large)
    m = _cross(n, x5)
    mn = _norm(m)
    if mn <= tol:  # n ∥ x5: planes parallel, p3 on a circle about p4; Porter: minimal q2
        keys.append("planes_parallel")
        d = _sub(p4, p2)
        dn = _norm(d)
        if near is not None:  # the member of the family nearest to ``near``
            a23 = float(nearest_parallel(T[:3, :3], T[:3, 3], L, a1, near, tol)[[1, 3]].sum())
            U: list[Vec] = [(math.sin(a23) * math.cos(a1), math.sin(a23) * math.sin(a1), math.cos(a23))]
        elif dn > tol * scale:
            U = [(-d[0] / dn, -d[1] / dn, -d[2] / dn)]
        else:  # p4 = p2: every p3 on the circle gives q2 = l3; take z4 = z0 (simplest)
            U = [(0.0, 0.0, 1.0)]
    else:
        z4: Vec = (m[0] / mn, m[1] / mn, m[2] / mn)
        U = [z4, (-z4[0], -z4[1], -z4[2])]
    out = []
    for u in U:
        p3 = _axpy(l3, u, p4)
        z4 = u  # z4 = (p3 - p4) / l3
        q2 = _norm(_sub(p3, p2))
        a4 = _angle(n, x5, z4) + math.pi / 2
        if "planes_parallel" in keys:
            a4 = math.copysign(math.pi / 2, math.sin(a4))  # snapped: c4 = 0 exactly
        a5 = _angle(u, z5, x5)
        row_keys = list(keys)
        down = (-u[0], -u[1], -u[2])  # p4 - p3, along -z4
        if q2 <= tol * scale:  # p3 = p2: α2 free, only α2 + α3 = angle(p2 - p0, p4 - p3) - π is fixed
            row_keys.append("q2_zero")
            q2, a2 = 0.0, 0.0
            a3 = _angle(_sub(p2, p0), down, n) - math.pi - a2
        else:
            a2 = _angle(_sub(p2, p0), _sub(p3, p2), n) - math.pi / 2
            a3 = _angle(_sub(p3, p2), down, n) - math.pi / 2
        q = np.array([a1, a2, q2, a3, a4, a5])
        if near is not None and q2 == 0.0:
            q = split_q2zero(q, near)
        out.append((q, tuple(row_keys)))
    return out
