"""Porter's direct problem derived in sympy: the local- and scene-frame products and the closed forms.

An independent second derivation of what the numeric Porter chain computes (lectures 05-07):

* :func:`local_product` - F05 as a product of motions in local frames (moving axes);
* :func:`scene_product` - F05 with each motion about/along an axis given in the SCENE frame,
  built with Rodrigues' formula and left-multiplication, nothing of the local product used;
* :func:`closed_forms` - x5, y5, z5, p5 in Porter's ci, si notation;
* :func:`to_sc`, :func:`from_sc`, :func:`reduce_sc`, :func:`sc_values` - between cos/sin and ci/si,
  and the reduction modulo ci² + si² = 1;
* :func:`corrected_z5_2` - the one damaged printed entry, repaired after the pattern of y5.

Porter's formulas as printed are in :mod:`puma_course.symbolic.printed.porter`; the symbols
(``q2``, ``l1``, ``c[1]``, ...) are those of :mod:`puma_course.symbolic.notation`, re-exported here
so that ``from puma_course.symbolic import porter as PS`` gives ``PS.q2``, ``PS.c[1]``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import sympy as sp

from .elementary import AXES, rot, rot_about, trans, trans_along
from .notation import PORTER_ANGLES, PORTER_Q, PORTER_SYMBOLS, c, l1, l3, l4, pose_symbols, q2, s
from .notation import alpha1 as _a1
from .notation import alpha2 as _a2
from .notation import alpha3 as _a3
from .notation import alpha4 as _a4
from .notation import alpha5 as _a5

__all__ = [
    "MOTIONS",
    "Q",
    "SYMBOLS",
    "q2",
    "l1",
    "l3",
    "l4",
    "c",
    "s",
    "pose_symbols",
    "local_product",
    "scene_product",
    "closed_forms",
    "to_sc",
    "from_sc",
    "reduce_sc",
    "sc_values",
    "corrected_z5_2",
]

#: Porter's configuration (α1, α2, q2, α3, α4, α5), the order of the numeric ``q``.
Q = PORTER_Q
#: Every symbol of the chain by name ("alpha1", "q2", "l1", ...).
SYMBOLS = PORTER_SYMBOLS

#: One motion of the chain: (kind, axis, value), kind "R" (rotation) or "T" (translation).
Motion = tuple[str, str, Any]

#: The chain's motions in order, each about/along an axis of the frame reached so far: the printed
#: local-frame product with the ``Tx(q2)`` it omits (the scene-frame product prints it).
MOTIONS: tuple[Motion, ...] = (
    ("R", "z", _a1), ("T", "z", l1), ("R", "y", _a2), ("T", "x", q2), ("R", "y", _a3),
    ("T", "z", -l3), ("R", "z", _a4), ("T", "x", l4), ("R", "x", _a5),
)  # fmt: skip

_ANGLE_INDEX = {a: i for i, a in enumerate(PORTER_ANGLES, start=1)}


def local_product(motions: Sequence[Motion] = MOTIONS) -> sp.Matrix:
    """F05 = Rz(α1) Tz(l1) Ry(α2) Tx(q2) Ry(α3) Tz(-l3) Rz(α4) Tx(l4) Rx(α5), the local-frame product.

    Porter's F05 "by transformations in corresponding local frames" (moving axes: each factor
    acts about/along an axis of the frame reached so far), with the ``Tx(q2)`` the print omits.
    ``motions`` multiplies other factors, e.g. the printed ones
    (:data:`puma_course.symbolic.printed.porter.LOCAL_PRODUCT`). Height of p5 at the zero pose:

    >>> F = local_product()
    >>> F[2, 3].subs({a: 0 for a in Q if a != q2})
    l1 - l3
    """
    M = sp.eye(4)
    for kind, axis, v in motions:
        M = M * (rot(axis, v) if kind == "R" else trans(axis, v))
    return M


def reduce_sc(expr: Any) -> sp.Expr:
    """Expand and reduce a polynomial in ci, si modulo ci² + si² = 1 (a canonical form: ci of degree <= 1).

    Two expressions are equal for all angles exactly when their reduced difference is 0.

    >>> reduce_sc(c[1] ** 2 + s[1] ** 2)
    1
    >>> reduce_sc(c[2] ** 3)
    -c2*s2**2 + c2
    """
    e = sp.expand(expr)
    for i in range(1, 6):
        if e.has(c[i]):
            e = sp.expand(sp.rem(sp.Poly(e, c[i]), sp.Poly(c[i] ** 2 + s[i] ** 2 - 1, c[i])).as_expr())
    return e


#: The literal reading of the printed scene product's subscripts: R_{y1}(α2) turns about a line
#: through p1 = p0, R_{y2}(α3) about a line through p2 (motion index -> the point's index).
_LITERAL_LINES = {2: 1, 4: 2}


def scene_product(lines: str = "current") -> sp.Matrix:
    """F05 = R_x4(α5) T_x4(l4) R_z3(α4) T_z3(-l3) R_y2(α3) T_x2(q2) R_y1(α2) T_z1(l1) R_z0(α1), in ci, si.

    Porter's scene-frame product (eq. 6): each motion acts about/along an axis given in SCENE
    coordinates, the unit axis being the column of the frame reached so far; each step, a
    Rodrigues rotation K(a, α) about a line (:func:`~puma_course.symbolic.elementary.rot_about`)
    or a translation l a, multiplies the product on the LEFT. Nothing of the local product is
    used. ``lines="current"``: the rotation lines pass through the current joint point (p2 for
    α2, p3 for α3), the reading that matches the printed p5. ``lines="literal"``: y1 and y2 taken
    as lines through the origins p1 = p0 and p2, as the subscripts read literally.

    The scene-frame product equals the local product (about 1 s):

    >>> M = scene_product()
    >>> sp.expand(M[2, 3] - closed_forms()["p5"][2])
    0
    """
    if lines not in ("current", "literal"):
        raise ValueError(f"lines: expected 'current' or 'literal', got {lines!r}")
    F = sp.eye(4)  # the frame reached so far (its columns: the axes and the point, in the scene)
    M = sp.eye(4)  # the accumulated scene-frame product
    points = {0: F[:3, 3], 1: F[:3, 3]}  # p0 = p1
    for k, (kind, axis, v) in enumerate(MOTIONS):
        a = F[:3, AXES.index(axis)]
        if kind == "R":
            i = _ANGLE_INDEX[v]
            point = points[_LITERAL_LINES[k]] if lines == "literal" and k in _LITERAL_LINES else F[:3, 3]
            step = rot_about(a, c[i], s[i], point)
        else:
            step = trans_along(a, v)
        M = (step * M).applyfunc(reduce_sc)
        F = (step * F).applyfunc(reduce_sc)
        if k == 1:
            points[2] = F[:3, 3]  # p2 = p0 + l1 z0 (Porter eq. 17)
    return M


def sc_values(q: Sequence[float], l1_: float, l3_: float, l4_: float) -> dict[sp.Symbol, float]:
    """Substitution dict {ci: cos αi, si: sin αi, q2, l1, l3, l4} for a numeric configuration q.

    q = (α1, α2, q2, α3, α4, α5) in radians (the order of the numeric chain).

    >>> d = sc_values([0.0, 0.0, 2.0, 0.0, 0.0, 0.0], 1.0, 0.5, 0.3)
    >>> d[c[1]], d[s[1]], d[q2], d[l3]
    (1.0, 0.0, 2.0, 0.5)
    >>> float(closed_forms()["p5"][0].subs(d))  # q2 + l4 at the zero angles
    2.3
    """
    angles = dict(zip((1, 2, 3, 4, 5), (q[0], q[1], q[3], q[4], q[5]), strict=True))
    d = {c[i]: math.cos(float(t)) for i, t in angles.items()}
    d.update({s[i]: math.sin(float(t)) for i, t in angles.items()})
    d.update({q2: float(q[2]), l1: float(l1_), l3: float(l3_), l4: float(l4_)})
    return d


def to_sc(expr: Any) -> sp.Expr:
    """Rewrite cos(αi), sin(αi) as the symbols ci, si (Porter: "si = sin(αi) and ci = cos(αi)") and expand.

    >>> to_sc(sp.cos(_a1 + _a2))
    c1*c2 - s1*s2
    """
    rep = {}
    for a, i in _ANGLE_INDEX.items():
        rep[sp.cos(a)] = c[i]
        rep[sp.sin(a)] = s[i]
    return sp.expand(sp.expand_trig(sp.sympify(expr)).subs(rep))


def from_sc(expr: Any) -> Any:
    """Replace ci, si by cos(αi), sin(αi) (the inverse of :func:`to_sc`), on expressions or matrices.

    >>> from_sc(c[1] * s[4])
    sin(alpha4)*cos(alpha1)
    """
    if isinstance(expr, sp.MatrixBase):
        return expr.applyfunc(from_sc)
    rep = {}
    for a, i in _ANGLE_INDEX.items():
        rep[c[i]] = sp.cos(a)
        rep[s[i]] = sp.sin(a)
    return sp.sympify(expr).xreplace(rep)


def closed_forms() -> dict[str, list[sp.Expr]]:
    """x5, y5, z5, p5 (the columns of the derived F05) in Porter's ci, si notation, expanded.

    >>> closed_forms()["x5"][2]
    -c2*c4*s3 - c3*c4*s2
    """
    M = local_product()
    return {name: [to_sc(M[i, j]) for i in range(3)] for j, name in enumerate(("x5", "y5", "z5", "p5"))}


def corrected_z5_2() -> sp.Expr:
    """The second component of z5, repaired after the pattern of y5[1]: s1(c2(..) + s2(..)) - c1 c4 s5.

    The printed z_{5,2} starts "-s2(..) + s2(..)" where y_{5,2} has "s1(c2(..) + s2(..))"; this
    is the printed entry with that pattern restored. It agrees with the derived product:

    >>> sp.expand(corrected_z5_2() - closed_forms()["z5"][1])
    0
    """
    c1, c2, c3, c4, c5 = (c[i] for i in range(1, 6))
    s1, s2, s3, s4, s5 = (s[i] for i in range(1, 6))
    return s1 * (c2 * (s3 * c5 + c3 * s4 * s5) + s2 * (c3 * c5 - s3 * s4 * s5)) - c1 * c4 * s5
