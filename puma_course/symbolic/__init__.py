"""sympy: the derivations, the sources' formulas as printed, and the checks between them (lectures 02-09).

One layer, one file per concern:

* :mod:`.notation` - every symbol (θi, the lengths, C1/S23, Porter's ci/si, pose entries);
* :mod:`.elementary` - the one rot/trans API (:func:`rot`, :func:`trans`, :func:`rot_about`, ...);
* :mod:`.dh` - Craig's modified DH: link matrices, tables, chain products, the PUMA-560 and MK3
  closed forms, the C/S short-hand, :func:`fk_from_forms`;
* :mod:`.porter` - Porter's local- and scene-frame products, closed forms, ci/si helpers
  (``from puma_course.symbolic import porter as PS``);
* :mod:`.printed` - the sources' formulas AS PRINTED, misprints kept (data only);
* :mod:`.checks` - :func:`check_printed`: printed versus derived, entry by entry.

Conventions: Craig's modified DH, radians, ``^{i-1}T_i`` maps frame {i} into frame {i-1}.
sympy is imported here only; ``import puma_course`` stays numpy-only.

>>> from puma_course import symbolic as S
>>> S.check_printed(S.printed.MK3_0T5, S.closed_forms_mk3())
PrintedCheck: all 12 entries agree with the derivation
"""

from __future__ import annotations

from . import checks, dh, elementary, notation, porter, printed
from .checks import EntryCheck, PrintedCheck, check_printed, numeric_error
from .dh import (
    chain_sym,
    closed_forms_mk3,
    closed_forms_puma560,
    collect_shorthand,
    derived_link_matrices,
    elementary_product_sym,
    entries,
    expand_shorthand,
    fk_from_forms,
    mdh_sym,
    mk3_table_sym,
    puma560_table_sym,
    table_sym,
    to_shorthand,
)
from .elementary import rot, rot_about, skew, trans, trans_along
from .notation import ENTRY_LATEX, ENTRY_NAMES, MK3_LENGTHS, PUMA560_LENGTHS, shorthand, theta_symbols

__all__ = [
    # sub-modules
    "checks",
    "dh",
    "elementary",
    "notation",
    "porter",
    "printed",
    # notation
    "theta_symbols",
    "shorthand",
    "PUMA560_LENGTHS",
    "MK3_LENGTHS",
    "ENTRY_NAMES",
    "ENTRY_LATEX",
    # elementary motions
    "rot",
    "trans",
    "skew",
    "rot_about",
    "trans_along",
    # modified DH
    "mdh_sym",
    "elementary_product_sym",
    "table_sym",
    "puma560_table_sym",
    "mk3_table_sym",
    "chain_sym",
    "derived_link_matrices",
    "entries",
    "closed_forms_puma560",
    "closed_forms_mk3",
    "to_shorthand",
    "expand_shorthand",
    "collect_shorthand",
    "fk_from_forms",
    # printed versus derived
    "EntryCheck",
    "PrintedCheck",
    "check_printed",
    "numeric_error",
]
