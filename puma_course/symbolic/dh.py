"""Craig's modified-DH derivations in sympy: link matrices, tables, chain products, closed forms.

Conventions: the same as the numeric layer (Craig's modified DH, radians,
``^{i-1}T_i`` maps frame {i} into frame {i-1}). Joint angles are the real symbols
``theta1, theta2, ...``; lengths are real symbols named as in the lecture (PUMA-560: a2, a3,
d3, d4; MK3: d1, a1, a2, a3, d5); see :mod:`puma_course.symbolic.notation`. Exact angles
(``-pi/2``) keep every cos/sin exact.

The short-hand of Meghdari's slides (C1 = cos θ1, S23 = sin(θ2 + θ3), C234 = cos(θ2 + θ3 + θ4))
is available both ways: :func:`to_shorthand` for display and :func:`expand_shorthand` to get
back an expression in sin/cos that ``sympy.lambdify`` understands.

Everything here is derived; the formulas as the lecture prints them are in
:mod:`puma_course.symbolic.printed`, and :mod:`puma_course.symbolic.checks` compares the two.
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from functools import cache
from typing import Any

import numpy as np
import sympy as sp

from .._validate import as_array
from .elementary import rot, trans
from .notation import ENTRY_INDEX, ENTRY_NAMES, MK3_LENGTHS, PUMA560_LENGTHS, shorthand, theta_symbols

__all__ = [
    "Row",
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
]

#: One row of a DH table: (α_{i-1}, a_{i-1}, θ_i, d_i), each a sympy expression or a number.
Row = tuple[Any, Any, Any, Any]


def mdh_sym(alpha_prev: Any, a_prev: Any, theta: Any, d: Any) -> sp.Matrix:
    """Craig's link matrix ^{i-1}T_i written out entry by entry (Meghdari, "the T transformation").

    Same layout as the numeric ``mdh``; arguments may be symbols or exact numbers.

    >>> al, a, th, d = sp.symbols("alpha a theta d", real=True)
    >>> mdh_sym(al, a, th, d)[1, :]
    Matrix([[sin(theta)*cos(alpha), cos(alpha)*cos(theta), -sin(alpha), -d*sin(alpha)]])
    """
    al, a, th, dd = map(sp.sympify, (alpha_prev, a_prev, theta, d))
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

    The four elementary motions that carry frame {i-1} onto frame {i} (Meghdari, "the T
    transformation", steps 1-4), each about/along an axis of the frame produced by the previous
    one, so the product reads left to right. A second derivation of :func:`mdh_sym`.

    >>> al, a, th, d = sp.symbols("alpha a theta d", real=True)
    >>> elementary_product_sym(al, a, th, d)[2, 3]
    d*cos(alpha)
    """
    P = rot("x", alpha_prev) * trans("x", a_prev) * rot("z", theta) * trans("z", d)
    return P.applyfunc(sp.expand)


def _exact_angle(x: float) -> sp.Expr:
    """A float angle as an exact multiple of π when it is one (to 1e-12), else a Float."""
    r = sp.nsimplify(x / np.pi, rational=True, tolerance=1e-12)
    if isinstance(r, sp.Rational) and r.q <= 12 and abs(float(r) * np.pi - x) < 1e-12:
        return r * sp.pi
    return sp.Float(x)


def table_sym(chain: Any) -> list[tuple[sp.Expr, sp.Expr, sp.Expr, sp.Expr]]:
    """The rows (α_{i-1}, a_{i-1}, θ_i, d_i) of a numeric chain, with symbolic joint variables.

    ``chain`` is anything with ``links``, each having ``alpha_prev``, ``a_prev``, ``d``,
    ``theta`` (floats) and ``kind`` ("R" or "P"), like a ``DHChain``. Revolute joints get
    θ_i = theta_i (+ the constant offset), prismatic ones d_i = d_i (+ offset); angles that are
    multiples of π/12 become exact, lengths become exact rationals (0.4318 -> 2159/5000).

    >>> from types import SimpleNamespace as Link
    >>> arm = Link(links=[Link(alpha_prev=np.pi / 2, a_prev=135.0, d=0.0, theta=0.0, kind="R"),
    ...                   Link(alpha_prev=0.0, a_prev=0.0, d=0.5, theta=np.pi / 2, kind="P")])
    >>> table_sym(arm)
    [(pi/2, 135, theta1, 0), (0, 0, pi/2, d2 + 1/2)]
    """
    rows = []
    for i, lk in enumerate(chain.links, start=1):
        al = _exact_angle(lk.alpha_prev)
        a = sp.nsimplify(lk.a_prev, rational=True)
        if lk.kind == "R":
            th = sp.Symbol(f"theta{i}", real=True) + _exact_angle(lk.theta)
            d = sp.nsimplify(lk.d, rational=True)
        elif lk.kind == "P":
            th = _exact_angle(lk.theta)
            d = sp.Symbol(f"d{i}", real=True) + sp.nsimplify(lk.d, rational=True)
        else:
            raise ValueError(f"chain.links[{i - 1}].kind: expected 'R' or 'P', got {lk.kind!r}")
        rows.append((al, a, th, d))
    return rows


