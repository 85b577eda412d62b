"""Porter's "PUMA" (direct and inverse problem), its formulas AS PRINTED: data, damage kept.

Source: ``/work/shared/sources/000_2a610ff9ad29216e.txt`` (line numbers below refer to it).
Written in Porter's own notation: ci = cos αi, si = sin αi as the symbols ``c[i]``, ``s[i]``,
the lengths l1, l3, l4, the pose entries x5_1 .. p5_3 (his x_{5,1} ...) and the points
p0 .. p4 (:mod:`puma_course.symbolic.notation`). A product of motions is a tuple of factors
(kind, axis, value), kind "R" (rotation) or "T" (translation), left to right as printed.
Nothing here is derived or checked: see :mod:`puma_course.symbolic.porter` and
:mod:`puma_course.symbolic.checks`.

>>> [f for f in LOCAL_PRODUCT if f[2] == q2]  # the printed local product has no Tx(q2)
[]
>>> CLOSED_FORMS["z5"][1]  # damaged as printed: "-s2(..) + s2(..)"
-c1*c4*s5 + s2*(c3*c5 - s3*s4*s5) - s2*(c3*s4*s5 + c5*s3)
"""

from __future__ import annotations

from collections.abc import Mapping
from types import MappingProxyType
from typing import Any

import sympy as sp

from ..notation import alpha1, alpha2, alpha3, alpha4, alpha5, c, l1, l3, l4, point_symbols, pose_symbols, q2, s

__all__ = ["SCENE_PRODUCT", "LOCAL_PRODUCT", "CLOSED_FORMS", "VER1", "VER2_N024", "VER2_EQ18", "VER2_P3"]

# ---- the direct problem ----------------------------------------------------------------------
#: The scene-frame product F05 as printed (line 20), left to right: (kind, axis, frame index of
#: the axis' subscript, value), e.g. ("R", "x", 4, α5) for R_{x4}(α5). It has T_{x2}(q2).
SCENE_PRODUCT: tuple[tuple[str, str, int, Any], ...] = (
    ("R", "x", 4, alpha5), ("T", "x", 4, l4), ("R", "z", 3, alpha4), ("T", "z", 3, -l3),
    ("R", "y", 2, alpha3), ("T", "x", 2, q2), ("R", "y", 1, alpha2), ("T", "z", 1, l1), ("R", "z", 0, alpha1),
)  # fmt: skip

#: The local-frame product F05 as printed (line 24), left to right: (kind, axis, value). Damage
#: kept: no Tx(q2) between Ry(α2) and Ry(α3) (and the underbraces label both R_y "F22'").
LOCAL_PRODUCT: tuple[tuple[str, str, Any], ...] = (
    ("R", "z", alpha1), ("T", "z", l1), ("R", "y", alpha2), ("R", "y", alpha3),
    ("T", "z", -l3), ("R", "z", alpha4), ("T", "x", l4), ("R", "x", alpha5),
)  # fmt: skip

_c1, _c2, _c3, _c4, _c5 = (c[i] for i in range(1, 6))
_s1, _s2, _s3, _s4, _s5 = (s[i] for i in range(1, 6))
_A = q2 - _s3 * l3 + _c3 * _c4 * l4
_B = _c3 * l3 + _s3 * _c4 * l4

#: x5, y5, z5, p5, the columns of F05, as printed (lines 32-38), each a tuple of 3 components.
#: Damage kept: z5[1] (Porter's z_{5,2}) prints "-s2(s3c5 + c3s4s5) + s2(c3c5 - s3s4s5)) - c1c4s5",
#: a stray parenthesis and "-s2" where the pattern of y5 has "s1(c2(..)".
CLOSED_FORMS: Mapping[str, tuple[sp.Expr, sp.Expr, sp.Expr]] = MappingProxyType(
    {
        "x5": (
            _c1 * _c4 * (_c2 * _c3 - _s2 * _s3) - _s1 * _s4,
            _s1 * _c4 * (_c2 * _c3 - _s2 * _s3) + _c1 * _s4,
            -_c4 * (_s2 * _c3 + _c2 * _s3),
        ),
        "y5": (
            _c1 * (_c2 * (_s3 * _s5 - _c3 * _s4 * _c5) + _s2 * (_c3 * _s5 + _s3 * _s4 * _c5)) - _s1 * _c4 * _c5,
            _s1 * (_c2 * (_s3 * _s5 - _c3 * _s4 * _c5) + _s2 * (_c3 * _s5 + _s3 * _s4 * _c5)) + _c1 * _c4 * _c5,
            -_s2 * (_s3 * _s5 - _c3 * _s4 * _c5) + _c2 * (_c3 * _s5 + _s3 * _s4 * _c5),
        ),
        "z5": (
            _c1 * (_c2 * (_s3 * _c5 + _c3 * _s4 * _s5) + _s2 * (_c3 * _c5 - _s3 * _s4 * _s5)) + _s1 * _c4 * _s5,
            -_s2 * (_s3 * _c5 + _c3 * _s4 * _s5) + _s2 * (_c3 * _c5 - _s3 * _s4 * _s5) - _c1 * _c4 * _s5,  # damaged
            -_s2 * (_s3 * _c5 + _c3 * _s4 * _s5) + _c2 * (_c3 * _c5 - _s3 * _s4 * _s5),
        ),
        "p5": (
            _c1 * (_c2 * _A - _s2 * _B) - _s1 * _s4 * l4,
            _s1 * (_c2 * _A - _s2 * _B) + _c1 * _s4 * l4,
            -_s2 * _A - _c2 * _B + l1,
        ),
    }
)

