"""The symbols of the symbolic layer, in one place: the derivations and the printed formulas share them.

sympy compares symbols by name *and* assumptions: ``Symbol("d5")`` and ``Symbol("d5", real=True)``
are different symbols, and a printed formula written with one would never cancel against a
derivation written with the other. So every symbol the layer uses is made here, once.

* Craig / Meghdari (lectures 02-04, 09): joint angles ``theta1, theta2, ...`` (real), the lengths
  of the PUMA-560 (a2, a3, d3, d4) and of the MK3 (d1, a1, a2, a3, d5), the slides' short-hand
  C1 = cos θ1, S23 = sin(θ2 + θ3), C234, ... (:func:`shorthand`), and the names r11..pz of the
  entries of a transform.
* Porter (lectures 05-07): the configuration (α1, α2, q2, α3, α4, α5), the lengths l1, l3, l4,
  his ci = cos αi, si = sin αi, and the entries x5_1 .. p5_3 of a given pose.

>>> theta_symbols(2), shorthand("C23 S1")
((theta1, theta2), (C23, S1))
>>> PORTER_Q
(alpha1, alpha2, q2, alpha3, alpha4, alpha5)
"""

from __future__ import annotations

import sympy as sp

__all__ = [
    "theta_symbols",
    "shorthand",
    "PUMA560_LENGTHS",
    "MK3_LENGTHS",
    "ENTRY_NAMES",
    "ENTRY_LATEX",
    "ENTRY_INDEX",
    "PORTER_ANGLES",
    "PORTER_Q",
    "PORTER_LENGTHS",
    "PORTER_SYMBOLS",
    "alpha1",
    "alpha2",
    "alpha3",
    "alpha4",
    "alpha5",
    "q2",
    "l1",
    "l3",
    "l4",
    "c",
    "s",
    "pose_symbols",
    "point_symbols",
]


# ---- Craig's modified DH, as in Meghdari's lecture ------------------------------------------
def theta_symbols(n: int) -> tuple[sp.Symbol, ...]:
    """The joint-angle symbols θ1..θn (real), named ``theta1``.. ``thetan``.

    >>> theta_symbols(3)
    (theta1, theta2, theta3)
    """
    return tuple(sp.Symbol(f"theta{i}", real=True) for i in range(1, n + 1))


def shorthand(names: str) -> tuple[sp.Symbol, ...]:
    """The short-hand symbols of Meghdari's slides (C1, S23, C234, ...), real, from space-separated names.

    They stand for cos/sin of a sum of joint angles: C23 = cos(θ2 + θ3) (see
    :func:`puma_course.symbolic.dh.expand_shorthand`).

    >>> shorthand("C1 S234")
    (C1, S234)
    """
    return tuple(sp.Symbol(n, real=True) for n in names.split())


#: The PUMA-560's lengths (Meghdari's table: a2, a3, d3, d4), real symbols.
PUMA560_LENGTHS: tuple[sp.Symbol, ...] = tuple(sp.symbols("a2 a3 d3 d4", real=True))
#: The MK3's lengths (Meghdari's table: d1, a1, a2, a3, d5), real symbols.
MK3_LENGTHS: tuple[sp.Symbol, ...] = tuple(sp.symbols("d1 a1 a2 a3 d5", real=True))

#: The twelve informative entries of a transform, row by row (Meghdari's r11 .. p_z).
ENTRY_NAMES = ("r11", "r12", "r13", "px", "r21", "r22", "r23", "py", "r31", "r32", "r33", "pz")
#: Where each entry sits in the 4x4 matrix: "px" -> (0, 3).
ENTRY_INDEX = {name: divmod(k, 4) for k, name in enumerate(ENTRY_NAMES)}
#: LaTeX names of the entries for display: "r11" -> "r_{11}", "px" -> "p_x".
ENTRY_LATEX = {name: (f"r_{{{name[1:]}}}" if name[0] == "r" else f"p_{name[1]}") for name in ENTRY_NAMES}


# ---- Porter's chain --------------------------------------------------------------------------
alpha1, alpha2, q2, alpha3, alpha4, alpha5 = sp.symbols("alpha1 alpha2 q2 alpha3 alpha4 alpha5", real=True)
l1, l3, l4 = sp.symbols("l1 l3 l4", positive=True)
#: Porter's five joint angles α1..α5 (real).
PORTER_ANGLES: tuple[sp.Symbol, ...] = (alpha1, alpha2, alpha3, alpha4, alpha5)
#: Porter's configuration in chain order (α1, α2, q2, α3, α4, α5), the order of the numeric ``q``.
PORTER_Q: tuple[sp.Symbol, ...] = (alpha1, alpha2, q2, alpha3, alpha4, alpha5)
#: Porter's constant lengths l1, l3, l4 (positive).
PORTER_LENGTHS: tuple[sp.Symbol, ...] = (l1, l3, l4)
#: Every symbol of Porter's chain by name.
PORTER_SYMBOLS: dict[str, sp.Symbol] = {str(x): x for x in (*PORTER_Q, *PORTER_LENGTHS)}
#: Porter's ci = cos(αi) and si = sin(αi) as plain symbols (keys 1..5), so products stay polynomials.
c: dict[int, sp.Symbol] = {i: sp.Symbol(f"c{i}") for i in range(1, 6)}
s: dict[int, sp.Symbol] = {i: sp.Symbol(f"s{i}") for i in range(1, 6)}


def pose_symbols() -> dict[str, sp.Symbol]:
    """Symbols x5_1..p5_3 (Porter's x_{5,1} etc.) for the entries of the given pose F5.

    >>> P = pose_symbols()
    >>> len(P), P["p5_3"]
    (12, p5_3)
    """
    return {f"{v}5_{i}": sp.Symbol(f"{v}5_{i}") for v in "xyzp" for i in (1, 2, 3)}


def point_symbols(i: int) -> sp.Matrix:
    """Porter's point p_i as a column of symbols (p{i}_1, p{i}_2, p{i}_3) (Ver.2, eqs. 17-19).

    Made like :func:`pose_symbols` (no assumptions), so ``point_symbols(5)`` is the pose's p5.

    >>> point_symbols(4).T
    Matrix([[p4_1, p4_2, p4_3]])
    >>> list(point_symbols(5)) == [pose_symbols()[f"p5_{k}"] for k in (1, 2, 3)]
    True
    """
    return sp.Matrix([sp.Symbol(f"p{i}_{k}") for k in (1, 2, 3)])