def puma560_table_sym() -> list[Row]:
    """The PUMA-560 table of the lecture (Meghdari's "Table of Link-Joint Parameters") with symbols.

    θ1..θ6 and the lengths a2, a3, d3, d4; α in exact multiples of π.

    >>> puma560_table_sym()[3]
    (-pi/2, a3, theta4, d4)
    """
    t = theta_symbols(6)
    a2, a3, d3, d4 = PUMA560_LENGTHS
    h = sp.pi / 2
    return [(0, 0, t[0], 0), (-h, 0, t[1], 0), (0, a2, t[2], d3), (-h, a3, t[3], d4), (h, 0, t[4], 0), (-h, 0, t[5], 0)]


def mk3_table_sym() -> list[Row]:
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
    """Symbolic link matrices ^{i-1}T_i and their product ^0T_n = ^0T_1 ^1T_2 ... ^{n-1}T_n.

    Meghdari's forward kinematics, ^0T_n = ^0T_1 ^1T_2 ^2T_3 ... ^{n-1}T_n. ``rows`` is a list
    of (α_{i-1}, a_{i-1}, θ_i, d_i) or a chain with ``links`` (then :func:`table_sym` is applied).
    With ``simplify`` the partial products are tidied after every link, which folds neighbouring
    parallel axes into sum-angle terms (cos(θ2 + θ3), ...) as the lecture's note suggests.

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


def derived_link_matrices(rows: Any) -> dict[str, sp.Matrix]:
    """Link matrices from a table (or a chain) keyed like the lecture prints them: "0T1", "1T2", ...

    >>> derived_link_matrices(mk3_table_sym())["4T5"][:3, 3].T  # from the table: the offset sits in row 2
    Matrix([[0, -d5, 0]])
    """
    mats, _ = chain_sym(rows, simplify=False)
    return {f"{i}T{i + 1}": m.applyfunc(sp.simplify) for i, m in enumerate(mats)}


def entries(T: sp.MatrixBase) -> dict[str, sp.Expr]:
    """The twelve informative entries of a 4x4 transform as a dict r11..r33, px, py, pz.

    >>> entries(trans("x", 5))["px"], entries(sp.eye(4))["r22"]
    (5, 1)
    """
    return {name: T[i, j] for name, (i, j) in ENTRY_INDEX.items()}


@cache
def _closed_forms(robot: str) -> tuple[tuple[str, sp.Expr], ...]:
    rows = puma560_table_sym() if robot == "puma560" else mk3_table_sym()
    _, T = chain_sym(rows)
    return tuple(entries(T).items())


def closed_forms_puma560(shorthand: bool = False) -> dict[str, sp.Expr]:
    """All twelve entries of the PUMA-560's ^0T6 (Meghdari eq. 3.14 prints r11, r21, r31).

    In sin/cos of θ1, θ2 + θ3, θ4, θ5, θ6 (ready for :func:`fk_from_forms`), or with
    ``shorthand=True`` in the slides' C1, S23, ... notation.

    >>> closed_forms_puma560(shorthand=True)["pz"]
    -C23*d4 - S2*a2 - S23*a3
    """
    f = dict(_closed_forms("puma560"))
    return {k: to_shorthand(v) for k, v in f.items()} if shorthand else f


def closed_forms_mk3(shorthand: bool = False) -> dict[str, sp.Expr]:
    """All twelve entries of the MK3's ^0T5 = ^0T1 ^1T2 ^2T3 ^3T4 ^4T5, derived from the lecture's table.

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
    digits = []
    for t in sp.Add.make_args(arg):
        m = _THETA.match(t.name) if isinstance(t, sp.Symbol) else None
        if m is None:
            return None
        digits.append(m.group(1))
    return "".join(sorted(digits))


