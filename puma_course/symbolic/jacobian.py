"""The PUMA-560's Jacobian in sympy, and the factors of its determinant (lecture 09).

The wrist is spherical, so taking the wrist centre w (the origin of frames {4}, {5}, {6}) as the
point the Jacobian describes makes it block triangular:

    J = [[J_w, 0], [*, (z4 z5 z6)]],   det J = det J_w · det(z4, z5, z6),

with J_w = ∂w/∂(θ1, θ2, θ3) (3 x 3; w depends on the first three joints only) and the last
factor the triple product of the wrist axes. Factored, the determinant is a product of three
conditions, each one of the singularities the inverse kinematics of lecture 09 meets:

* **elbow**:    a3 s3 + d4 c3 = 0 (the arm stretched or folded: up and down meet),
* **shoulder**: a2 c2 + a3 c23 - d4 s23 = 0 (the wrist centre on the cylinder ρ = |d3|: left and
  right meet; this is the reach X = c1 px + s1 py of the θ1 equation),
* **wrist**:    s5 = 0 (axes 4 and 6 aligned: flip and noflip meet).

The derivation is checked numerically against :meth:`puma_course.kinematics.DHChain.jacobian`
(a second, independent computation) in the tests.
"""

from __future__ import annotations

from functools import cache

import sympy as sp

from .dh import chain_sym, puma560_table_sym
from .notation import PUMA560_LENGTHS, theta_symbols

__all__ = [
    "puma560_wrist_centre",
    "puma560_position_jacobian",
    "puma560_wrist_axes_determinant",
    "puma560_jacobian_determinant",
    "SINGULARITY_FACTORS",
]

_t = theta_symbols(6)
_a2, _a3, _d3, _d4 = PUMA560_LENGTHS

#: The three factors of det J (det J = -a2 · elbow · shoulder · wrist), named by the singularity they mark.
SINGULARITY_FACTORS: dict[str, sp.Expr] = {
    "elbow": _a3 * sp.sin(_t[2]) + _d4 * sp.cos(_t[2]),
    "shoulder": _a2 * sp.cos(_t[1]) + _a3 * sp.cos(_t[1] + _t[2]) - _d4 * sp.sin(_t[1] + _t[2]),
    "wrist": sp.sin(_t[4]),
}


@cache
def _frames() -> tuple[sp.Matrix, ...]:
    mats, _ = chain_sym(puma560_table_sym(), simplify=False)
    out = [sp.eye(4)]
    for m in mats:
        out.append(out[-1] * m)
    return tuple(out)


def puma560_wrist_centre() -> sp.Matrix:
    """The wrist centre w (the origin of frame {4}) in base coordinates, a function of θ1, θ2, θ3.

    >>> w = puma560_wrist_centre()
    >>> sorted(s.name for s in w.free_symbols)
    ['a2', 'a3', 'd3', 'd4', 'theta1', 'theta2', 'theta3']
    """
    return sp.simplify(_frames()[4][:3, 3])


@cache
def puma560_position_jacobian() -> sp.Matrix:
    """J_w = ∂w/∂(θ1, θ2, θ3), the 3 x 3 Jacobian of the wrist centre.

    >>> puma560_position_jacobian().shape
    (3, 3)
    """
    return puma560_wrist_centre().jacobian(sp.Matrix(_t[:3])).applyfunc(sp.simplify)


def puma560_wrist_axes_determinant() -> sp.Expr:
    """det(z4, z5, z6): the triple product of the wrist's joint axes, simplified.

    >>> puma560_wrist_axes_determinant()
    -sin(theta5)
    """
    F = _frames()
    z4, z5, z6 = (F[i][:3, 2] for i in (4, 5, 6))
    return sp.simplify(sp.trigsimp(sp.Matrix.hstack(z4, z5, z6).det()))


@cache
def puma560_jacobian_determinant() -> sp.Expr:
    """det J of the PUMA-560 at its wrist centre, factored: -a2 · (elbow) · (shoulder) · (wrist).

    >>> d = puma560_jacobian_determinant()
    >>> f = SINGULARITY_FACTORS
    >>> sp.simplify(d / (f["elbow"] * f["shoulder"] * f["wrist"]))
    -a2
    """
    # expand to products of sines and cosines of single angles, factor, then tidy each factor on its own
    # (trigsimp of small factors is quick; of the whole determinant, slow): s1² + c1² factors become 1
    det_w = sp.factor(sp.expand(sp.expand_trig(puma560_position_jacobian().det(method="berkowitz"))))
    det_w = sp.Mul(*[sp.trigsimp(f) for f in sp.Mul.make_args(det_w)])
    return sp.factor(det_w * puma560_wrist_axes_determinant())
