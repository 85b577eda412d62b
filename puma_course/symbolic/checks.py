"""Printed versus derived: compare the sources' formulas with the derivations, entry by entry.

:func:`check_printed` takes the printed formulas (:mod:`puma_course.symbolic.printed`) and the
derived ones (:mod:`puma_course.symbolic.dh`, :mod:`puma_course.symbolic.porter`), in the
source's own notation, and returns a :class:`PrintedCheck`: for every printed entry the
simplified difference (for display) and the largest numeric difference on seeded random
values, which decides. A simplifier that fails to reach 0 cannot raise a false alarm, and a
misprint cannot hide behind one.

>>> from puma_course.symbolic import printed, dh
>>> check_printed(printed.MK3_LINK_MATRICES, dh.derived_link_matrices(dh.mk3_table_sym())).differ
['4T5[2,4]', '4T5[3,4]']
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any

import numpy as np
import sympy as sp

from .dh import expand_shorthand, to_shorthand
from .porter import from_sc, reduce_sc, to_sc

__all__ = ["EntryCheck", "PrintedCheck", "NOTATIONS", "check_printed", "numeric_error"]


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

    @property
    def verdicts(self) -> dict[str, bool]:
        """``{name: agrees}`` for every compared entry, in order."""
        return {e.name: e.agrees for e in self.entries}

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


@dataclass(frozen=True)
class _Notation:
    """How a source writes its formulas: to cos/sin of angle symbols, the difference simplified, and back."""

    expand: Callable[[Any], Any]
    simplify: Callable[[Any], Any]
    display: Callable[[Any], Any]


def _trig_simplify(e: sp.Expr) -> sp.Expr:
    return sp.simplify(sp.trigsimp(sp.expand(e)))


def _porter_simplify(e: sp.Expr) -> sp.Expr:
    return reduce_sc(to_sc(e))


#: The notations :func:`check_printed` reads: Meghdari's short-hand C1, S23 (joint angles
#: theta1, ...) and Porter's ci, si (angles alpha1 .. alpha5, reduced modulo ci² + si² = 1).
NOTATIONS: Mapping[str, _Notation] = MappingProxyType(
    {
        "meghdari": _Notation(expand_shorthand, _trig_simplify, to_shorthand),
        "porter": _Notation(from_sc, _porter_simplify, lambda e: e),
    }
)


def _flatten(obj: Any, prefix: str = "") -> dict[str, sp.Expr]:
    """Name every entry: matrices "[i,j]" (1-based, as in print), sequences "[i]" (0-based), dict keys as prefix."""
    if isinstance(obj, sp.MatrixBase):
        return {f"{prefix}[{i + 1},{j + 1}]": obj[i, j] for i in range(obj.rows) for j in range(obj.cols)}
    if isinstance(obj, Mapping):
        out: dict[str, sp.Expr] = {}
        for k, v in obj.items():
            out.update(_flatten(v, f"{prefix}{k}"))
        return out
    if isinstance(obj, Sequence) and not isinstance(obj, str):
        out = {}
        for i, v in enumerate(obj):
            out.update(_flatten(v, f"{prefix}[{i}]"))
        return out
    return {prefix or "expr": sp.sympify(obj)}


_ANGLE = re.compile(r"^(theta|alpha)\d*$")


def numeric_error(expr: Any, *, seed: int = 0, samples: int = 32) -> float:
    """The largest |expr| at ``samples`` seeded random points: angles in [-π, π], other symbols in [0.5, 2].

    Angles are the symbols named theta, thetaN, alpha, alphaN; every other symbol is a length.
    This is what decides whether a printed entry agrees with its derivation.

    >>> t = sp.Symbol("theta1", real=True)
    >>> numeric_error(sp.sin(t) ** 2 + sp.cos(t) ** 2 - 1) < 1e-12, numeric_error(sp.Symbol("a")) >= 0.5
    (True, True)
    """
    e = sp.sympify(expr)
    syms = sorted(e.free_symbols, key=lambda x: x.name)
    if not syms:
        return abs(complex(e))
    rng = np.random.default_rng(seed)
    vals = [
        rng.uniform(-np.pi, np.pi, samples) if _ANGLE.match(x.name) else rng.uniform(0.5, 2.0, samples) for x in syms
    ]
    f: Callable[..., Any] = sp.lambdify(syms, e, modules="numpy")
    return float(np.max(np.abs(np.broadcast_to(np.asarray(f(*vals), dtype=complex), (samples,)))))


def check_printed(
    printed: Any, derived: Any, *, notation: str = "meghdari", seed: int = 0, samples: int = 32
) -> PrintedCheck:
    """Compare printed formulas with derived ones, entry by entry (the errata of the notebooks).

    ``printed`` and ``derived`` are matching sympy matrices, dicts of expressions, dicts of
    matrices (entries named "4T5[2,4]", 1-based as printed) or dicts of sequences (entries named
    "z5[1]", the Python index). Only the entries present in ``printed`` are checked. Both are in
    the source's ``notation``: "meghdari" (short-hand C1, S23, ...) or "porter" (ci, si). They
    are expanded to cos/sin; the difference printed − derived is evaluated at ``samples`` seeded
    random points (:func:`numeric_error`), which decides, and simplified for display.

    >>> t1, d5 = sp.symbols("theta1 d5", real=True)
    >>> check_printed({"p": d5 * sp.cos(t1)}, {"p": d5 * sp.cos(t1), "q": 0}).ok
    True
    >>> check_printed(sp.Matrix([[0, -d5]]), sp.Matrix([[-d5, 0]])).differ
    ['[1,1]', '[1,2]']
    """
    if notation not in NOTATIONS:
        raise ValueError(f"notation: expected one of {sorted(NOTATIONS)}, got {notation!r}")
    how = NOTATIONS[notation]
    P = _flatten(printed)
    D = _flatten(derived)
    missing = [k for k in P if k not in D]
    if missing:
        raise ValueError(f"derived: expected entries named like the printed ones, missing {missing}")
    out = []
    for k, (name, p) in enumerate(P.items()):
        raw = how.expand(p) - how.expand(D[name])
        err = numeric_error(raw, seed=seed + k, samples=samples)
        out.append(EntryCheck(name, p, how.display(D[name]), how.display(how.simplify(raw)), err))
    return PrintedCheck(tuple(out))
