"""Where the MK3's wrist point can be, as the approach turns in the arm plane (lecture 04 §8).

In the arm plane, with coordinates ρ (along the plane's horizontal direction e_r) and z, an approach
z' = cos β e_r + sin β e_z puts the wrist point at w' = p - d5 z': as β runs round, w' runs round the circle
of radius d5 about the tool point p. Joint 2 sits at (a1, d1) for one plane and at (-a1, d1) for the other
(reaching over the base), and the arm reaches w' when its distance ℓ from one of them lies in the annulus
|a2 - a3| <= ℓ <= a2 + a3. With v = p - J (length V, direction γ):

    ℓ² = V² + d5² - 2 d5 V cos(β - γ),

so the reachable β of one joint-2 position are those with cos(β - γ) between (V² + d5² - (a2 + a3)²) / (2 d5 V)
and (V² + d5² - (a2 - a3)²) / (2 d5 V): at most two arcs, symmetric about γ. :func:`wrist_arcs` gives them,
:func:`nearest_on_arcs` the β on them nearest a given one (the approach turned the least).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .._validate import as_array, as_length
from ..transforms import wrap_angle

__all__ = ["wrist_arcs", "nearest_on_arcs", "wrist_range"]

_TAU = 2.0 * math.pi


def _checked(rho: Any, pz: Any, L: Any) -> tuple[float, float, tuple[float, ...]]:
    """The tool point's plane coordinates and the five lengths, checked (``ValueError`` naming the argument)."""
    x = as_length(rho, "rho", what="a single number (the tool point along the arm plane, mm)")
    z = as_length(pz, "pz", what="a single number (the tool point's height, mm)")
    arr = as_array(L, "L", (5,), what="the five lengths (d1, a1, a2, a3, d5) in mm")
    lengths = tuple(as_length(float(v), f"L[{i}]", positive=i in (2, 3)) for i, v in enumerate(arr))
    return x, z, lengths


def _joints(a1: float, d1: float) -> tuple[tuple[float, float], ...]:
    return ((a1, d1), (-a1, d1))


def wrist_range(rho: Any, pz: Any, L: Any) -> list[tuple[float, float]]:
    """The least and greatest distance from joint 2 (front, then back) of the circle of wrist points.

    ``rho``, ``pz``: the tool point in the arm plane; ``L`` = (d1, a1, a2, a3, d5). The arm reaches some
    wrist point on the circle from that joint exactly when [least, greatest] meets [|a2 - a3|, a2 + a3].

    >>> [round(x, 3) for x in wrist_range(400.0, 300.0, (360.0, 135.0, 250.0, 215.0, 100.0))[0]]  # V = |(265, -60)|
    [171.708, 371.708]
    """
    rho, pz, (d1, a1, _, _, d5) = _checked(rho, pz, L)
    out = []
    for jr, jz in _joints(a1, d1):
        V = math.hypot(rho - jr, pz - jz)
        out.append((abs(V - abs(d5)), V + abs(d5)))
    return out


def wrist_arcs(rho: Any, pz: Any, L: Any) -> list[tuple[float, float]]:
    """The arcs [lo, hi] of approach angles β (radians, lo <= hi, lo in (-π, π]) whose wrist point is in reach.

    β is measured in the arm plane from e_r (away from the base, through the tool point) towards e_z (up),
    so the approach is z' = cos β e_r + sin β e_z. ``rho``, ``pz``: the tool point's coordinates in the plane;
    ``L`` = (d1, a1, a2, a3, d5) in millimetres. The boundaries are where the wrist point is at a2 + a3 or
    |a2 - a3| from joint 2 (the arm stretched or folded); an empty list: no approach in the plane will do.

    >>> arcs = wrist_arcs(400.0, 300.0, (360.0, 135.0, 250.0, 215.0, 100.0))
    >>> len(arcs), any(lo <= -math.pi / 2 <= hi for lo, hi in arcs)  # every direction, straight down among them
    (1, True)
    """
    rho, pz, (d1, a1, a2, a3, d5) = _checked(rho, pz, L)
    rmin2, rmax2 = (a2 - a3) ** 2, (a2 + a3) ** 2
    arcs: list[tuple[float, float]] = []
    for jr, jz in _joints(a1, d1):
        vr, vz = rho - jr, pz - jz
        V = math.hypot(vr, vz)
        base = V * V + d5 * d5
        if abs(d5) * V <= 1e-12 * (base + rmax2):  # the distance does not depend on β
            if rmin2 <= base <= rmax2:
                return [(-math.pi, math.pi)]
            continue
        den = 2.0 * abs(d5) * V  # d5 < 0 puts the circle's point for β on the other side: γ turns by π
        lo_c, hi_c = (base - rmax2) / den, (base - rmin2) / den
        if lo_c > 1.0 or hi_c < -1.0:
            continue
        A = math.acos(min(1.0, max(-1.0, hi_c)))  # |β - γ| >= A (not nearer than |a2 - a3|)
        B = math.acos(min(1.0, max(-1.0, lo_c)))  # |β - γ| <= B (not farther than a2 + a3)
        if A > B:
            continue
        g = math.atan2(vz, vr) + (math.pi if d5 < 0 else 0.0)
        if B - A >= math.pi or (A == 0.0 and B == math.pi):
            return [(-math.pi, math.pi)]
        if A == 0.0:
            arcs.append(_arc(g - B, g + B))
        elif B == math.pi:
            arcs.append(_arc(g + A, g + _TAU - A))
        else:
            arcs += [_arc(g + A, g + B), _arc(g - B, g - A)]
    return arcs


def _arc(lo: float, hi: float) -> tuple[float, float]:
    """The arc [lo, hi] (hi - lo < 2π) shifted so that lo is in (-π, π]."""
    start = wrap_angle(float(lo))
    return start, start + (hi - lo)


def _past(a: float, lo: float) -> float:
    """How far a is past lo going round the circle the positive way, in [0, 2π)."""
    d = wrap_angle(float(a - lo))
    return d + _TAU if d < 0.0 else d


def nearest_on_arcs(beta0: Any, arcs: Any) -> tuple[float, float, float] | None:
    """The angle on the arcs nearest ``beta0`` round the circle, in (-π, π], with its arc (lo, hi); None when
    there are no arcs.

    >>> nearest_on_arcs(0.0, [(0.5, 1.0), (-2.0, -0.6)])
    (0.5, 0.5, 1.0)
    """
    beta0 = float(as_array(beta0, "beta0", (), what="a single angle (radians)"))
    if isinstance(arcs, (list, tuple)) and len(arcs) == 0:
        arcs = np.zeros((0, 2))
    A = as_array(arcs, "arcs", (None, 2), what="arcs (lo, hi) of angles in radians, shape (n, 2)")
    for lo, hi in A.tolist():
        if not (lo <= hi <= lo + _TAU and abs(lo) <= 4.0 * math.pi):
            raise ValueError(f"arcs: expected arcs (lo, hi) with lo <= hi <= lo + 2π (radians), got ({lo}, {hi})")
    best: tuple[float, float, float] | None = None
    best_gap = math.inf
    for lo, hi in A.tolist():
        if _past(beta0, lo) <= hi - lo:  # β0 on the arc
            return wrap_angle(float(beta0)), lo, hi
        for end in (lo, hi):
            g = abs(wrap_angle(float(beta0 - end)))
            if g < best_gap:
                best, best_gap = (wrap_angle(float(end)), lo, hi), g
    return best