# ---- the inverse problem, Ver.1 (explicit) ---------------------------------------------------
_P = pose_symbols()
_x51, _x52, _x53 = _P["x5_1"], _P["x5_2"], _P["x5_3"]
_y51, _y52 = _P["y5_1"], _P["y5_2"]
_z51, _z52 = _P["z5_1"], _P["z5_2"]
_p51, _p52, _p53 = _P["p5_1"], _P["p5_2"], _P["p5_3"]

#: Porter's Ver.1 formulas as printed (right-hand sides), in the pose symbols and c1, s1, c2, c4, s4:
#: ``s4_eq8`` and ``s4_eq8_p`` (the two forms of eq. 8, line 57), ``tan_a1_eq9`` (line 66),
#: ``c5_eq11``, ``s5_eq11`` (line 90), ``a5_eq12``, ``a6_eq12`` (the auxiliary labels, line 97),
#: ``tan_a2_eq14`` (line 117), ``q2_eq15`` (line 122).
VER1: Mapping[str, sp.Expr] = MappingProxyType(
    {
        "s4_eq8": _c1 * _x52 - _s1 * _x51,
        "s4_eq8_p": (_c1 * _p52 - _s1 * _p51) / l4,
        "tan_a1_eq9": (_p52 - l4 * _x52) / (_p51 - l4 * _x51),
        "c5_eq11": (_c1 * _y52 - _s1 * _y51) / _c4,
        "s5_eq11": (_s1 * _z51 - _c1 * _z52) / _c4,
        "a5_eq12": (_x51 + _s1 * _s4) / (_c1 * _c4),
        "a6_eq12": -_x53 / _c4,
        "tan_a2_eq14": -(_c1 * _c4 * (_p53 - l4 * _x53 - l1) + l3 * (_x51 + _s1 * _s4))
        / (_c4 * (_p51 - l4 * _x51) - _c1 * l3 * _x53),
        "q2_eq15": (_c4 * (_p51 - l4 * _x51) - _c1 * l3 * _x53) / (_c1 * _c2 * _c4),
    }
)

# ---- the inverse problem, Ver.2 (geometric) --------------------------------------------------
_p0, _p2, _p3, _p4 = (point_symbols(i) for i in (0, 2, 3, 4))
_x5 = sp.Matrix([_x51, _x52, _x53])
_n = sp.Matrix(sp.symbols("n024_1:4"))
_z4 = sp.Matrix(sp.symbols("z4_1:4"))
_m = (_p4 - _p0).cross(_p2 - _p0)

#: The plane's normal n024 as printed (line 149): (p4 - p0) • (p2 - p0) / |(p4 - p0) • (p2 - p0)|,
#: the extracted "•" read as the cross product (a dot product is not a vector). In the points'
#: symbols p0_1 .. p4_3.
VER2_N024 = sp.ImmutableMatrix(_m / sp.sqrt(_m.dot(_m)))

#: Eq. 18 as printed (lines 152-158), each condition as "left - right" (= 0 when it holds), in the
#: points p3, p4, the pose's x5 and the normal's symbols n024_1..3:
#: <p3 - p4; n024> = 0, <p3 - p4; x5> = 0, <p3 - p4; p3 - p4> = l4² (the chain has l3 there).
VER2_EQ18: tuple[sp.Expr, sp.Expr, sp.Expr] = (
    (_p3 - _p4).dot(_n),
    (_p3 - _p4).dot(_x5),
    (_p3 - _p4).dot(_p3 - _p4) - l4**2,
)

#: The two points p3 = p4 ± l3 z4 as printed after eq. 19 (line 171), in the symbols z4_1..3.
VER2_P3 = (sp.ImmutableMatrix(_p4 + l3 * _z4), sp.ImmutableMatrix(_p4 - l3 * _z4))
