"""The sources' formulas AS PRINTED, misprints and extraction damage kept: plain, immutable data.

* :mod:`.meghdari` - Meghdari's lecture: the general link matrix, the PUMA-560 and MK3 link
  matrices, the PUMA-560's ^0T6 (eq. 3.14, three entries) and the MK3's ^0T5;
* :mod:`.porter` - Porter's "PUMA": the scene- and local-frame products, the closed forms
  x5, y5, z5, p5, the Ver.1 formulas (eqs. 8-15) and parts of Ver.2 (n024, eq. 18).

Each object carries a comment citing where it is printed. Nothing in this package derives or
checks; it imports only sympy and :mod:`puma_course.symbolic.notation` (tests/symbolic keep it so).

>>> from puma_course.symbolic import printed
>>> printed.MK3_0T5["r33"], printed.porter.CLOSED_FORMS["x5"][2]
(-C234, -c4*(c2*s3 + c3*s2))
"""

from __future__ import annotations

from . import meghdari, porter
from .meghdari import GENERAL_LINK_MATRIX, MK3_0T5, MK3_LINK_MATRICES, PUMA560_0T6, PUMA560_LINK_MATRICES

__all__ = [
    "meghdari",
    "porter",
    "GENERAL_LINK_MATRIX",
    "PUMA560_LINK_MATRICES",
    "PUMA560_0T6",
    "MK3_LINK_MATRICES",
    "MK3_0T5",
]