def to_shorthand(expr: Any) -> Any:
    """Write cos(θ2 + θ3) as C23, sin(θ1) as S1, ... (Meghdari's notation, for display); expressions or matrices.

    >>> t = theta_symbols(3)
    >>> to_shorthand(sp.cos(t[0]) * sp.sin(t[1] + t[2]))
    C1*S23
    """
    if isinstance(expr, sp.MatrixBase):
        return expr.applyfunc(to_shorthand)

    def is_target(e: sp.Expr) -> bool:
        return isinstance(e, (sp.cos, sp.sin)) and _joint_sum_digits(e.args[0]) is not None

    def repl(e: sp.Expr) -> sp.Expr:
        digits = _joint_sum_digits(e.args[0])
        return shorthand(("C" if isinstance(e, sp.cos) else "S") + str(digits))[0]

    return sp.sympify(expr).replace(is_target, repl)


def expand_shorthand(expr: Any) -> Any:
    """Replace C23 by cos(θ2 + θ3), S1 by sin(θ1), ... (Meghdari: S23 = S(θ2 + θ3); inverse of :func:`to_shorthand`).

    >>> expand_shorthand(sp.Symbol("C23", real=True) * sp.Symbol("d4", real=True))
    d4*cos(theta2 + theta3)
    """
    if isinstance(expr, sp.MatrixBase):
        return expr.applyfunc(expand_shorthand)
    expr = sp.sympify(expr)
    subs = {}
    for sym in expr.free_symbols:
        m = _SHORT.match(sym.name)
        if m:
            arg = sum(sp.Symbol(f"theta{k}", real=True) for k in m.group(2))
            subs[sym] = (sp.cos if m.group(1) == "C" else sp.sin)(arg)
    return expr.xreplace(subs)


def collect_shorthand(expr: Any) -> Any:
    """Short-hand form grouped the way the slides write it: by C1/S1 first, then by C23/S23 or C234/S234.

    >>> collect_shorthand(closed_forms_puma560()["px"])
    C1*(C2*a2 + C23*a3 - S23*d4) - S1*d3
    """
    if isinstance(expr, sp.MatrixBase):
        return expr.applyfunc(collect_shorthand)
    e = to_shorthand(expr)
    outer = shorthand("C1 S1")
    inner = shorthand("C234 S234 C23 S23")
    return sp.collect(sp.expand(e), outer, func=lambda x: sp.collect(x, inner))


# ---- numeric evaluation of closed forms ----------------------------------------------------
def fk_from_forms(forms: Mapping[str, Any], q: Any, **lengths: float) -> np.ndarray:
    """Evaluate closed forms r11..pz (Meghdari's ^0T_n entries) at joint values ``q`` (n,) or (N, n).

    The forms may use the short-hand (it is expanded first); ``lengths`` gives a value to every
    other symbol by name. Returns (4, 4) or (N, 4, 4), vectorised with ``sympy.lambdify``.

    >>> f = closed_forms_puma560()
    >>> np.round(fk_from_forms(f, np.zeros(6), a2=0.4318, a3=0.0203, d3=0.15005, d4=0.4318)[:3, 3], 5)
    array([ 0.4521 ,  0.15005, -0.4318 ])
    """
    exprs = [expand_shorthand(forms[k]) for k in ENTRY_NAMES]
    free = set().union(*(e.free_symbols for e in exprs))
    thetas = [sym for sym in free if _THETA.match(sym.name)]
    n = max((int(sym.name[5:]) for sym in thetas), default=0)
    Q = as_array(q, "q", (None,), batch=True)
    if Q.shape[-1] < n:
        raise ValueError(f"q: expected at least {n} joint values (the forms use θ1..θ{n}), got shape {Q.shape}")
    others = sorted((sym for sym in free if not _THETA.match(sym.name)), key=lambda sym: sym.name)
    missing = [sym.name for sym in others if sym.name not in lengths]
    if missing:
        raise ValueError(f"lengths: expected values for {missing} (keyword arguments), got {sorted(lengths)}")
    syms: Sequence[sp.Symbol] = list(theta_symbols(n)) + others
    fn = sp.lambdify(syms, exprs, modules="numpy")
    vals = fn(*[Q[..., i] for i in range(n)], *[float(lengths[sym.name]) for sym in others])
    batch = Q.shape[:-1]
    T = np.zeros(batch + (4, 4))
    for name, v in zip(ENTRY_NAMES, vals, strict=True):
        i, j = ENTRY_INDEX[name]
        T[..., i, j] = np.broadcast_to(np.asarray(v, dtype=float), batch)
    T[..., 3, 3] = 1.0
    return T
