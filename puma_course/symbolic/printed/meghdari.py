"""Meghdari's lecture "Manipulator kinematics" (Session 11), its formulas AS PRINTED: data, misprints kept.

Source: ``/work/shared/sources/004_6759431b437dacf7.txt`` (line numbers below refer to it).
Transcribed faithfully, in the slides' short-hand (C1 = cos θ1, S23 = sin(θ2 + θ3), C234, ...,
see :func:`puma_course.symbolic.notation.shorthand`), with the lecture's length symbols. Nothing
here is derived or checked; :mod:`puma_course.symbolic.checks` compares these with the
derivations of :mod:`puma_course.symbolic.dh`. The objects are immutable, so a misprint cannot
be "fixed" by accident in a notebook.

>>> MK3_LINK_MATRICES["4T5"][:3, 3].T  # as printed (wrong): the d5 offset sits in row 3
Matrix([[0, 0, -d5]])
>>> sorted(PUMA560_0T6)  # the lecture prints three entries of 0T6, then "..."
['r11', 'r21', 'r31']
"""

from __future__ import annotations

from collections.abc import Mapping
from types import MappingProxyType

import sympy as sp

from ..notation import MK3_LENGTHS, PUMA560_LENGTHS, shorthand

__all__ = ["GENERAL_LINK_MATRIX", "PUMA560_LINK_MATRICES", "PUMA560_0T6", "MK3_LINK_MATRICES", "MK3_0T5"]

_M = sp.ImmutableMatrix

# ---- the general link matrix -----------------------------------------------------------------
# Printed under 'The "T" Transformation' (line 71, repeated with the PUMA matrices at line 170):
# ^{i-1}T_i = Rot(X, α_{i-1}) Trans(X, a_{i-1}) Rot(Z, θ_i) Trans(Z, d_i) written out, here in
# the plain symbols alpha (α_{i-1}), a (a_{i-1}), theta (θ_i), d (d_i).
_al, _a, _th, _d = sp.symbols("alpha a theta d", real=True)
_Ct, _St, _Ca, _Sa = sp.cos(_th), sp.sin(_th), sp.cos(_al), sp.sin(_al)
#: The general link matrix as printed (line 71), symbols alpha, a, theta, d.
GENERAL_LINK_MATRIX = _M(
    [
        [_Ct, -_St, 0, _a],
        [_St * _Ca, _Ct * _Ca, -_Sa, -_Sa * _d],
        [_St * _Sa, _Ct * _Sa, _Ca, _Ca * _d],
        [0, 0, 0, 1],
    ]
)

# ---- PUMA-560 --------------------------------------------------------------------------------
_C1, _C2, _C3, _C4, _C5, _C6, _C23 = shorthand("C1 C2 C3 C4 C5 C6 C23")
_S1, _S2, _S3, _S4, _S5, _S6, _S23 = shorthand("S1 S2 S3 S4 S5 S6 S23")
_a2, _a3, _d3, _d4 = PUMA560_LENGTHS

#: The six PUMA-560 link matrices ^0T1 .. ^5T6 as printed ("Now compute each of the link
#: transformations", lines 158-168; printed with Cθ1 for C1).
PUMA560_LINK_MATRICES: Mapping[str, sp.ImmutableMatrix] = MappingProxyType(
    {
        "0T1": _M([[_C1, -_S1, 0, 0], [_S1, _C1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]),
        "1T2": _M([[_C2, -_S2, 0, 0], [0, 0, 1, 0], [-_S2, -_C2, 0, 0], [0, 0, 0, 1]]),
        "2T3": _M([[_C3, -_S3, 0, _a2], [_S3, _C3, 0, 0], [0, 0, 1, _d3], [0, 0, 0, 1]]),
        "3T4": _M([[_C4, -_S4, 0, _a3], [0, 0, 1, _d4], [-_S4, -_C4, 0, 0], [0, 0, 0, 1]]),
        "4T5": _M([[_C5, -_S5, 0, 0], [0, 0, -1, 0], [_S5, _C5, 0, 0], [0, 0, 0, 1]]),
        "5T6": _M([[_C6, -_S6, 0, 0], [0, 0, 1, 0], [-_S6, -_C6, 0, 0], [0, 0, 0, 1]]),
    }
)

_w = _C4 * _C5 * _C6 - _S4 * _S6
#: r11, r21, r31 of the PUMA-560's ^0T6 as printed (Equation 3.14, lines 180-188; the rest is "...").
PUMA560_0T6: Mapping[str, sp.Expr] = MappingProxyType(
    {
        "r11": _C1 * (_C23 * _w - _S23 * _S5 * _C6) + _S1 * (_S4 * _C5 * _C6 + _C4 * _S6),
        "r21": _S1 * (_C23 * _w - _S23 * _S5 * _C6) - _C1 * (_S4 * _C5 * _C6 + _C4 * _S6),
        "r31": -_S23 * _w - _C23 * _S5 * _C6,
    }
)

# ---- Motoman MK3 -----------------------------------------------------------------------------
_C234, _S234 = shorthand("C234 S234")
_d1, _a1, _a2m, _a3m, _d5 = MK3_LENGTHS

#: The five MK3 link matrices ^0T1 .. ^4T5 as printed (lines 220-228). Misprint kept: the printed
#: ^4T5 has -d5 in row 3 (z), column 4 and 0 in row 2; the table (α4 = 90°, d5) gives
#: -sin(α4) d5 = -d5 in row 2 and cos(α4) d5 = 0 in row 3.
MK3_LINK_MATRICES: Mapping[str, sp.ImmutableMatrix] = MappingProxyType(
    {
        "0T1": _M([[_C1, -_S1, 0, 0], [_S1, _C1, 0, 0], [0, 0, 1, _d1], [0, 0, 0, 1]]),
        "1T2": _M([[_C2, -_S2, 0, _a1], [0, 0, -1, 0], [_S2, _C2, 0, 0], [0, 0, 0, 1]]),
        "2T3": _M([[_C3, -_S3, 0, _a2m], [_S3, _C3, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]),
        "3T4": _M([[_C4, -_S4, 0, _a3m], [_S4, _C4, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]),
        "4T5": _M([[_C5, -_S5, 0, 0], [0, 0, -1, 0], [_S5, _C5, 0, -_d5], [0, 0, 0, 1]]),  # misprint: -d5 in row 3
    }
)

_reach = _a1 + _a2m * _C2 + _a3m * _C23 + _d5 * _S234
#: All twelve entries of the MK3's ^0T5 as printed (line 238); they agree with the table, not
#: with the printed ^4T5.
MK3_0T5: Mapping[str, sp.Expr] = MappingProxyType(
    {
        "r11": _C1 * _C234 * _C5 + _S1 * _S5,
        "r12": -_C1 * _C234 * _S5 + _S1 * _C5,
        "r13": _C1 * _S234,
        "px": _C1 * _reach,
        "r21": _S1 * _C234 * _C5 - _C1 * _S5,
        "r22": -_S1 * _C234 * _S5 - _C1 * _C5,
        "r23": _S1 * _S234,
        "py": _S1 * _reach,
        "r31": _C5 * _S234,
        "r32": -_S5 * _S234,
        "r33": -_C234,
        "pz": _d1 + _a2m * _S2 + _a3m * _S23 - _d5 * _C234,
    }
)
