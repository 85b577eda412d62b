"""Symbolic derivations (sympy) of link matrices and closed forms, and checks of printed formulas.

Conventions: the same as the numeric modules (Craig's modified DH, radians,
``^{i-1}T_i`` maps frame {i} into frame {i-1}). Joint angles are the real
symbols ``theta1, theta2, ...`` (printed θ₁, θ₂, ...); lengths are real symbols
named as in the lecture (PUMA-560: a2, a3, d3, d4; MK3: d1, a1, a2, a3, d5).
Exact angles (``-pi/2``) keep every cos/sin exact.

The short-hand of Meghdari's slides (C1 = cos θ1, S23 = sin(θ2 + θ3),
C234 = cos(θ2 + θ3 + θ4), ...) is available both ways: :func:`to_shorthand`
for display and :func:`expand_shorthand` to get back an expression in sin/cos
that ``sympy.lambdify`` understands.

The *printed* formulas of the lecture are transcribed here faithfully,
misprints included (``printed_*``), so that :func:`check_printed` can show,
entry by entry, which ones disagree with the derivation, symbolically and on
random numbers.

sympy is imported by this module only; ``import puma_course`` stays numpy-only.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from functools import cache
from typing import Any

import numpy as np
import sympy as sp

from ._validate import as_array

__all__ = [
    "theta_symbols",
    "rot_x_sym",
    "rot_z_sym",
    "trans_x_sym",
    "trans_z_sym",
    "mdh_sym",
    "elementary_product_sym",
    "table_sym",
    "puma560_table_sym",
    "mk3_table_sym",
    "chain_sym",
    "entries",
    "closed_forms_puma560",
    "closed_forms_mk3",
    "to_shorthand",
    "expand_shorthand",
    "collect_shorthand",
    "fk_from_forms",
    "printed_general_link_matrix",
    "printed_puma560_link_matrices",
    "printed_puma560_0T6_entries",
    "printed_mk3_link_matrices",
    "printed_mk3_0T5",
    "derived_link_matrices",
    "EntryCheck",
    "PrintedCheck",
    "check_printed",
    "ENTRY_NAMES",
    "ENTRY_LATEX",
]

ENTRY_NAMES = ("r11", "r12", "r13", "px", "r21", "r22", "r23", "py", "r31", "r32", "r33", "pz")
_ENTRY_INDEX = {name: divmod(k, 4) for k, name in enumerate(ENTRY_NAMES)}
#: LaTeX names of the entries for display: "r11" -> "r_{11}", "px" -> "p_x"
ENTRY_LATEX = {name: (f"r_{{{name[1:]}}}" if name[0] == "r" else f"p_{name[1]}") for name in ENTRY_NAMES}

PUMA560_LENGTHS = sp.symbols("a2 a3 d3 d4", real=True)
MK3_LENGTHS = sp.symbols("d1 a1 a2 a3 d5", real=True)


def theta_symbols(n: int) -> tuple[sp.Symbol, ...]:
    """The joint-angle symbols θ1..θn (real), named ``theta1``.. ``thetan``.

    >>> theta_symbols(3)
    (theta1, theta2, theta3)
    """
    return tuple(sp.Symbol(f"theta{i}", real=True) for i in range(1, n + 1))


def _s(x: Any) -> sp.Expr:
    return sp.sympify(x)


def rot_x_sym(angle: Any) -> sp.Matrix:
    """Rot(X, angle) as a symbolic 4x4 transform (active rotation about x).

    >>> rot_x_sym(sp.pi / 2) * sp.Matrix([0, 1, 0, 1])  # y turns onto z
    Matrix([
    [0],
    [0],
    [1],
    [1]])
    """
    c, s = sp.cos(_s(angle)), sp.sin(_s(angle))
    return sp.Matrix([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1]])


def rot_z_sym(angle: Any) -> sp.Matrix:
    """Rot(Z, angle) as a symbolic 4x4 transform (active rotation about z).

    >>> rot_z_sym(sp.pi / 2)[:2, :2]
    Matrix([
    [0, -1],
    [1,  0]])
    """
    c, s = sp.cos(_s(angle)), sp.sin(_s(angle))
    return sp.Matrix([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])


def trans_x_sym(a: Any) -> sp.Matrix:
    """Trans(X, a) as a symbolic 4x4 transform (slide along x by a).

    >>> trans_x_sym(sp.Symbol("a"))[:3, 3].T
    Matrix([[a, 0, 0]])
    """
    T = sp.eye(4)
    T[0, 3] = _s(a)
    return T


def trans_z_sym(d: Any) -> sp.Matrix:
    """Trans(Z, d) as a symbolic 4x4 transform (slide along z by d).

    >>> trans_z_sym(sp.Symbol("d"))[:3, 3].T
    Matrix([[0, 0, d]])
    """
    T = sp.eye(4)
    T[2, 3] = _s(d)
    return T


def mdh_sym(alpha_prev: Any, a_prev: Any, theta: Any, d: Any) -> sp.Matrix:
    """Craig's link matrix ^{i-1}T_i written out entry by entry (Meghdari's general "T" matrix).

    Same layout as :func:`puma_course.dh.mdh`; arguments may be symbols or
    exact numbers.

    >>> al, a, th, d = sp.symbols("alpha a theta d", real=True)
    >>> mdh_sym(al, a, th, d)[1, :]
    Matrix([[sin(theta)*cos(alpha), cos(alpha)*cos(theta), -sin(alpha), -d*sin(alpha)]])
    """
    al, a, th, dd = map(_s, (alpha_prev, a_prev, theta, d))
    ca, sa, ct, st = sp.cos(al), sp.sin(al), sp.cos(th), sp.sin(th)
    return sp.Matrix(
        [
            [ct, -st, 0, a],
            [st * ca, ct * ca, -sa, -sa * dd],
            [st * sa, ct * sa, ca, ca * dd],
            [0, 0, 0, 1],
        ]
    )


def elementary_product_sym(alpha_prev: Any, a_prev: Any, theta: Any, d: Any) -> sp.Matrix:
    """Rot(X, α_{i-1}) Trans(X, a_{i-1}) Rot(Z, θ_i) Trans(Z, d_i), multiplied out (entries expanded).

    The four elementary motions that carry frame {i-1} onto frame {i}, each
    about/along an axis of the frame produced by the previous one (so the
    product reads left to right). Equal to :func:`mdh_sym`.

    >>> al, a, th, d = sp.symbols("alpha a theta d", real=True)
    >>> sp.simplify(elementary_product_sym(al, a, th, d) - mdh_sym(al, a, th, d)) == sp.zeros(4, 4)
    True
    """
    P = rot_x_sym(alpha_prev) * trans_x_sym(a_prev) * rot_z_sym(theta) * trans_z_sym(d)
    return P.applyfunc(sp.expand)


def _exact_angle(x: float) -> sp.Expr:
    """A float angle as an exact multiple of π when it is one (to 1e-12), else a Float."""
    r = sp.nsimplify(x / np.pi, rational=True, tolerance=1e-12)
    if isinstance(r, sp.Rational) and r.q <= 12 and abs(float(r) * np.pi - x) < 1e-12:
        return r * sp.pi
    return sp.Float(x)


def table_sym(chain: Any) -> list[tuple[sp.Expr, sp.Expr, sp.Expr, sp.Expr]]:
    """The rows (α_{i-1}, a_{i-1}, θ_i, d_i) of a numeric ``DHChain`` with symbolic joint variables.

    Revolute joints get θ_i = theta_i (+ the constant offset), prismatic ones
    d_i = d_i (+ offset); angles that are multiples of π/12 become exact,
    lengths become exact rationals (0.4318 -> 2159/5000).

    >>> from puma_course import mk3
    >>> table_sym(mk3())[1]
    (pi/2, 135, theta2, 0)
    """
    rows = []
    for i, lk in enumerate(chain.links, start=1):
        al = _exact_angle(lk.alpha_prev)
        a = sp.nsimplify(lk.a_prev, rational=True)
        if lk.kind == "R":
            th = sp.Symbol(f"theta{i}", real=True) + _exact_angle(lk.theta)
            d = sp.nsimplify(lk.d, rational=True)
        else:
            th = _exact_angle(lk.theta)
            d = sp.Symbol(f"d{i}", real=True) + sp.nsimplify(lk.d, rational=True)
        rows.append((al, a, th, d))
    return rows


def puma560_table_sym() -> list[tuple[sp.Expr, sp.Expr, sp.Expr, sp.Expr]]:
    """The PUMA-560 table of the lecture with symbols: θ1..θ6 and the lengths a2, a3, d3, d4.

    >>> puma560_table_sym()[3]
    (-pi/2, a3, theta4, d4)
    """
    t = theta_symbols(6)
    a2, a3, d3, d4 = PUMA560_LENGTHS
    h = sp.pi / 2
    return [(0, 0, t[0], 0), (-h, 0, t[1], 0), (0, a2, t[2], d3), (-h, a3, t[3], d4), (h, 0, t[4], 0), (-h, 0, t[5], 0)]


def mk3_table_sym() -> list[tuple[sp.Expr, sp.Expr, sp.Expr, sp.Expr]]:
    """The Motoman MK3 table of the lecture with symbols: θ1..θ5 and the lengths d1, a1, a2, a3, d5.

    >>> mk3_table_sym()[4]
    (pi/2, 0, theta5, d5)
    """
    t = theta_symbols(5)
    d1, a1, a2, a3, d5 = MK3_LENGTHS
    h = sp.pi / 2
    return [(0, 0, t[0], d1), (h, a1, t[1], 0), (0, a2, t[2], 0), (0, a3, t[3], 0), (h, 0, t[4], d5)]


def _tidy(e: sp.Expr) -> sp.Expr:
    """Expand, then let trigsimp fold c2 c3 - s2 s3 into cos(θ2 + θ3) and the like."""
    return sp.trigsimp(sp.expand(e))


def chain_sym(rows: Any, simplify: bool = True) -> tuple[list[sp.Matrix], sp.Matrix]:
    """Symbolic link matrices ^{i-1}T_i and their product ^0T_n for a table or a ``DHChain``.

    ``rows`` is a list of (α_{i-1}, a_{i-1}, θ_i, d_i) or a ``DHChain`` (then
    :func:`table_sym` is applied). With ``simplify`` the partial products are
    tidied after every link, which folds neighbouring parallel axes into
    sum-angle terms (cos(θ2 + θ3), ...) as the lecture's note suggests.

    >>> mats, T = chain_sym([(0, 0, sp.Symbol("theta1"), 0), (0, 1, sp.Symbol("theta2"), 0)])
    >>> T[0, 0]
    cos(theta1 + theta2)
    """
    if hasattr(rows, "links"):
        rows = table_sym(rows)
    mats = [mdh_sym(*r) for r in rows]
    T = sp.eye(4)
    for A in mats:
        T = T * A
        if simplify:
            T = T.applyfunc(_tidy)
    return mats, T


def entries(T: sp.Matrix) -> dict[str, sp.Expr]:
    """The twelve informative entries of a 4x4 transform as a dict r11..r33, px, py, pz.

    >>> entries(trans_x_sym(5))["px"], entries(sp.eye(4))["r22"]
    (5, 1)
    """
    return {name: T[i, j] for name, (i, j) in _ENTRY_INDEX.items()}


@cache
def _closed_forms(robot: str) -> tuple[tuple[str, sp.Expr], ...]:
    rows = puma560_table_sym() if robot == "puma560" else mk3_table_sym()
    _, T = chain_sym(rows)
    return tuple(entries(T).items())


def closed_forms_puma560(shorthand: bool = False) -> dict[str, sp.Expr]:
    """All twelve entries of the PUMA-560's ^0T6 (Meghdari eq. 3.14 gives r11, r21, r31).

    In sin/cos of θ1, θ2 + θ3, θ4, θ5, θ6 (ready for :func:`fk_from_forms`),
    or with ``shorthand=True`` in the slides' C1, S23, ... notation.

    >>> closed_forms_puma560(shorthand=True)["pz"]
    -C23*d4 - S2*a2 - S23*a3
    """
    f = dict(_closed_forms("puma560"))
    return {k: to_shorthand(v) for k, v in f.items()} if shorthand else f


def closed_forms_mk3(shorthand: bool = False) -> dict[str, sp.Expr]:
    """All twelve entries of the MK3's ^0T5, derived from the lecture's table.

    >>> closed_forms_mk3(shorthand=True)["r33"]
    -C234
    """
    f = dict(_closed_forms("mk3"))
    return {k: to_shorthand(v) for k, v in f.items()} if shorthand else f


# ---- short-hand C1, S23, C234 ---------------------------------------------------------------
_THETA = re.compile(r"^theta(\d)$")
_SHORT = re.compile(r"^([CS])(\d+)$")


def _joint_sum_digits(arg: sp.Expr) -> str | None:
    """'23' for θ2 + θ3, '1' for θ1; None when the argument is not a plain sum of joint angles."""
    terms = sp.Add.make_args(arg)
    digits = []
    for t in terms:
        m = _THETA.match(t.name) if isinstance(t, sp.Symbol) else None
        if m is None:
            return None
        digits.append(m.group(1))
    return "".join(sorted(digits))


def to_shorthand(expr: Any) -> Any:
    """Write cos(θ2 + θ3) as C23, sin(θ1) as S1, ... (for display); works on expressions and matrices.

    >>> t = theta_symbols(3)
    >>> to_shorthand(sp.cos(t[0]) * sp.sin(t[1] + t[2]))
    C1*S23
    """
    if isinstance(expr, sp.MatrixBase):
        return expr.applyfunc(to_shorthand)

    def is_target(e: sp.Expr) -> bool:
        return isinstance(e, (sp.cos, sp.sin)) and _joint_sum_digits(e.args[0]) is not None

    def repl(e: sp.Expr) -> sp.Expr:
        return sp.Symbol(("C" if isinstance(e, sp.cos) else "S") + _joint_sum_digits(e.args[0]), real=True)

    return sp.sympify(expr).replace(is_target, repl)


def expand_shorthand(expr: Any) -> Any:
    """Replace C23 by cos(θ2 + θ3), S1 by sin(θ1), ... (the inverse of :func:`to_shorthand`).

    >>> expand_shorthand(sp.Symbol("C23", real=True) * sp.Symbol("d4", real=True))
    d4*cos(theta2 + theta3)
    """
    if isinstance(expr, sp.MatrixBase):
        return expr.applyfunc(expand_shorthand)
    expr = sp.sympify(expr)
    subs = {}
    for s in expr.free_symbols:
        m = _SHORT.match(s.name)
        if m:
            arg = sum(sp.Symbol(f"theta{c}", real=True) for c in m.group(2))
            subs[s] = (sp.cos if m.group(1) == "C" else sp.sin)(arg)
    return expr.xreplace(subs)


def collect_shorthand(expr: Any) -> Any:
    """Short-hand form grouped the way the slides write it: by C1/S1 first, then by C23/S23 or C234/S234.

    >>> collect_shorthand(closed_forms_puma560()["px"])
    C1*(C2*a2 + C23*a3 - S23*d4) - S1*d3
    """
    if isinstance(expr, sp.MatrixBase):
        return expr.applyfunc(collect_shorthand)
    e = to_shorthand(expr)
    outer = _sh("C1 S1")
    inner = _sh("C234 S234 C23 S23")
    return sp.collect(sp.expand(e), outer, func=lambda c: sp.collect(c, inner))


def _sh(names: str) -> tuple[sp.Symbol, ...]:
    return tuple(sp.Symbol(n, real=True) for n in names.split())


# ---- numeric evaluation of closed forms ----------------------------------------------------
def fk_from_forms(forms: Mapping[str, Any], q: Any, **lengths: float) -> np.ndarray:
    """Evaluate closed forms r11..pz at joint values ``q`` (n,) or (N, n) and the given lengths.

    The forms may use the short-hand (it is expanded first). Returns (4, 4) or
    (N, 4, 4), vectorised with ``sympy.lambdify``.

    >>> f = closed_forms_puma560()
    >>> np.round(fk_from_forms(f, np.zeros(6), a2=0.4318, a3=0.0203, d3=0.15005, d4=0.4318)[:3, 3], 5)
    array([ 0.4521 ,  0.15005, -0.4318 ])
    """
    exprs = [expand_shorthand(forms[k]) for k in ENTRY_NAMES]
    free = set().union(*(e.free_symbols for e in exprs))
    thetas = sorted((s for s in free if _THETA.match(s.name)), key=lambda s: int(s.name[5:]))
    n = max((int(s.name[5:]) for s in thetas), default=0)
    Q = as_array(q, "q", (None,), batch=True)
    if Q.shape[-1] < n:
        raise ValueError(f"q: expected at least {n} joint values (the forms use θ1..θ{n}), got shape {Q.shape}")
    others = sorted((s for s in free if not _THETA.match(s.name)), key=lambda s: s.name)
    missing = [s.name for s in others if s.name not in lengths]
    if missing:
        raise ValueError(f"lengths: expected values for {missing} (keyword arguments), got {sorted(lengths)}")
    syms = list(theta_symbols(n)) + others
    fn = sp.lambdify(syms, exprs, modules="numpy")
    vals = fn(*[Q[..., i] for i in range(n)], *[float(lengths[s.name]) for s in others])
    batch = Q.shape[:-1]
    T = np.zeros(batch + (4, 4))
    for name, v in zip(ENTRY_NAMES, vals, strict=True):
        i, j = _ENTRY_INDEX[name]
        T[..., i, j] = np.broadcast_to(np.asarray(v, dtype=float), batch)
    T[..., 3, 3] = 1.0
    return T


# ---- the lecture's printed formulas (transcribed as printed, misprints included) -----------
def printed_general_link_matrix() -> sp.Matrix:
    """The general link matrix as printed (Meghdari, "the T transformation"), symbols alpha, a, theta, d.

    >>> printed_general_link_matrix()[2, 3]
    d*cos(alpha)
    """
    al, a, th, d = sp.symbols("alpha a theta d", real=True)
    Ct, St, Ca, Sa = sp.cos(th), sp.sin(th), sp.cos(al), sp.sin(al)
    return sp.Matrix([[Ct, -St, 0, a], [St * Ca, Ct * Ca, -Sa, -Sa * d], [St * Sa, Ct * Sa, Ca, Ca * d], [0, 0, 0, 1]])


def printed_puma560_link_matrices() -> dict[str, sp.Matrix]:
    """The six PUMA-560 link matrices ^0T1 .. ^5T6 exactly as printed (short-hand C1 = cos θ1, ...).

    >>> printed_puma560_link_matrices()["3T4"][1, :]
    Matrix([[0, 0, 1, d4]])
    """
    C1, C2, C3, C4, C5, C6 = _sh("C1 C2 C3 C4 C5 C6")
    S1, S2, S3, S4, S5, S6 = _sh("S1 S2 S3 S4 S5 S6")
    a2, a3, d3, d4 = PUMA560_LENGTHS
    M = sp.Matrix
    return {
        "0T1": M([[C1, -S1, 0, 0], [S1, C1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]),
        "1T2": M([[C2, -S2, 0, 0], [0, 0, 1, 0], [-S2, -C2, 0, 0], [0, 0, 0, 1]]),
        "2T3": M([[C3, -S3, 0, a2], [S3, C3, 0, 0], [0, 0, 1, d3], [0, 0, 0, 1]]),
        "3T4": M([[C4, -S4, 0, a3], [0, 0, 1, d4], [-S4, -C4, 0, 0], [0, 0, 0, 1]]),
        "4T5": M([[C5, -S5, 0, 0], [0, 0, -1, 0], [S5, C5, 0, 0], [0, 0, 0, 1]]),
        "5T6": M([[C6, -S6, 0, 0], [0, 0, 1, 0], [-S6, -C6, 0, 0], [0, 0, 0, 1]]),
    }


def printed_puma560_0T6_entries() -> dict[str, sp.Expr]:
    """r11, r21, r31 of the PUMA-560's ^0T6 as printed (Meghdari eq. 3.14), in the short-hand.

    >>> printed_puma560_0T6_entries()["r31"]
    -C23*C6*S5 - S23*(C4*C5*C6 - S4*S6)
    """
    C1, C4, C5, C6, C23 = _sh("C1 C4 C5 C6 C23")
    S1, S4, S5, S6, S23 = _sh("S1 S4 S5 S6 S23")
    return {
        "r11": C1 * (C23 * (C4 * C5 * C6 - S4 * S6) - S23 * S5 * C6) + S1 * (S4 * C5 * C6 + C4 * S6),
        "r21": S1 * (C23 * (C4 * C5 * C6 - S4 * S6) - S23 * S5 * C6) - C1 * (S4 * C5 * C6 + C4 * S6),
        "r31": -S23 * (C4 * C5 * C6 - S4 * S6) - C23 * S5 * C6,
    }


def printed_mk3_link_matrices() -> dict[str, sp.Matrix]:
    """The five MK3 link matrices ^0T1 .. ^4T5 exactly as printed.

    Misprint kept on purpose: the printed ^4T5 has -d5 in row 3 (z), column 4
    and 0 in row 2; the table (α4 = 90°, d5) gives -sin(α4) d5 = -d5 in row 2
    and cos(α4) d5 = 0 in row 3.

    >>> printed_mk3_link_matrices()["4T5"][:3, 3].T  # as printed (wrong): the offset sits in row 3
    Matrix([[0, 0, -d5]])
    """
    C1, C2, C3, C4, C5 = _sh("C1 C2 C3 C4 C5")
    S1, S2, S3, S4, S5 = _sh("S1 S2 S3 S4 S5")
    d1, a1, a2, a3, d5 = MK3_LENGTHS
    M = sp.Matrix
    return {
        "0T1": M([[C1, -S1, 0, 0], [S1, C1, 0, 0], [0, 0, 1, d1], [0, 0, 0, 1]]),
        "1T2": M([[C2, -S2, 0, a1], [0, 0, -1, 0], [S2, C2, 0, 0], [0, 0, 0, 1]]),
        "2T3": M([[C3, -S3, 0, a2], [S3, C3, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]),
        "3T4": M([[C4, -S4, 0, a3], [S4, C4, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]),
        "4T5": M([[C5, -S5, 0, 0], [0, 0, -1, 0], [S5, C5, 0, -d5], [0, 0, 0, 1]]),
    }


def printed_mk3_0T5() -> dict[str, sp.Expr]:
    """All twelve entries of the MK3's ^0T5 as printed, in the short-hand (they agree with the table).

    >>> printed_mk3_0T5()["pz"]
    -C234*d5 + S2*a2 + S23*a3 + d1
    """
    C1, C2, C5, C23, C234 = _sh("C1 C2 C5 C23 C234")
    S1, S2, S5, S23, S234 = _sh("S1 S2 S5 S23 S234")
    d1, a1, a2, a3, d5 = MK3_LENGTHS
    reach = a1 + a2 * C2 + a3 * C23 + d5 * S234
    return {
        "r11": C1 * C234 * C5 + S1 * S5,
        "r12": -C1 * C234 * S5 + S1 * C5,
        "r13": C1 * S234,
        "px": C1 * reach,
        "r21": S1 * C234 * C5 - C1 * S5,
        "r22": -S1 * C234 * S5 - C1 * C5,
        "r23": S1 * S234,
        "py": S1 * reach,
        "r31": C5 * S234,
        "r32": -S5 * S234,
        "r33": -C234,
        "pz": d1 + a2 * S2 + a3 * S23 - d5 * C234,
    }


def derived_link_matrices(rows: Any) -> dict[str, sp.Matrix]:
    """Link matrices from a table (or ``DHChain``) keyed like the printed ones: "0T1", "1T2", ...

    >>> derived_link_matrices(mk3_table_sym())["4T5"][:3, 3].T  # from the table: the offset sits in row 2
    Matrix([[0, -d5, 0]])
    """
    mats, _ = chain_sym(rows, simplify=False)
    return {f"{i}T{i + 1}": m.applyfunc(sp.simplify) for i, m in enumerate(mats)}


# ---- comparing printed with derived ---------------------------------------------------------
@dataclass(frozen=True)
class EntryCheck:
    """One compared entry: printed and derived expressions, their simplified difference, numeric error."""

    name: str
    printed: sp.Expr
    derived: sp.Expr
    difference: sp.Expr
    numeric_error: float

    @property
    def agrees(self) -> bool:
        """True when printed and derived are equal (decided numerically on random values)."""
        return self.numeric_error <= 1e-9


@dataclass(frozen=True)
class PrintedCheck:
    """The result of :func:`check_printed`: every entry compared, and which differ."""

    entries: tuple[EntryCheck, ...]

    @property
    def differ(self) -> list[str]:
        """Names of the entries where the printed form is wrong."""
        return [e.name for e in self.entries if not e.agrees]

    @property
    def ok(self) -> bool:
        """True when every printed entry agrees with the derivation."""
        return not self.differ

    def __repr__(self) -> str:
        if self.ok:
            return f"PrintedCheck: all {len(self.entries)} entries agree with the derivation"
        lines = [f"PrintedCheck: {len(self.differ)} of {len(self.entries)} entries differ"]
        for e in self.entries:
            if not e.agrees:
                lines.append(
                    f"  {e.name}: printed {e.printed}, derived {e.derived}, printed - derived = {e.difference}"
                )
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        rows = "".join(
            f"<tr><td>{e.name}</td><td>{'agrees' if e.agrees else '<b>DIFFERS</b>'}</td>"
            f"<td>${sp.latex(e.printed)}$</td><td>${sp.latex(e.derived)}$</td><td>${sp.latex(e.difference)}$</td></tr>"
            for e in self.entries
            if not e.agrees
        )
        head = (
            f"<p>{len(self.entries) - len(self.differ)} of {len(self.entries)} printed entries agree with the "
            "derivation.</p>"
        )
        if not rows:
            return head
        return (
            head + "<table><thead><tr><th>entry</th><th>verdict</th><th>printed</th><th>derived</th>"
            f"<th>printed − derived</th></tr></thead><tbody>{rows}</tbody></table>"
        )


def _flatten(obj: Any, prefix: str = "") -> dict[str, sp.Expr]:
    if isinstance(obj, sp.MatrixBase):
        return {f"{prefix}[{i + 1},{j + 1}]": obj[i, j] for i in range(obj.rows) for j in range(obj.cols)}
    if isinstance(obj, Mapping):
        out: dict[str, sp.Expr] = {}
        for k, v in obj.items():
            out.update(_flatten(v, f"{prefix}{k}"))
        return out
    return {prefix or "expr": sp.sympify(obj)}


def _numeric_error(diff: sp.Expr, rng: np.random.Generator, samples: int) -> float:
    syms = sorted(diff.free_symbols, key=lambda s: s.name)
    if not syms:
        return abs(float(diff))
    vals = []
    for s in syms:
        if _THETA.match(s.name) or s.name in ("alpha", "theta"):
            vals.append(rng.uniform(-np.pi, np.pi, samples))
        else:
            vals.append(rng.uniform(0.5, 2.0, samples))
    f: Callable[..., Any] = sp.lambdify(syms, diff, modules="numpy")
    return float(np.max(np.abs(np.broadcast_to(np.asarray(f(*vals), dtype=float), (samples,)))))


def check_printed(printed: Any, derived: Any, *, seed: int = 0, samples: int = 32) -> PrintedCheck:
    """Compare printed formulas with derived ones, entry by entry.

    ``printed`` and ``derived`` are matching sympy matrices, dicts of
    expressions, or dicts of matrices (entries are then named "4T5[2,4]").
    Only the entries present in ``printed`` are checked. Both may use the
    short-hand C1, S23, ...; it is expanded first. For every entry the
    difference printed − derived is simplified, and it is evaluated at
    ``samples`` seeded random points (angles in [-π, π], lengths in [0.5, 2]);
    the numeric value decides (a simplifier that fails to reach 0 cannot cause
    a false alarm).

    >>> t1, d5 = sp.symbols("theta1 d5", real=True)
    >>> check_printed({"p": d5 * sp.cos(t1)}, {"p": d5 * sp.cos(t1), "q": 0}).ok
    True
    >>> check_printed(sp.Matrix([[0, -d5]]), sp.Matrix([[-d5, 0]])).differ
    ['[1,1]', '[1,2]']
    """
    P = _flatten(printed)
    D = _flatten(derived)
    missing = [k for k in P if k not in D]
    if missing:
        raise ValueError(f"derived: expected entries named like the printed ones, missing {missing}")
    rng = np.random.default_rng(seed)
    out = []
    for name, p in P.items():
        pe, de = expand_shorthand(p), expand_shorthand(D[name])
        diff = sp.simplify(sp.trigsimp(sp.expand(pe - de)))
        err = _numeric_error(diff, rng, samples)
        out.append(EntryCheck(name, p, to_shorthand(D[name]), to_shorthand(diff), err))
    return PrintedCheck(tuple(out))
